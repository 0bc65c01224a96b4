#pragma once
// A fixed-size histogram of durations in nanoseconds, for cycle times, latencies and jitter.
// No allocation ever (the buckets are a std::array inside the object, about 18 KB), nothing
// throws, record() is a few instructions.
//
// Buckets are log-linear, as in HdrHistogram: values below 128 ns have one bucket each (exact);
// above, every power of two [2^e, 2^(e+1)) is split into 64 equal sub-buckets. A bucket's width
// is therefore at most 1/64 of its lower bound, and a value reported from a bucket (its upper
// bound) is within kMaxRelativeError (1/64, about 1.6 %) above the true sample. The buckets
// reach kMaxTrackableNs (2^40 - 1 ns, about 18 minutes); larger samples are counted in
// overflow_count() and take part exactly in count(), min(), max() and mean(); percentile()
// reports them as max() and count_above() counts them as above any ns below max().
//
// count(), min(), max() and mean() are exact (mean from an exact 64-bit sum of the samples,
// which wraps only after 2^64 ns, about 584 years, of accumulated durations).
//
// Threading: plain memory, no atomics. One thread records; other threads must not read the
// object while it records. Hand a copy to readers instead, for example by publishing it through
// a TripleBuffer<LatencyHistogram> (copy assignment is a plain memberwise copy).

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace grip::rt {

class LatencyHistogram {
 public:
  // Sub-buckets per power of two: 2^kSubBucketBits.
  static constexpr int kSubBucketBits = 6;
  // Samples above kMaxTrackableNs = 2^kMaxTrackableBits - 1 land in overflow_count().
  static constexpr int kMaxTrackableBits = 40;
  static constexpr std::int64_t kMaxTrackableNs = (std::int64_t{1} << kMaxTrackableBits) - 1;
  // Upper bound on (reported - true) / true for a percentile below the overflow range.
  static constexpr double kMaxRelativeError = 1.0 / 64.0;
  // 128 exact buckets, then 64 for each further power of two up to kMaxTrackableBits.
  static constexpr std::size_t kBucketCount =
      static_cast<std::size_t>(kMaxTrackableBits - kSubBucketBits + 1) << kSubBucketBits;

  // An empty histogram.
  LatencyHistogram() noexcept = default;

  // Adds one sample. A negative `ns` (a clock that went backwards, a deadline already past) is
  // recorded as 0 and also counted in negative_count().
  void record(std::int64_t ns) noexcept {
    std::uint64_t value = 0;
    if (ns < 0) {
      ++negative_count_;
    } else {
      value = static_cast<std::uint64_t>(ns);
    }
    if (value <= static_cast<std::uint64_t>(kMaxTrackableNs)) {
      ++buckets_[bucket_index(value)];
    } else {
      ++overflow_count_;
    }
    ++count_;
    sum_ns_ += value;
    if (value < min_ns_) {
      min_ns_ = value;
    }
    if (value > max_ns_) {
      max_ns_ = value;
    }
  }

  // Number of samples recorded, negative and overflowing ones included.
  [[nodiscard]] std::uint64_t count() const noexcept { return count_; }
  // Number of samples that were negative (and were recorded as 0).
  [[nodiscard]] std::uint64_t negative_count() const noexcept { return negative_count_; }
  // Number of samples above kMaxTrackableNs.
  [[nodiscard]] std::uint64_t overflow_count() const noexcept { return overflow_count_; }

  // Smallest and largest sample, exact (negative samples count as 0); 0 when empty.
  [[nodiscard]] std::int64_t min() const noexcept {
    return count_ == 0 ? 0 : static_cast<std::int64_t>(min_ns_);
  }
  [[nodiscard]] std::int64_t max() const noexcept { return static_cast<std::int64_t>(max_ns_); }

  // Arithmetic mean of the samples in ns; 0.0 when empty.
  [[nodiscard]] double mean() const noexcept;

  // The sample of rank ceil(q * count()) (at least 1) in ascending order, reported as the upper
  // bound of its bucket clamped to max(): percentile(1.0) == max() and percentile(0.0) == min()
  // exactly; in between the result is at most kMaxRelativeError above the true sample (and never
  // below it). q outside [0, 1] is clamped into it, NaN counts as 0. Returns 0 when empty.
  [[nodiscard]] std::int64_t percentile(double q) const noexcept;

  // Number of samples known to be greater than `ns`: those in buckets whose every value exceeds
  // `ns`. Exact when ns < 128, when ns + 1 is a bucket's lower bound, when ns < min() and when
  // ns >= max(); otherwise it may miss samples of the one bucket holding ns (values within
  // kMaxRelativeError of ns).
  [[nodiscard]] std::uint64_t count_above(std::int64_t ns) const noexcept;

  // Forgets every sample.
  void reset() noexcept;

  // Adds `other`'s samples, as if they had been recorded here too.
  void merge(const LatencyHistogram& other) noexcept;

  // The bucket a value in [0, kMaxTrackableNs] falls in, and a bucket's value range, inclusive.
  // Public so that tests and exporters can reason about the resolution.
  [[nodiscard]] static constexpr std::size_t bucket_index(std::uint64_t ns) noexcept {
    // Below 2^(kSubBucketBits + 1) the shift is 0 and the index is the value. Above, the shift
    // keeps the top kSubBucketBits + 1 bits, whose value is in [64, 128): consecutive powers of
    // two map onto consecutive runs of 64 indices.
    const int width = static_cast<int>(std::bit_width(ns));
    const int shift = width > kSubBucketBits + 1 ? width - (kSubBucketBits + 1) : 0;
    return (static_cast<std::size_t>(shift) << kSubBucketBits) +
           static_cast<std::size_t>(ns >> shift);
  }
  [[nodiscard]] static constexpr std::int64_t bucket_lower_bound(std::size_t index) noexcept {
    const auto [top, shift] = split(index);
    return static_cast<std::int64_t>(top << shift);
  }
  [[nodiscard]] static constexpr std::int64_t bucket_upper_bound(std::size_t index) noexcept {
    const auto [top, shift] = split(index);
    return static_cast<std::int64_t>(((top + 1) << shift) - 1);
  }

 private:
  static constexpr std::size_t kSubBuckets = std::size_t{1} << kSubBucketBits;

  struct Split {
    std::uint64_t top;  // the value's leading bits
    unsigned shift;     // how far they are shifted
  };
  static constexpr Split split(std::size_t index) noexcept {
    if (index < 2 * kSubBuckets) {
      return {index, 0};
    }
    const std::size_t shift = index / kSubBuckets - 1;
    return {index - shift * kSubBuckets, static_cast<unsigned>(shift)};
  }

  std::array<std::uint64_t, kBucketCount> buckets_{};
  std::uint64_t count_ = 0;
  std::uint64_t negative_count_ = 0;
  std::uint64_t overflow_count_ = 0;
  std::uint64_t sum_ns_ = 0;
  std::uint64_t min_ns_ = std::numeric_limits<std::uint64_t>::max();  // that while empty
  std::uint64_t max_ns_ = 0;
};

static_assert(LatencyHistogram::bucket_index(LatencyHistogram::kMaxTrackableNs) + 1 ==
              LatencyHistogram::kBucketCount);
static_assert(LatencyHistogram::bucket_upper_bound(LatencyHistogram::kBucketCount - 1) ==
              LatencyHistogram::kMaxTrackableNs);

}  // namespace grip::rt
