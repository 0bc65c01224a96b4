#include "grip/rt/spsc_ring.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <type_traits>
#include <vector>

#include "grip/platform/alloc_counter.hpp"

namespace grip::rt {
namespace {

// What the planning thread might send to a logger: a plain record.
struct Event {
  std::uint64_t sequence = 0;
  double cycle_time_s = 0.0;
};

using Ring = SpscRing<Event, 8>;

static_assert(Ring::capacity() == 8);
static_assert(!std::is_copy_constructible_v<Ring> && !std::is_move_constructible_v<Ring>);
static_assert(std::is_nothrow_default_constructible_v<Ring>);

class SpscRingTest : public ::testing::Test {
 protected:
  static Event event(std::uint64_t sequence) {
    return Event{sequence, 0.001 * static_cast<double>(sequence)};
  }

  Ring ring_;
};

TEST_F(SpscRingTest, StartsEmpty) {
  EXPECT_EQ(ring_.size_approx(), 0U);
  EXPECT_EQ(ring_.dropped(), 0U);
  Event out;
  EXPECT_FALSE(ring_.try_pop(out));
}

TEST_F(SpscRingTest, PopsInTheOrderPushed) {
  // GIVEN five events pushed in order
  for (std::uint64_t i = 1; i <= 5; ++i) {
    ASSERT_TRUE(ring_.try_push(event(i)));
  }
  EXPECT_EQ(ring_.size_approx(), 5U);

  // WHEN they are popped THEN they come out first in, first out, with their contents
  for (std::uint64_t i = 1; i <= 5; ++i) {
    Event out;
    ASSERT_TRUE(ring_.try_pop(out));
    EXPECT_EQ(out.sequence, i);
    EXPECT_DOUBLE_EQ(out.cycle_time_s, 0.001 * static_cast<double>(i));
  }
  EXPECT_EQ(ring_.size_approx(), 0U);
}

TEST_F(SpscRingTest, FullRingRefusesWithoutChangingAnything) {
  // GIVEN a full ring
  for (std::uint64_t i = 0; i < Ring::capacity(); ++i) {
    ASSERT_TRUE(ring_.try_push(event(i)));
  }
  ASSERT_EQ(ring_.size_approx(), Ring::capacity());

  // WHEN one more is pushed
  const bool pushed = ring_.try_push(event(99));

  // THEN it is refused, the size is unchanged and the oldest element is still first
  EXPECT_FALSE(pushed);
  EXPECT_EQ(ring_.size_approx(), Ring::capacity());
  EXPECT_EQ(ring_.dropped(), 0U) << "try_push refusals are not counted as drops";
  Event out;
  ASSERT_TRUE(ring_.try_pop(out));
  EXPECT_EQ(out.sequence, 0U);
}

TEST_F(SpscRingTest, PoppingFromAFullRingFreesExactlyOneSlot) {
  // GIVEN a full ring
  for (std::uint64_t i = 0; i < Ring::capacity(); ++i) {
    ASSERT_TRUE(ring_.try_push(event(i)));
  }

  // WHEN one element is popped
  Event out;
  ASSERT_TRUE(ring_.try_pop(out));

  // THEN exactly one more push fits, and it comes out last
  EXPECT_TRUE(ring_.try_push(event(100)));
  EXPECT_FALSE(ring_.try_push(event(101)));
  for (std::uint64_t i = 1; i < Ring::capacity(); ++i) {
    ASSERT_TRUE(ring_.try_pop(out));
    EXPECT_EQ(out.sequence, i);
  }
  ASSERT_TRUE(ring_.try_pop(out));
  EXPECT_EQ(out.sequence, 100U);
  EXPECT_FALSE(ring_.try_pop(out));
}

TEST_F(SpscRingTest, PopOnAnEmptyRingLeavesTheOutputUntouched) {
  // GIVEN a ring that was filled and drained
  ASSERT_TRUE(ring_.try_push(event(1)));
  Event out;
  ASSERT_TRUE(ring_.try_pop(out));

  // WHEN popping again
  out = event(42);
  const bool popped = ring_.try_pop(out);

  // THEN nothing comes out and the output keeps its value
  EXPECT_FALSE(popped);
  EXPECT_EQ(out.sequence, 42U);
}

TEST_F(SpscRingTest, WrapsAroundManyTimesKeepingOrder) {
  // GIVEN batches of varying sizes, so that the read and write positions meet every slot
  std::uint64_t next_in = 0;
  std::uint64_t next_out = 0;
  for (std::size_t round = 0; round < 1000; ++round) {
    const std::size_t batch = 1 + round % Ring::capacity();
    // WHEN each batch is pushed and then drained
    for (std::size_t i = 0; i < batch; ++i) {
      ASSERT_TRUE(ring_.try_push(event(next_in++)));
    }
    ASSERT_EQ(ring_.size_approx(), batch);
    Event out;
    while (ring_.try_pop(out)) {
      // THEN every element comes out once, in order
      ASSERT_EQ(out.sequence, next_out++);
    }
  }
  EXPECT_EQ(next_out, next_in);
  EXPECT_GT(next_in, 100 * Ring::capacity());
}

TEST_F(SpscRingTest, PushOrCountDropCountsOnlyRefusals) {
  // GIVEN a ring with one free slot
  for (std::uint64_t i = 0; i + 1 < Ring::capacity(); ++i) {
    ASSERT_TRUE(ring_.try_push(event(i)));
  }

  // WHEN four events are offered with push_or_count_drop
  EXPECT_TRUE(ring_.push_or_count_drop(event(7)));
  EXPECT_FALSE(ring_.push_or_count_drop(event(8)));
  EXPECT_FALSE(ring_.push_or_count_drop(event(9)));
  EXPECT_FALSE(ring_.push_or_count_drop(event(10)));

  // THEN the first is enqueued and the other three are counted as dropped
  EXPECT_EQ(ring_.dropped(), 3U);
  EXPECT_EQ(ring_.size_approx(), Ring::capacity());

  // AND after a pop the next offer succeeds without changing the count
  Event out;
  ASSERT_TRUE(ring_.try_pop(out));
  EXPECT_TRUE(ring_.push_or_count_drop(event(11)));
  EXPECT_EQ(ring_.dropped(), 3U);
}

TEST(SpscRingCapacityOne, HoldsOneElementAtATime) {
  SpscRing<std::uint64_t, 1> ring;
  std::uint64_t out = 0;
  for (std::uint64_t i = 0; i < 10; ++i) {
    ASSERT_TRUE(ring.try_push(i));
    EXPECT_FALSE(ring.try_push(i + 100));
    EXPECT_EQ(ring.size_approx(), 1U);
    ASSERT_TRUE(ring.try_pop(out));
    EXPECT_EQ(out, i);
    EXPECT_FALSE(ring.try_pop(out));
  }
}

TEST(SpscRingConcurrency, DeliversEverySequenceNumberExactlyOnceInOrder) {
  // GIVEN a small ring between a producer and a consumer thread
  constexpr std::uint64_t kCount = 1'000'000;
  auto ring = std::make_unique<SpscRing<std::uint64_t, 64>>();

  // WHEN the producer pushes 0 .. kCount-1, retrying (yielding) whenever the ring is full
  std::thread producer([&ring] {
    for (std::uint64_t i = 0; i < kCount; ++i) {
      while (!ring->try_push(i)) {
        std::this_thread::yield();
      }
    }
  });

  // THEN the consumer receives each number once, in order, with nothing extra
  std::uint64_t expected = 0;
  std::uint64_t out_of_order = 0;
  while (expected < kCount) {
    std::uint64_t value = 0;
    if (!ring->try_pop(value)) {
      std::this_thread::yield();
      continue;
    }
    if (value != expected) {
      ++out_of_order;
    }
    expected = value + 1;
  }
  producer.join();
  EXPECT_EQ(out_of_order, 0U);
  EXPECT_EQ(expected, kCount);
  std::uint64_t extra = 0;
  EXPECT_FALSE(ring->try_pop(extra));
  EXPECT_EQ(ring->dropped(), 0U);
}

TEST(SpscRingConcurrency, ProducerThatNeverWaitsLosesOnlyWhatItCounts) {
  // GIVEN a tiny ring, a producer that never retries and a concurrently draining consumer
  constexpr std::uint64_t kCount = 200'000;
  auto ring = std::make_unique<SpscRing<std::uint64_t, 4>>();
  std::atomic<bool> done{false};

  // WHEN the producer offers kCount values with push_or_count_drop
  std::thread producer([&ring, &done] {
    for (std::uint64_t i = 0; i < kCount; ++i) {
      ring->push_or_count_drop(i);
    }
    done.store(true, std::memory_order_release);
  });
  std::uint64_t received = 0;
  std::uint64_t not_increasing = 0;
  std::uint64_t last = 0;
  for (;;) {
    std::uint64_t value = 0;
    if (ring->try_pop(value)) {
      if (received > 0 && value <= last) {
        ++not_increasing;
      }
      last = value;
      ++received;
    } else if (done.load(std::memory_order_acquire)) {
      // The producer has finished: whatever is still in the ring is visible now.
      while (ring->try_pop(value)) {
        if (received > 0 && value <= last) {
          ++not_increasing;
        }
        last = value;
        ++received;
      }
      break;
    }
  }
  producer.join();

  // THEN every value was either received (in increasing order) or counted as dropped
  EXPECT_EQ(not_increasing, 0U);
  EXPECT_EQ(received + ring->dropped(), kCount);
  EXPECT_GT(received, 0U);
}

// Counting allocations needs the real allocator; sanitizers replace it.
#if GRIP_ALLOC_COUNTER_INTERPOSE
TEST_F(SpscRingTest, PushAndPopNeverTouchTheHeap) {
  ASSERT_TRUE(alloc_counter::interposed())
      << "the allocation counter is not interposed, so this test would prove nothing";

  // GIVEN an armed allocation counter
  alloc_counter::arm();

  // WHEN the ring is filled, overfilled and drained many times
  for (std::uint64_t round = 0; round < 100; ++round) {
    for (std::uint64_t i = 0; i <= Ring::capacity(); ++i) {
      ring_.push_or_count_drop(event(i));
    }
    Event out;
    while (ring_.try_pop(out)) {
    }
  }
  alloc_counter::disarm();

  // THEN nothing was allocated or freed
  EXPECT_EQ(alloc_counter::counts().allocations, 0U);
  EXPECT_EQ(alloc_counter::counts().deallocations, 0U);
  EXPECT_EQ(ring_.dropped(), 100U);
}
#endif

}  // namespace
}  // namespace grip::rt
