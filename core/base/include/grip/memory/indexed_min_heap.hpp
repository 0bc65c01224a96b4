#pragma once
// A binary min-heap of handles keyed by double, with O(log n) decrease-/increase-key and erase:
// the open set of a graph search. Handles are small integers in [0, capacity()), typically pool
// handles (edges) or grid cell indices; each handle is in the heap at most once.
//
// Both arrays (the heap of (key, handle) entries and the position of every handle) are allocated
// by the constructor; nothing allocates or throws afterwards.
//
// Order is fully deterministic: entries compare by (key, handle) lexicographically, so equal
// keys come out smallest handle first. Keys may be +infinity; a NaN key is a contract violation
// (panics), as are handles out of range, pushing a handle twice and touching an absent handle.

#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include "grip/common/assert.hpp"

namespace grip {

class IndexedMinHeap {
 public:
  // Handles in [0, capacity); up to `capacity` entries at once. Allocates: call at start-up.
  explicit IndexedMinHeap(std::uint32_t capacity) : IndexedMinHeap(capacity, capacity) {}

  // Handles in [0, capacity), but at most `max_size` (<= capacity) entries at once: a large
  // handle space (a grid) with a bounded open set. push() refuses once size() == max_size.
  IndexedMinHeap(std::uint32_t capacity, std::uint32_t max_size)
      // Value-initialised so that every page is touched here, at start-up, never in a loop.
      : entries_(new Entry[checked_max_size(capacity, max_size)]()),
        position_(new std::uint32_t[capacity]),
        capacity_(capacity),
        max_size_(max_size) {
    for (std::uint32_t h = 0; h < capacity_; ++h) {
      position_[h] = kAbsent;
    }
  }

  IndexedMinHeap(const IndexedMinHeap&) = delete;
  IndexedMinHeap& operator=(const IndexedMinHeap&) = delete;

  // The source is left empty with capacity 0.
  IndexedMinHeap(IndexedMinHeap&& other) noexcept
      : entries_(std::move(other.entries_)),
        position_(std::move(other.position_)),
        capacity_(std::exchange(other.capacity_, 0)),
        max_size_(std::exchange(other.max_size_, 0)),
        size_(std::exchange(other.size_, 0)) {}
  IndexedMinHeap& operator=(IndexedMinHeap&& other) noexcept {
    if (this != &other) {
      entries_ = std::move(other.entries_);
      position_ = std::move(other.position_);
      capacity_ = std::exchange(other.capacity_, 0);
      max_size_ = std::exchange(other.max_size_, 0);
      size_ = std::exchange(other.size_, 0);
    }
    return *this;
  }

  ~IndexedMinHeap() = default;

  // Inserts `handle` with `key`. Returns false, changing nothing, when size() == max_size().
  // Panics when handle >= capacity(), the handle is already contained, or key is NaN.
  [[nodiscard]] bool push(std::uint32_t handle, double key) noexcept {
    GRIP_ASSERT(handle < capacity_);
    GRIP_ASSERT(position_[handle] == kAbsent);
    GRIP_ASSERT(!std::isnan(key));
    if (size_ == max_size_) {
      return false;
    }
    const std::uint32_t i = size_++;
    place(i, Entry{key, handle});
    sift_up(i);
    return true;
  }

  // Changes the key of a contained handle, up or down. Panics when absent or key is NaN.
  void update(std::uint32_t handle, double key) noexcept {
    GRIP_ASSERT(contains(handle));
    GRIP_ASSERT(!std::isnan(key));
    const std::uint32_t i = position_[handle];
    const double old_key = entries_[i].key;
    entries_[i].key = key;
    if (key < old_key) {
      sift_up(i);
    } else {
      sift_down(i);
    }
  }

  // Removes a contained handle, wherever it is. Panics when absent.
  void erase(std::uint32_t handle) noexcept {
    GRIP_ASSERT(contains(handle));
    const std::uint32_t i = position_[handle];
    position_[handle] = kAbsent;
    const std::uint32_t last = --size_;
    if (i != last) {
      place(i, entries_[last]);  // the last entry fills the hole, then moves up or down
      if (i > 0 && less(entries_[i], entries_[parent(i)])) {
        sift_up(i);
      } else {
        sift_down(i);
      }
    }
  }

