#pragma once
// A pool of plain records addressed by 32-bit handles (edge records, trajectory blocks).
//
// All memory is reserved by the constructor; acquire() and release() are O(1), never allocate
// and never throw. As in ETL's `ipool` and iceoryx's mempool, the free list is threaded through
// the unused slots themselves (a slot holds either a T or the index of the next free slot); a
// compact in-use bit array, allocated once too, lets every access check its handle.
//
// Determinism: after construction or clear(), acquire() hands out 0, 1, 2, ... in order; a
// released handle is the next one acquired (LIFO reuse).
//
// Misuse panics through GRIP_ASSERT: releasing a handle twice, releasing or accessing a handle
// that is out of range or not in use.

#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "grip/common/assert.hpp"

namespace grip {

template <typename T>
class ObjectPool {
  static_assert(std::is_trivially_copyable_v<T>, "ObjectPool<T>: T must be trivially copyable");
  static_assert(std::is_trivially_destructible_v<T>,
                "ObjectPool<T>: T must be trivially destructible");

 public:
  using Handle = std::uint32_t;
  static constexpr Handle kInvalid = 0xFFFFFFFF;

  // Reserves `capacity` slots (capacity < kInvalid). Allocates: call at start-up.
  explicit ObjectPool(std::uint32_t capacity)
      : slots_(new Slot[checked_capacity(capacity)]),
        in_use_(new std::uint64_t[words_for(capacity)]),
        capacity_(capacity) {
    clear();
  }

  ObjectPool(const ObjectPool&) = delete;
  ObjectPool& operator=(const ObjectPool&) = delete;

  // The source is left empty with capacity 0.
  ObjectPool(ObjectPool&& other) noexcept
      : slots_(std::move(other.slots_)),
        in_use_(std::move(other.in_use_)),
        capacity_(std::exchange(other.capacity_, 0)),
        used_(std::exchange(other.used_, 0)),
        high_water_mark_(std::exchange(other.high_water_mark_, 0)),
        free_head_(std::exchange(other.free_head_, kInvalid)) {}
  ObjectPool& operator=(ObjectPool&& other) noexcept {
    if (this != &other) {
      slots_ = std::move(other.slots_);
      in_use_ = std::move(other.in_use_);
      capacity_ = std::exchange(other.capacity_, 0);
      used_ = std::exchange(other.used_, 0);
      high_water_mark_ = std::exchange(other.high_water_mark_, 0);
      free_head_ = std::exchange(other.free_head_, kInvalid);
    }
    return *this;
  }

  ~ObjectPool() = default;

  // Takes a free slot and value-initialises it (`T{}`). Returns kInvalid when every slot is in
  // use.
  [[nodiscard]] Handle acquire() noexcept {
    if (free_head_ == kInvalid) {
      return kInvalid;
    }
    const Handle handle = free_head_;
    Slot& slot = slots_[handle];
    free_head_ = slot.next_free;
    ::new (static_cast<void*>(&slot.value)) T{};
    set_in_use(handle, true);
    ++used_;
    if (used_ > high_water_mark_) {
      high_water_mark_ = used_;
    }
    return handle;
  }

  // Returns the slot to the pool; it is the next one acquire() hands out. Panics when the
  // handle is out of range or not in use (double release).
  void release(Handle handle) noexcept {
    GRIP_ASSERT(handle < capacity_);
    GRIP_ASSERT(in_use(handle));
    set_in_use(handle, false);
    slots_[handle].next_free = free_head_;
    free_head_ = handle;
    --used_;
  }

  // Panics when the handle is not in use.
  T& operator[](Handle handle) noexcept {
    GRIP_ASSERT(in_use(handle));
    return slots_[handle].value;
  }
  const T& operator[](Handle handle) const noexcept {
    GRIP_ASSERT(in_use(handle));
    return slots_[handle].value;
  }

  // False for free slots and for handles out of range (including kInvalid).
  bool in_use(Handle handle) const noexcept {
    if (handle >= capacity_) {
      return false;
    }
    return ((in_use_[handle / 64] >> (handle % 64)) & 1U) != 0;
  }

  std::uint32_t used() const noexcept { return used_; }
  std::uint32_t available() const noexcept { return capacity_ - used_; }
  std::uint32_t capacity() const noexcept { return capacity_; }
  bool empty() const noexcept { return used_ == 0; }
  bool full() const noexcept { return used_ == capacity_; }

  // The largest used() since construction; clear() does not reset it.
  std::uint32_t high_water_mark() const noexcept { return high_water_mark_; }

  // Releases every slot and rebuilds the free list in ascending order, so that acquire() hands
  // out 0, 1, 2, ... again. O(capacity).
  void clear() noexcept {
    for (Handle i = 0; i < capacity_; ++i) {
      slots_[i].next_free = (i + 1 < capacity_) ? i + 1 : kInvalid;
    }
    const std::uint32_t words = words_for(capacity_);
    for (std::uint32_t w = 0; w < words; ++w) {
      in_use_[w] = 0;
    }
    free_head_ = capacity_ > 0 ? 0 : kInvalid;
    used_ = 0;
  }

 private:
  // A free slot stores the index of the next free slot; an acquired one stores the T.
  union Slot {
    Slot() noexcept : next_free(kInvalid) {}
    T value;
    Handle next_free;
  };

  static std::uint32_t checked_capacity(std::uint32_t capacity) noexcept {
    GRIP_ASSERT(capacity < kInvalid);  // kInvalid must never be a valid handle
    return capacity;
  }

  static constexpr std::uint32_t words_for(std::uint32_t capacity) noexcept {
    return capacity / 64 + (capacity % 64 != 0 ? 1 : 0);
  }

  void set_in_use(Handle handle, bool value) noexcept {
    const std::uint64_t bit = std::uint64_t{1} << (handle % 64);
    if (value) {
      in_use_[handle / 64] |= bit;
    } else {
      in_use_[handle / 64] &= ~bit;
    }
  }

  std::unique_ptr<Slot[]> slots_;
  std::unique_ptr<std::uint64_t[]> in_use_;
  std::uint32_t capacity_;
  std::uint32_t used_ = 0;
  std::uint32_t high_water_mark_ = 0;
  Handle free_head_ = kInvalid;
};

}  // namespace grip
