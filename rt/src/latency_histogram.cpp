#include "grip/rt/latency_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grip::rt {

double LatencyHistogram::mean() const noexcept {
  if (count_ == 0) {
    return 0.0;
  }
  return static_cast<double>(sum_ns_) / static_cast<double>(count_);
}

std::int64_t LatencyHistogram::percentile(double q) const noexcept {
  if (count_ == 0) {
    return 0;
  }
  if (!(q > 0.0)) {  // also NaN
    q = 0.0;
  } else if (q > 1.0) {
    q = 1.0;
  }
  // The rank in [1, count]; the double may round above count when count exceeds 2^53.
  const double scaled = std::ceil(q * static_cast<double>(count_));
  std::uint64_t rank = count_;
  if (scaled < 1.0) {
    rank = 1;
  } else if (scaled < static_cast<double>(count_)) {
    rank = static_cast<std::uint64_t>(scaled);
  }
  if (rank == 1) {
    return min();
  }
  if (rank == count_) {
    return max();
  }
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < kBucketCount; ++i) {
    seen += buckets_[i];
    if (seen >= rank) {
      return std::min(bucket_upper_bound(i), max());
    }
  }
  return max();  // the rank falls among the overflowing samples
}

std::uint64_t LatencyHistogram::count_above(std::int64_t ns) const noexcept {
  if (count_ == 0 || ns >= max()) {
    return 0;
  }
  if (ns < min()) {  // also every negative ns: samples are recorded as >= 0
    return count_;
  }
  std::uint64_t above = overflow_count_;
  if (ns < kMaxTrackableNs) {
    for (std::size_t i = bucket_index(static_cast<std::uint64_t>(ns)) + 1; i < kBucketCount; ++i) {
      above += buckets_[i];
    }
  }
  return above;
}

void LatencyHistogram::reset() noexcept {
  // Field by field rather than `*this = LatencyHistogram{}`: no 18 KB temporary on the stack.
  buckets_.fill(0);
  count_ = 0;
  negative_count_ = 0;
  overflow_count_ = 0;
  sum_ns_ = 0;
  min_ns_ = std::numeric_limits<std::uint64_t>::max();
  max_ns_ = 0;
}

void LatencyHistogram::merge(const LatencyHistogram& other) noexcept {
  for (std::size_t i = 0; i < kBucketCount; ++i) {
    buckets_[i] += other.buckets_[i];
  }
  count_ += other.count_;
  negative_count_ += other.negative_count_;
  overflow_count_ += other.overflow_count_;
  sum_ns_ += other.sum_ns_;
  min_ns_ = std::min(min_ns_, other.min_ns_);
  max_ns_ = std::max(max_ns_, other.max_ns_);
}

}  // namespace grip::rt
