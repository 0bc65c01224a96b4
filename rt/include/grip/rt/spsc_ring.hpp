#pragma once
// A bounded single-producer single-consumer queue: the lock-free hand-off between exactly one
// producing thread and exactly one consuming thread (for example the real-time planning thread
// sending events to a logger).
//
//   SpscRing<T, Capacity>   capacity in the type, storage inline (no heap at all).
//
// Neither side ever blocks, allocates or throws: a full ring refuses (`try_push` returns false),
// an empty ring has nothing to give (`try_pop` returns false). The producer that must not wait
// uses `push_or_count_drop`, which counts what it could not hand over in `dropped()`.
//
// Threading contract (not checked): at any time at most one thread calls the producer side
// (try_push, push_or_count_drop) and at most one thread calls the consumer side (try_pop).
// size_approx(), dropped() and capacity() may be called from any thread.
//
// How: head (next slot to read, written only by the consumer) and tail (next slot to write,
// written only by the producer) are free-running counters on separate cache lines; a slot index
// is `counter & (Capacity - 1)`, hence Capacity must be a power of two (the counters then wrap
// around 2^64 without breaking the index). The producer publishes a slot with a release store of
// tail that the consumer reads with acquire, and hands nothing back until the consumer's release
// store of head says the slot was copied out. Each side caches the other side's counter so that
// the shared cache line is read only when the cached value says full (or empty).
//
// T must be nothrow default constructible (the slots are constructed with the ring), nothrow
// copy assignable (push and pop copy) and nothrow destructible. A ring of large T is large:
// place it in static storage or in an object created at start-up, not on a small thread stack.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace grip::rt {

template <typename T, std::size_t Capacity>
class SpscRing {
  static_assert(Capacity > 0 && (Capacity & (Capacity - 1)) == 0,
                "SpscRing: Capacity must be a power of two");
  static_assert(std::is_nothrow_default_constructible_v<T>,
                "SpscRing: T must be nothrow default constructible");
  static_assert(std::is_nothrow_copy_assignable_v<T>,
                "SpscRing: T must be nothrow copy assignable");
  static_assert(std::is_nothrow_destructible_v<T>, "SpscRing: T must be nothrow destructible");
  static_assert(std::atomic<std::size_t>::is_always_lock_free,
                "SpscRing: needs lock-free atomic counters");
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free,
                "SpscRing: needs a lock-free atomic drop counter");

 public:
  using value_type = T;

  SpscRing() noexcept = default;
  // Shared between two threads by address: neither copyable nor movable.
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;
  SpscRing(SpscRing&&) = delete;
  SpscRing& operator=(SpscRing&&) = delete;
  ~SpscRing() = default;

  // The number of elements the ring holds when full.
  static constexpr std::size_t capacity() noexcept { return Capacity; }

  // Producer side. Appends a copy of `value`. Returns false, and changes nothing, when full.
  [[nodiscard]] bool try_push(const T& value) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);  // only we write it
    if (tail - head_cache_ == Capacity) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail - head_cache_ == Capacity) {
        return false;
      }
    }
    slots_[tail & kMask] = value;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Producer side. As try_push, but a refused value is also counted in dropped(). Returns true
  // iff `value` was enqueued.
  bool push_or_count_drop(const T& value) noexcept {
    if (try_push(value)) {
      return true;
    }
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }

  // Consumer side. Moves the oldest element into `out` (by copy assignment) and frees its slot.
  // Returns false, and leaves `out` untouched, when empty.
  [[nodiscard]] bool try_pop(T& out) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);  // only we write it
    if (head == tail_cache_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head == tail_cache_) {
        return false;
      }
    }
    out = slots_[head & kMask];
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Any thread. The number of elements in the ring at some moment during the call: exact when
  // called by the producer or consumer while the other side is idle, otherwise a snapshot that
  // may already be stale. Always in [0, Capacity].
  [[nodiscard]] std::size_t size_approx() const noexcept {
    // head first: both counters only grow and tail >= head, so a later tail never makes the
    // difference negative; it can exceed Capacity when the consumer popped in between.
    const std::size_t head = head_.load(std::memory_order_acquire);
    const std::size_t tail = tail_.load(std::memory_order_acquire);
    const std::size_t size = tail - head;
    return size < Capacity ? size : Capacity;
  }

  // Any thread. How many values push_or_count_drop refused since construction.
  [[nodiscard]] std::uint64_t dropped() const noexcept {
    return dropped_.load(std::memory_order_relaxed);
  }

 private:
  static constexpr std::size_t kMask = Capacity - 1;
  // A cache line on x86-64 and most ARMv8 cores; a literal, because
  // std::hardware_destructive_interference_size makes GCC warn about ABI stability.
  static constexpr std::size_t kCacheLine = 64;

  // Consumer's line: what it writes (head) and what it caches of the producer (tail).
  alignas(kCacheLine) std::atomic<std::size_t> head_{0};
  std::size_t tail_cache_ = 0;
  // Producer's line: what it writes (tail, dropped) and what it caches of the consumer (head).
  alignas(kCacheLine) std::atomic<std::size_t> tail_{0};
  std::size_t head_cache_ = 0;
  std::atomic<std::uint64_t> dropped_{0};
  alignas(kCacheLine) std::array<T, Capacity> slots_{};
};

}  // namespace grip::rt