  // False for absent handles and for handles out of range.
  bool contains(std::uint32_t handle) const noexcept {
    return handle < capacity_ && position_[handle] != kAbsent;
  }

  // The handle with the smallest (key, handle). Panics when empty.
  std::uint32_t top() const noexcept {
    GRIP_ASSERT(size_ > 0);
    return entries_[0].handle;
  }
  double top_key() const noexcept {
    GRIP_ASSERT(size_ > 0);
    return entries_[0].key;
  }

  // Removes and returns top(). Panics when empty.
  std::uint32_t pop() noexcept {
    const std::uint32_t handle = top();
    erase(handle);
    return handle;
  }

  // The key of a contained handle. Panics when absent.
  double key(std::uint32_t handle) const noexcept {
    GRIP_ASSERT(contains(handle));
    return entries_[position_[handle]].key;
  }

  std::uint32_t size() const noexcept { return size_; }
  bool empty() const noexcept { return size_ == 0; }
  bool full() const noexcept { return size_ == max_size_; }
  // Handles are in [0, capacity()).
  std::uint32_t capacity() const noexcept { return capacity_; }
  // The most entries held at once (== capacity() unless constructed with a smaller bound).
  std::uint32_t max_size() const noexcept { return max_size_; }

  // Removes every entry. O(size()).
  void clear() noexcept {
    for (std::uint32_t i = 0; i < size_; ++i) {
      position_[entries_[i].handle] = kAbsent;
    }
    size_ = 0;
  }

  // Heap order, position consistency and key sanity; O(capacity()). For tests.
  bool check_invariants() const noexcept {
    if (size_ > max_size_ || max_size_ > capacity_) {
      return false;
    }
    for (std::uint32_t i = 0; i < size_; ++i) {
      const Entry& e = entries_[i];
      if (e.handle >= capacity_ || position_[e.handle] != i || std::isnan(e.key)) {
        return false;
      }
      if (i > 0 && less(e, entries_[parent(i)])) {
        return false;
      }
    }
    std::uint32_t contained = 0;
    for (std::uint32_t h = 0; h < capacity_; ++h) {
      if (position_[h] != kAbsent) {
        if (position_[h] >= size_) {
          return false;
        }
        ++contained;
      }
    }
    return contained == size_;
  }

 private:
  struct Entry {
    double key;
    std::uint32_t handle;
  };

  static constexpr std::uint32_t kAbsent = 0xFFFFFFFF;

  static std::uint32_t checked_max_size(std::uint32_t capacity, std::uint32_t max_size) noexcept {
    GRIP_ASSERT(capacity < kAbsent);
    GRIP_ASSERT(max_size <= capacity);
    return max_size;
  }

  static bool less(const Entry& a, const Entry& b) noexcept {
    return a.key < b.key || (a.key == b.key && a.handle < b.handle);
  }
  static std::uint32_t parent(std::uint32_t i) noexcept { return (i - 1) / 2; }

  void place(std::uint32_t i, const Entry& e) noexcept {
    entries_[i] = e;
    position_[e.handle] = i;
  }

  void sift_up(std::uint32_t i) noexcept {
    const Entry moving = entries_[i];
    while (i > 0 && less(moving, entries_[parent(i)])) {
      place(i, entries_[parent(i)]);
      i = parent(i);
    }
    place(i, moving);
  }

  void sift_down(std::uint32_t i) noexcept {
    const Entry moving = entries_[i];
    for (;;) {
      // 64-bit arithmetic: 2 * i + 1 can exceed 32 bits for large heaps.
      const std::uint64_t left = 2 * std::uint64_t{i} + 1;
      if (left >= size_) {
        break;
      }
      auto child = static_cast<std::uint32_t>(left);
      if (child + 1 < size_ && less(entries_[child + 1], entries_[child])) {
        ++child;
      }
      if (!less(entries_[child], moving)) {
        break;
      }
      place(i, entries_[child]);
      i = child;
    }
    place(i, moving);
  }

  std::unique_ptr<Entry[]> entries_;
  std::unique_ptr<std::uint32_t[]> position_;
  std::uint32_t capacity_;
  std::uint32_t max_size_;
  std::uint32_t size_ = 0;
};

}  // namespace grip
