#include "grip/rt/latency_histogram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "grip/platform/alloc_counter.hpp"

namespace grip::rt {
namespace {

using H = LatencyHistogram;

// The rank percentile() promises: ceil(q * n), at least 1, at most n.
std::size_t rank_of(double q, std::size_t n) {
  const double scaled = std::ceil(q * static_cast<double>(n));
  if (scaled < 1.0) {
    return 1;
  }
  return std::min(n, static_cast<std::size_t>(scaled));
}

// 18 KB each: the fixture keeps them on the heap rather than on the test's stack.
class LatencyHistogramTest : public ::testing::Test {
 protected:
  H& histogram() { return *histogram_; }
  std::unique_ptr<H> histogram_ = std::make_unique<H>();
};

TEST(LatencyHistogramBuckets, CoverEveryValueUpToTheLimitContiguously) {
  // GIVEN the bucket layout
  // THEN the buckets start at 0, follow each other without gap or overlap, end at the limit
  EXPECT_EQ(H::bucket_lower_bound(0), 0);
  for (std::size_t i = 0; i + 1 < H::kBucketCount; ++i) {
    ASSERT_EQ(H::bucket_lower_bound(i + 1), H::bucket_upper_bound(i) + 1) << "bucket " << i;
  }
  EXPECT_EQ(H::bucket_upper_bound(H::kBucketCount - 1), H::kMaxTrackableNs);
  // AND reach at least 100 s
  EXPECT_GE(H::kMaxTrackableNs, std::int64_t{100'000'000'000});
}

TEST(LatencyHistogramBuckets, AreNarrowerThanTheDocumentedRelativeError) {
  for (std::size_t i = 1; i < H::kBucketCount; ++i) {
    const auto lower = static_cast<double>(H::bucket_lower_bound(i));
    const double widest_error = static_cast<double>(H::bucket_upper_bound(i)) - lower;
    ASSERT_LT(widest_error / lower, H::kMaxRelativeError) << "bucket " << i;
  }
}

TEST(LatencyHistogramBuckets, MapEachValueIntoTheBucketThatContainsIt) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> any(0, H::kMaxTrackableNs);
  for (int k = 0; k < 100'000; ++k) {
    const std::int64_t v = k < 1000 ? std::int64_t{k} : any(rng);
    const std::size_t i = H::bucket_index(static_cast<std::uint64_t>(v));
    ASSERT_LT(i, H::kBucketCount);
    ASSERT_LE(H::bucket_lower_bound(i), v);
    ASSERT_GE(H::bucket_upper_bound(i), v);
  }
}

TEST_F(LatencyHistogramTest, EmptyHistogramReportsZeros) {
  EXPECT_EQ(histogram().count(), 0U);
  EXPECT_EQ(histogram().min(), 0);
  EXPECT_EQ(histogram().max(), 0);
  EXPECT_EQ(histogram().mean(), 0.0);
  EXPECT_EQ(histogram().percentile(0.0), 0);
  EXPECT_EQ(histogram().percentile(0.5), 0);
  EXPECT_EQ(histogram().percentile(1.0), 0);
  EXPECT_EQ(histogram().count_above(-1), 0U);
  EXPECT_EQ(histogram().negative_count(), 0U);
  EXPECT_EQ(histogram().overflow_count(), 0U);
}

TEST_F(LatencyHistogramTest, CountMinMaxAndMeanAreExact) {
  // GIVEN samples far from bucket boundaries
  histogram().record(5);
  histogram().record(1'000);
  histogram().record(123'456'789);
  histogram().record(42);

  // THEN the summary statistics are exact
  EXPECT_EQ(histogram().count(), 4U);
  EXPECT_EQ(histogram().min(), 5);
  EXPECT_EQ(histogram().max(), 123'456'789);
  EXPECT_DOUBLE_EQ(histogram().mean(), (5.0 + 1'000.0 + 123'456'789.0 + 42.0) / 4.0);
}

TEST_F(LatencyHistogramTest, PercentilesMatchASortedReferenceWithinTheRelativeError) {
  // GIVEN 100,000 log-uniform samples between 1 ns and 100 s
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> exponent(0.0, 11.0);
  std::vector<std::int64_t> reference;
  reference.reserve(100'000);
  for (int i = 0; i < 100'000; ++i) {
    const auto v = static_cast<std::int64_t>(std::pow(10.0, exponent(rng)));
    reference.push_back(v);
    histogram().record(v);
  }
  std::sort(reference.begin(), reference.end());

  // WHEN asked for every per-mille percentile and the usual tail percentiles
  std::vector<double> qs;
  for (int k = 0; k <= 1000; ++k) {
    qs.push_back(k / 1000.0);
  }
  for (const double q : {0.9999, 0.99999, 0.00001}) {
    qs.push_back(q);
  }

  // THEN each is never below the true sample of that rank and at most kMaxRelativeError above
  for (const double q : qs) {
    const std::int64_t truth = reference[rank_of(q, reference.size()) - 1];
    const std::int64_t reported = histogram().percentile(q);
    ASSERT_GE(reported, truth) << "q = " << q;
    ASSERT_LE(static_cast<double>(reported - truth),
              H::kMaxRelativeError * static_cast<double>(truth))
        << "q = " << q << ", truth = " << truth << ", reported = " << reported;
  }
  // AND the extremes are exact
  EXPECT_EQ(histogram().percentile(1.0), reference.back());
  EXPECT_EQ(histogram().percentile(0.0), reference.front());
  EXPECT_EQ(histogram().max(), reference.back());
  EXPECT_EQ(histogram().min(), reference.front());
}

TEST_F(LatencyHistogramTest, P100IsTheMaximumExactlyEvenInsideAWideBucket) {
  // GIVEN samples whose largest sits inside a bucket 2^23 ns wide
  histogram().record(1'000);
  histogram().record(1'000'000'007);

  // THEN p100 is that sample, not its bucket's upper bound
  EXPECT_EQ(histogram().percentile(1.0), 1'000'000'007);
  EXPECT_EQ(histogram().percentile(0.99), 1'000'000'007);
}

TEST_F(LatencyHistogramTest, QuantilesOutsideTheUnitIntervalAreClamped) {
  for (std::int64_t v = 1; v <= 100; ++v) {
    histogram().record(v);
  }
  EXPECT_EQ(histogram().percentile(-0.5), 1);
  EXPECT_EQ(histogram().percentile(std::nan("")), 1);
  EXPECT_EQ(histogram().percentile(2.0), 100);
  EXPECT_EQ(histogram().percentile(0.5), 50) << "values below 128 ns are exact";
}

TEST_F(LatencyHistogramTest, NegativeSamplesCountAsZeroAndAreCountedSeparately) {
  // GIVEN two negative samples and one positive
  histogram().record(-5);
  histogram().record(-1'000'000);
  histogram().record(30);

  // THEN the negatives are zeros in every statistic and counted apart
  EXPECT_EQ(histogram().count(), 3U);
  EXPECT_EQ(histogram().negative_count(), 2U);
  EXPECT_EQ(histogram().min(), 0);
  EXPECT_EQ(histogram().max(), 30);
  EXPECT_DOUBLE_EQ(histogram().mean(), 10.0);
  EXPECT_EQ(histogram().percentile(0.5), 0);
  EXPECT_EQ(histogram().count_above(0), 1U);
}

TEST_F(LatencyHistogramTest, SamplesBeyondTheLastBucketOverflowButStayExactInTheSummary) {
  // GIVEN one sample beyond the buckets' range
  const std::int64_t huge = H::kMaxTrackableNs + 12'345;
  histogram().record(10);
  histogram().record(huge);

  // THEN it is counted as overflow, and max, p100 and mean are still exact
  EXPECT_EQ(histogram().overflow_count(), 1U);
  EXPECT_EQ(histogram().count(), 2U);
  EXPECT_EQ(histogram().max(), huge);
  EXPECT_EQ(histogram().percentile(1.0), huge);
  EXPECT_DOUBLE_EQ(histogram().mean(), (10.0 + static_cast<double>(huge)) / 2.0);
  EXPECT_EQ(histogram().count_above(1'000), 1U);
}

TEST_F(LatencyHistogramTest, CountAboveIsExactForSmallValuesAndBucketBoundaries) {
  // GIVEN 1 .. 100 ns once each, 1000 samples of 10 ms and 5 of 20 ms
  for (std::int64_t v = 1; v <= 100; ++v) {
    histogram().record(v);
  }
  for (int i = 0; i < 1000; ++i) {
    histogram().record(10'000'000);
  }
  for (int i = 0; i < 5; ++i) {
    histogram().record(20'000'000);
  }

  // THEN counts strictly above are exact in the unit-width range and at the extremes
  EXPECT_EQ(histogram().count_above(-1), 1105U);
  EXPECT_EQ(histogram().count_above(0), 1105U);
  EXPECT_EQ(histogram().count_above(50), 1055U);
  EXPECT_EQ(histogram().count_above(100), 1005U);
  EXPECT_EQ(histogram().count_above(15'000'000), 5U);
  EXPECT_EQ(histogram().count_above(20'000'000), 0U);
  // AND at a bucket's upper bound, everything in that bucket is below
  const std::size_t ten_ms = H::bucket_index(10'000'000);
  EXPECT_EQ(histogram().count_above(H::bucket_upper_bound(ten_ms)), 5U);
  EXPECT_EQ(histogram().count_above(H::bucket_lower_bound(ten_ms) - 1), 1005U);
}

TEST_F(LatencyHistogramTest, MergeEqualsRecordingBothSets) {
  // GIVEN two histograms of different samples, and a third that recorded all of them
  auto other = std::make_unique<H>();
  auto both = std::make_unique<H>();
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> exponent(0.0, 9.0);
  for (int i = 0; i < 5'000; ++i) {
    const auto a = static_cast<std::int64_t>(std::pow(10.0, exponent(rng)));
    const auto b = static_cast<std::int64_t>(std::pow(10.0, exponent(rng) * 0.5)) - 3;
    histogram().record(a);
    other->record(b);
    both->record(a);
    both->record(b);
  }

  // WHEN the second is merged into the first
  histogram().merge(*other);

  // THEN the first reports exactly what the third does
  EXPECT_EQ(histogram().count(), both->count());
  EXPECT_EQ(histogram().negative_count(), both->negative_count());
  EXPECT_GT(histogram().negative_count(), 0U);
  EXPECT_EQ(histogram().min(), both->min());
  EXPECT_EQ(histogram().max(), both->max());
  EXPECT_DOUBLE_EQ(histogram().mean(), both->mean());
  for (int k = 0; k <= 100; ++k) {
    const double q = k / 100.0;
    ASSERT_EQ(histogram().percentile(q), both->percentile(q)) << "q = " << q;
  }
  for (const std::int64_t ns :
       std::array<std::int64_t, 6>{-1, 0, 10, 1'000, 1'000'000, 100'000'000}) {
    EXPECT_EQ(histogram().count_above(ns), both->count_above(ns)) << "ns = " << ns;
  }
}

TEST_F(LatencyHistogramTest, MergingIntoOrFromAnEmptyHistogramKeepsTheSamples) {
  histogram().record(500);
  histogram().record(700);
  auto empty = std::make_unique<H>();

  histogram().merge(*empty);
  EXPECT_EQ(histogram().count(), 2U);
  EXPECT_EQ(histogram().min(), 500);

  empty->merge(histogram());
  EXPECT_EQ(empty->count(), 2U);
  EXPECT_EQ(empty->min(), 500);
  EXPECT_EQ(empty->max(), 700);
  EXPECT_DOUBLE_EQ(empty->mean(), 600.0);
}

TEST_F(LatencyHistogramTest, ResetForgetsEverySample) {
  // GIVEN a histogram with ordinary, negative and overflowing samples
  histogram().record(1'000);
  histogram().record(-3);
  histogram().record(H::kMaxTrackableNs + 1);

  // WHEN it is reset
  histogram().reset();

  // THEN it reports like an empty one
  EXPECT_EQ(histogram().count(), 0U);
  EXPECT_EQ(histogram().negative_count(), 0U);
  EXPECT_EQ(histogram().overflow_count(), 0U);
  EXPECT_EQ(histogram().min(), 0);
  EXPECT_EQ(histogram().max(), 0);
  EXPECT_EQ(histogram().mean(), 0.0);
  EXPECT_EQ(histogram().percentile(0.5), 0);
  EXPECT_EQ(histogram().count_above(-1), 0U);

  // AND records afresh
  histogram().record(77);
  EXPECT_EQ(histogram().min(), 77);
  EXPECT_EQ(histogram().max(), 77);
  EXPECT_EQ(histogram().percentile(0.5), 77);
}

// Counting allocations needs the real allocator; sanitizers replace it.
#if GRIP_ALLOC_COUNTER_INTERPOSE
TEST_F(LatencyHistogramTest, RecordingAndQueryingNeverTouchTheHeap) {
  ASSERT_TRUE(alloc_counter::interposed())
      << "the allocation counter is not interposed, so this test would prove nothing";
  auto other = std::make_unique<H>();

  // GIVEN an armed allocation counter
  alloc_counter::arm();

  // WHEN samples are recorded, queried, merged and reset
  std::int64_t sink = 0;
  for (std::int64_t i = -10; i < 100'000; ++i) {
    histogram().record(i * 1'013);
  }
  sink += histogram().percentile(0.99) + histogram().max();
  sink += static_cast<std::int64_t>(histogram().count_above(1'000'000));
  other->merge(histogram());
  histogram().reset();
  alloc_counter::disarm();

  // THEN nothing was allocated or freed
  EXPECT_EQ(alloc_counter::counts().allocations, 0U);
  EXPECT_EQ(alloc_counter::counts().deallocations, 0U);
  EXPECT_GT(sink, 0);
  EXPECT_EQ(other->count(), 100'010U);
}
#endif

}  // namespace
}  // namespace grip::rt
