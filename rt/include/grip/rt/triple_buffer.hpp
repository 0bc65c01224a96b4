#pragma once
// Latest-value hand-off between exactly one writer thread and exactly one reader thread: the
// writer publishes whole snapshots (a plan, a statistics block), the reader always takes the
// most recent complete one. Wait-free on both sides: each call is a bounded number of steps, no
// lock, no retry loop, no allocation, no exception. Snapshots published between two takes are
// skipped, never queued; the sequence numbers tell the reader how many.
//
//   TripleBuffer<T>   three T slots inline and one atomic state word.
//
// Writer side (one thread):
//   T& buffer = tb.write_buffer();   // fill it in place (zero copy) ...
//   tb.publish();                    // ... and hand it over; or tb.write(value) to copy.
// Reader side (one thread):
//   if (tb.update()) { use(tb.read_buffer()); }   // zero copy; or tb.read(out) to copy.
//   tb.fresh();                      // would update() take one? (to poll for it)
//
// Threading contract (not checked): the writer-side calls (write_buffer, publish, write,
// published) come from one thread at a time, the reader-side calls (update, read_buffer, read,
// read_sequence, skipped, fresh) from one thread at a time. A reference from write_buffer() is
// valid until the next publish(); one from read_buffer() until the next update() or read().
//
// How: at any moment the writer owns one slot, the reader owns one slot and the third is the
// "middle". The state word holds the middle's index and a fresh bit. publish() swaps the
// writer's slot into the middle with the fresh bit set (release: the snapshot is visible before
// the index); update() swaps the reader's slot into the middle and clears the bit (acquire: it
// sees the snapshot). Each exchange is acquire-release, so a slot given back by one side is
// never written or read by the other while still in use.
//
// T must be nothrow default constructible (the slots are constructed with the buffer); write()
// and read() copy, so they also need T nothrow copy assignable, while the zero-copy calls work
// for a move-only T such as FixedVector<T, N>. Three T live inline: a buffer of a large T
// belongs in static storage or in an object created at start-up, not on a small thread stack.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace grip::rt {

template <typename T>
class TripleBuffer {
  static_assert(std::is_nothrow_default_constructible_v<T>,
                "TripleBuffer: T must be nothrow default constructible");
  static_assert(std::is_nothrow_destructible_v<T>, "TripleBuffer: T must be nothrow destructible");
  static_assert(std::atomic<std::uint32_t>::is_always_lock_free,
                "TripleBuffer: needs a lock-free atomic state word");

 public:
  using value_type = T;

  TripleBuffer() noexcept = default;
  // Shared between two threads by address: neither copyable nor movable.
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;
  TripleBuffer(TripleBuffer&&) = delete;
  TripleBuffer& operator=(TripleBuffer&&) = delete;
  ~TripleBuffer() = default;

  // ---- Writer side ----

  // The slot the writer owns, to fill before publish(). It holds an older snapshot (or T{}), not
  // necessarily the last one published: overwrite everything the reader will look at.
  [[nodiscard]] T& write_buffer() noexcept { return slots_[write_index_].value; }

  // Hands the write buffer to the reader as the newest snapshot, with sequence number
  // published() + 1, and takes another slot as the write buffer. A snapshot published earlier
  // and not yet taken by the reader is discarded.
  void publish() noexcept {
    ++published_;
    slots_[write_index_].sequence = published_;
    const std::uint32_t previous =
        state_.exchange(write_index_ | kFreshBit, std::memory_order_acq_rel);
    write_index_ = previous & kIndexMask;
  }

  // Copies `value` into the write buffer and publishes it.
  void write(const T& value) noexcept requires std::is_nothrow_copy_assignable_v<T> {
    write_buffer() = value;
    publish();
  }

  // How many snapshots this writer has published; the newest has this sequence number.
  [[nodiscard]] std::uint64_t published() const noexcept { return published_; }

  // ---- Reader side ----

  // Takes the newest published snapshot as the read buffer if one arrived since the last take.
  // Returns true iff it did; otherwise the read buffer is unchanged.
  bool update() noexcept {
    if (!fresh()) return false;  // only the reader clears the bit: a fresh one cannot vanish
    const std::uint32_t previous = state_.exchange(read_index_, std::memory_order_acq_rel);
    read_index_ = previous & kIndexMask;
    ++taken_;
    return true;
  }

  // Whether update() would take a snapshot: one was published since the last take. Cheap
  // enough to poll (one relaxed load); a fresh snapshot stays fresh until the reader takes it.
  [[nodiscard]] bool fresh() const noexcept {
    return (state_.load(std::memory_order_relaxed) & kFreshBit) != 0;
  }

  // The snapshot taken by the last successful update(); T{} before the first one.
  [[nodiscard]] const T& read_buffer() const noexcept { return slots_[read_index_].value; }

  // update(), then, iff it took a newer snapshot, copies it into `out` and returns true. Returns
  // false, and leaves `out` untouched, when nothing was published since the last take.
  bool read(T& out) noexcept requires std::is_nothrow_copy_assignable_v<T> {
    if (!update()) {
      return false;
    }
    out = read_buffer();
    return true;
  }

  // The sequence number of read_buffer(): 1 for the first snapshot published, 0 before the
  // first take. The difference between two takes minus one is how many were skipped between them.
  [[nodiscard]] std::uint64_t read_sequence() const noexcept {
    return slots_[read_index_].sequence;
  }

  // How many published snapshots up to read_sequence() the reader never took.
  [[nodiscard]] std::uint64_t skipped() const noexcept { return read_sequence() - taken_; }

 private:
  // A cache line on x86-64 and most ARMv8 cores; a literal, because
  // std::hardware_destructive_interference_size makes GCC warn about ABI stability.
  static constexpr std::size_t kCacheLine = 64;
  static constexpr std::uint32_t kIndexMask = 0x3U;
  static constexpr std::uint32_t kFreshBit = 0x4U;

  // Each slot on its own cache lines, so that writing one never invalidates another.
  struct alignas(kCacheLine) Slot {
    T value{};
    std::uint64_t sequence = 0;  // 0: never published
  };

  // Slot 0 starts as the writer's, 1 as the middle (not fresh), 2 as the reader's.
  alignas(kCacheLine) std::atomic<std::uint32_t> state_{1U};
  alignas(kCacheLine) std::uint32_t write_index_ = 0;  // writer only
  std::uint64_t published_ = 0;                        // writer only
  alignas(kCacheLine) std::uint32_t read_index_ = 2;   // reader only
  std::uint64_t taken_ = 0;                            // reader only: successful updates
  std::array<Slot, 3> slots_{};
};

}  // namespace grip::rt
