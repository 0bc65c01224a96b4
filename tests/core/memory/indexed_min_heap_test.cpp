#include "grip/memory/indexed_min_heap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <type_traits>
#include <utility>
#include <vector>

#include "grip/common/random.hpp"

namespace grip {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

static_assert(!std::is_copy_constructible_v<IndexedMinHeap>);
static_assert(std::is_nothrow_move_constructible_v<IndexedMinHeap>);

// Drains the heap, checking the invariants after every pop.
std::vector<std::uint32_t> drain(IndexedMinHeap& heap) {
  std::vector<std::uint32_t> order;
  while (!heap.empty()) {
    order.push_back(heap.pop());
    EXPECT_TRUE(heap.check_invariants());
  }
  return order;
}

TEST(IndexedMinHeap, StartsEmpty) {
  IndexedMinHeap heap(8);
  EXPECT_TRUE(heap.empty());
  EXPECT_FALSE(heap.full());
  EXPECT_EQ(heap.size(), 0U);
  EXPECT_EQ(heap.capacity(), 8U);
  EXPECT_EQ(heap.max_size(), 8U);
  EXPECT_FALSE(heap.contains(0));
  EXPECT_FALSE(heap.contains(8));  // out of range is simply not contained
  EXPECT_TRUE(heap.check_invariants());
}

TEST(IndexedMinHeap, TopIsTheSmallestKey) {
  IndexedMinHeap heap(8);
  ASSERT_TRUE(heap.push(3, 5.0));
  ASSERT_TRUE(heap.push(6, 2.0));
  ASSERT_TRUE(heap.push(1, 9.0));
  EXPECT_EQ(heap.top(), 6U);
  EXPECT_DOUBLE_EQ(heap.top_key(), 2.0);
  EXPECT_DOUBLE_EQ(heap.key(3), 5.0);
  EXPECT_TRUE(heap.contains(1));
  EXPECT_EQ(heap.size(), 3U);
}

TEST(IndexedMinHeap, PopsRandomKeysInSortedOrder) {
  // GIVEN 1000 handles with random keys, pushed in a random order
  constexpr std::uint32_t kCount = 1000;
  IndexedMinHeap heap(kCount);
  Random random(7);
  std::vector<std::uint32_t> handles(kCount);
  for (std::uint32_t i = 0; i < kCount; ++i) {
    handles[i] = i;
  }
  for (std::uint32_t i = kCount - 1; i > 0; --i) {
    std::swap(handles[i], handles[random.below(i + 1)]);
  }
  std::vector<std::pair<double, std::uint32_t>> reference;
  for (const std::uint32_t h : handles) {
    const double key = random.uniform(-100.0, 100.0);
    ASSERT_TRUE(heap.push(h, key));
    reference.emplace_back(key, h);
  }
  ASSERT_TRUE(heap.check_invariants());

  // WHEN the heap is drained THEN handles come out in (key, handle) order
  std::sort(reference.begin(), reference.end());
  const std::vector<std::uint32_t> order = drain(heap);
  ASSERT_EQ(order.size(), reference.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_EQ(order[i], reference[i].second) << "at position " << i;
  }
}

TEST(IndexedMinHeap, BreaksTiesBySmallerHandle) {
  IndexedMinHeap heap(16);
  for (const std::uint32_t h : {9U, 5U, 12U, 1U, 3U}) {
    ASSERT_TRUE(heap.push(h, 4.0));
  }
  ASSERT_TRUE(heap.push(7, 4.5));
  ASSERT_TRUE(heap.push(15, 3.5));
  EXPECT_EQ(drain(heap), (std::vector<std::uint32_t>{15, 1, 3, 5, 9, 12, 7}));
}

TEST(IndexedMinHeap, UpdateMovesAHandleUpAndDown) {
  IndexedMinHeap heap(8);
  for (std::uint32_t h = 0; h < 8; ++h) {
    ASSERT_TRUE(heap.push(h, static_cast<double>(h)));
  }
  // WHEN the largest key becomes the smallest THEN it is the top
  heap.update(7, -1.0);
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(heap.top(), 7U);
  EXPECT_DOUBLE_EQ(heap.key(7), -1.0);

  // WHEN the top's key grows past all others THEN it comes out last
  heap.update(7, 100.0);
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(heap.top(), 0U);
  EXPECT_EQ(drain(heap), (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST(IndexedMinHeap, UpdateToTheSameKeyKeepsTheOrder) {
  IndexedMinHeap heap(4);
  ASSERT_TRUE(heap.push(2, 1.0));
  ASSERT_TRUE(heap.push(0, 1.0));
  heap.update(2, 1.0);
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(drain(heap), (std::vector<std::uint32_t>{0, 2}));
}

TEST(IndexedMinHeap, EraseFromTheMiddleKeepsTheRestOrdered) {
  IndexedMinHeap heap(32);
  for (std::uint32_t h = 0; h < 32; ++h) {
    ASSERT_TRUE(heap.push(h, static_cast<double>((h * 7) % 32)));
  }
  for (const std::uint32_t h : {13U, 0U, 31U, 20U}) {
    heap.erase(h);
    EXPECT_FALSE(heap.contains(h));
    EXPECT_TRUE(heap.check_invariants());
  }
  EXPECT_EQ(heap.size(), 28U);
  std::vector<double> keys;
  while (!heap.empty()) {
    keys.push_back(heap.top_key());
    static_cast<void>(heap.pop());
  }
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
}

TEST(IndexedMinHeap, InfiniteKeysComeLastInHandleOrder) {
  IndexedMinHeap heap(8);
  ASSERT_TRUE(heap.push(4, kInf));
  ASSERT_TRUE(heap.push(1, kInf));
  ASSERT_TRUE(heap.push(6, 1e300));
  ASSERT_TRUE(heap.push(2, kInf));
  ASSERT_TRUE(heap.push(0, -kInf));
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(heap.top(), 0U);

  heap.update(2, 3.0);  // from +inf down to a finite key
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(drain(heap), (std::vector<std::uint32_t>{0, 2, 6, 1, 4}));
}

TEST(IndexedMinHeap, HoldsEveryHandleAtOnceAndAcceptsAgainAfterAPop) {
  // GIVEN a heap holding all of its handles
  IndexedMinHeap heap(5);
  for (std::uint32_t h = 0; h < 5; ++h) {
    ASSERT_TRUE(heap.push(h, 10.0 - h));
  }
  EXPECT_TRUE(heap.full());
  EXPECT_EQ(heap.size(), heap.capacity());

  // WHEN one is popped THEN it can be pushed back with another key
  EXPECT_EQ(heap.pop(), 4U);
  EXPECT_FALSE(heap.full());
  EXPECT_TRUE(heap.push(4, 100.0));
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(heap.top(), 3U);
}

TEST(IndexedMinHeap, WithABoundedSizeRefusesPushWhenFull) {
  // GIVEN a large handle space with room for three entries
  IndexedMinHeap heap(1000, 3);
  EXPECT_EQ(heap.capacity(), 1000U);
  EXPECT_EQ(heap.max_size(), 3U);
  ASSERT_TRUE(heap.push(999, 3.0));
  ASSERT_TRUE(heap.push(500, 1.0));
  ASSERT_TRUE(heap.push(0, 2.0));

  // WHEN a fourth is pushed THEN it is refused and the heap is unchanged
  EXPECT_FALSE(heap.push(7, 0.0));
  EXPECT_FALSE(heap.contains(7));
  EXPECT_EQ(heap.size(), 3U);
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_EQ(heap.top(), 500U);

  // WHEN one leaves THEN the push succeeds
  heap.erase(0);
  EXPECT_TRUE(heap.push(7, 0.0));
  EXPECT_EQ(heap.top(), 7U);
}

TEST(IndexedMinHeap, ClearEmptiesTheHeapAndForgetsEveryHandle) {
  IndexedMinHeap heap(10);
  for (std::uint32_t h = 0; h < 10; h += 2) {
    ASSERT_TRUE(heap.push(h, 1.0));
  }
  heap.clear();
  EXPECT_TRUE(heap.empty());
  for (std::uint32_t h = 0; h < 10; ++h) {
    EXPECT_FALSE(heap.contains(h));
  }
  EXPECT_TRUE(heap.check_invariants());
  EXPECT_TRUE(heap.push(4, 2.0));  // a handle that was in before can be pushed again
}

TEST(IndexedMinHeap, MoveTransfersTheEntries) {
  IndexedMinHeap a(4);
  ASSERT_TRUE(a.push(2, 1.0));
  IndexedMinHeap b(std::move(a));
  EXPECT_EQ(b.top(), 2U);
  EXPECT_EQ(b.capacity(), 4U);
  // The moved-from state is defined: checking it is the point.
  // NOLINTBEGIN(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
  EXPECT_EQ(a.capacity(), 0U);
  EXPECT_TRUE(a.empty());
  EXPECT_TRUE(a.check_invariants());
  // NOLINTEND(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
}

// The heap against a model: an ordered set of (key, handle) and a map handle -> key.
class IndexedMinHeapModelTest : public ::testing::Test {
 protected:
  static constexpr std::uint32_t kCapacity = 64;

  double random_key() {
    switch (random_.below(10)) {
      case 0:
        return kInf;
      case 1:
      case 2:
        return static_cast<double>(random_.below(4));  // frequent ties
      default:
        return random_.uniform(-1000.0, 1000.0);
    }
  }
  std::uint32_t random_contained() {
    auto it = keys_.begin();
    std::advance(it, static_cast<long>(random_.below(static_cast<std::uint32_t>(keys_.size()))));
    return it->first;
  }

  void expect_matches_model() {
    ASSERT_TRUE(heap_.check_invariants());
    ASSERT_EQ(heap_.size(), order_.size());
    if (!order_.empty()) {
      ASSERT_EQ(heap_.top(), order_.begin()->second);
      ASSERT_EQ(heap_.top_key(), order_.begin()->first);
    }
  }

  IndexedMinHeap heap_{kCapacity};
  std::set<std::pair<double, std::uint32_t>> order_;
  std::map<std::uint32_t, double> keys_;
  Random random_{2024};
};

TEST_F(IndexedMinHeapModelTest, AgreesWithTheModelThroughTenThousandRandomOperations) {
  int pushes = 0;
  int updates = 0;
  int erases = 0;
  int pops = 0;
  for (int step = 0; step < 10000; ++step) {
    const std::uint32_t op = random_.below(4);
    if (op == 0 || keys_.empty()) {
      const std::uint32_t h = random_.below(kCapacity);
      if (keys_.count(h) != 0) {
        continue;  // pushing a contained handle is a contract violation, tested elsewhere
      }
      const double key = random_key();
      ASSERT_TRUE(heap_.push(h, key));
      order_.emplace(key, h);
      keys_[h] = key;
      ++pushes;
    } else if (op == 1) {
      const std::uint32_t h = random_contained();
      const double key = random_key();
      heap_.update(h, key);
      order_.erase({keys_[h], h});
      order_.emplace(key, h);
      keys_[h] = key;
      ++updates;
    } else if (op == 2) {
      const std::uint32_t h = random_contained();
      heap_.erase(h);
      order_.erase({keys_[h], h});
      keys_.erase(h);
      ++erases;
    } else {
      const auto expected = *order_.begin();
      ASSERT_EQ(heap_.pop(), expected.second);
      order_.erase(order_.begin());
      keys_.erase(expected.second);
      ++pops;
    }
    ASSERT_NO_FATAL_FAILURE(expect_matches_model()) << "after step " << step;
    for (const auto& [h, key] : keys_) {
      ASSERT_TRUE(heap_.contains(h));
      ASSERT_EQ(heap_.key(h), key);
    }
  }
  // Every kind of operation was exercised many times.
  EXPECT_GT(pushes, 1000);
  EXPECT_GT(updates, 1000);
  EXPECT_GT(erases, 1000);
  EXPECT_GT(pops, 1000);
}

TEST(IndexedMinHeapDeathTest, PushingAContainedHandlePanics) {
  IndexedMinHeap heap(4);
  ASSERT_TRUE(heap.push(1, 1.0));
  EXPECT_DEATH(static_cast<void>(heap.push(1, 2.0)), "invariant violated");
}

TEST(IndexedMinHeapDeathTest, PushingAHandleOutOfRangePanics) {
  IndexedMinHeap heap(4);
  EXPECT_DEATH(static_cast<void>(heap.push(4, 1.0)), "invariant violated");
}

TEST(IndexedMinHeapDeathTest, NanKeysPanic) {
  IndexedMinHeap heap(4);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DEATH(static_cast<void>(heap.push(0, nan)), "invariant violated");
  ASSERT_TRUE(heap.push(0, 1.0));
  EXPECT_DEATH(heap.update(0, nan), "invariant violated");
}

TEST(IndexedMinHeapDeathTest, TouchingAnAbsentHandlePanics) {
  IndexedMinHeap heap(4);
  ASSERT_TRUE(heap.push(0, 1.0));
  EXPECT_DEATH(heap.update(2, 1.0), "invariant violated");
  EXPECT_DEATH(heap.erase(2), "invariant violated");
  EXPECT_DEATH(static_cast<void>(heap.key(2)), "invariant violated");
}

TEST(IndexedMinHeapDeathTest, TopOrPopOnAnEmptyHeapPanics) {
  IndexedMinHeap heap(4);
  EXPECT_DEATH(static_cast<void>(heap.top()), "invariant violated");
  EXPECT_DEATH(static_cast<void>(heap.top_key()), "invariant violated");
  EXPECT_DEATH(static_cast<void>(heap.pop()), "invariant violated");
}

TEST(IndexedMinHeapDeathTest, AMaxSizeAboveTheCapacityPanics) {
  EXPECT_DEATH(IndexedMinHeap(4, 5), "invariant violated");
}

}  // namespace
}  // namespace grip
