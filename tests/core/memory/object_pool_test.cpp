#include "grip/memory/object_pool.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <set>
#include <type_traits>
#include <utility>
#include <vector>

namespace grip {
namespace {

// What the planner stores: a plain record.
struct Edge {
  std::uint32_t from = 7;  // default member initialisers show that acquire() value-initialises
  std::uint32_t to = 7;
  double cost_s = 1.5;
};

using Pool = ObjectPool<Edge>;

static_assert(!std::is_copy_constructible_v<Pool>);
static_assert(std::is_nothrow_move_constructible_v<Pool>);

class ObjectPoolTest : public ::testing::Test {
 protected:
  static constexpr std::uint32_t kCapacity = 100;  // spans two words of the in-use bit array
  Pool pool_{kCapacity};
};

TEST_F(ObjectPoolTest, StartsEmpty) {
  EXPECT_EQ(pool_.capacity(), kCapacity);
  EXPECT_EQ(pool_.used(), 0U);
  EXPECT_EQ(pool_.available(), kCapacity);
  EXPECT_TRUE(pool_.empty());
  EXPECT_FALSE(pool_.full());
  EXPECT_EQ(pool_.high_water_mark(), 0U);
  for (Pool::Handle h = 0; h < kCapacity; ++h) {
    EXPECT_FALSE(pool_.in_use(h));
  }
}

TEST_F(ObjectPoolTest, AcquiresHandlesInAscendingOrder) {
  for (Pool::Handle expected = 0; expected < kCapacity; ++expected) {
    EXPECT_EQ(pool_.acquire(), expected);
  }
}

TEST_F(ObjectPoolTest, AcquireValueInitialisesTheSlot) {
  // GIVEN a slot that was modified and released
  const Pool::Handle h = pool_.acquire();
  pool_[h] = Edge{1, 2, 3.0};
  pool_.release(h);

  // WHEN it is acquired again
  const Pool::Handle again = pool_.acquire();

  // THEN it holds a fresh T{}, not the old record or the free-list link
  ASSERT_EQ(again, h);
  EXPECT_EQ(pool_[again].from, 7U);
  EXPECT_EQ(pool_[again].to, 7U);
  EXPECT_DOUBLE_EQ(pool_[again].cost_s, 1.5);
}

TEST_F(ObjectPoolTest, SlotsHoldIndependentRecords) {
  std::vector<Pool::Handle> handles;
  for (std::uint32_t i = 0; i < kCapacity; ++i) {
    handles.push_back(pool_.acquire());
    pool_[handles.back()] = Edge{i, i + 1, static_cast<double>(i)};
  }
  for (std::uint32_t i = 0; i < kCapacity; ++i) {
    const Pool& const_pool = pool_;
    EXPECT_EQ(const_pool[handles[i]].from, i);
    EXPECT_EQ(const_pool[handles[i]].to, i + 1);
  }
}

TEST_F(ObjectPoolTest, ReturnsInvalidWhenExhaustedAndWorksAgainAfterARelease) {
  // GIVEN a pool with every slot in use
  for (std::uint32_t i = 0; i < kCapacity; ++i) {
    ASSERT_NE(pool_.acquire(), Pool::kInvalid);
  }
  ASSERT_TRUE(pool_.full());

  // WHEN one more is asked for THEN it is refused and nothing changes
  EXPECT_EQ(pool_.acquire(), Pool::kInvalid);
  EXPECT_EQ(pool_.used(), kCapacity);

  // WHEN one slot is released THEN exactly that one can be acquired again
  pool_.release(42);
  EXPECT_EQ(pool_.used(), kCapacity - 1);
  EXPECT_EQ(pool_.acquire(), 42U);
  EXPECT_EQ(pool_.acquire(), Pool::kInvalid);
}

TEST_F(ObjectPoolTest, ReusesTheMostRecentlyReleasedHandleFirst) {
  for (int i = 0; i < 10; ++i) {
    static_cast<void>(pool_.acquire());
  }
  pool_.release(3);
  pool_.release(8);
  pool_.release(5);
  EXPECT_EQ(pool_.acquire(), 5U);
  EXPECT_EQ(pool_.acquire(), 8U);
  EXPECT_EQ(pool_.acquire(), 3U);
  EXPECT_EQ(pool_.acquire(), 10U);  // then the untouched tail
}

TEST_F(ObjectPoolTest, TracksInUseAndUsedCount) {
  const Pool::Handle a = pool_.acquire();
  const Pool::Handle b = pool_.acquire();
  EXPECT_TRUE(pool_.in_use(a));
  EXPECT_TRUE(pool_.in_use(b));
  EXPECT_EQ(pool_.used(), 2U);
  pool_.release(a);
  EXPECT_FALSE(pool_.in_use(a));
  EXPECT_TRUE(pool_.in_use(b));
  EXPECT_EQ(pool_.used(), 1U);
  EXPECT_FALSE(pool_.in_use(kCapacity));
  EXPECT_FALSE(pool_.in_use(Pool::kInvalid));
}

TEST_F(ObjectPoolTest, HighWaterMarkKeepsTheMaximumEvenAfterClear) {
  for (int i = 0; i < 30; ++i) {
    static_cast<void>(pool_.acquire());
  }
  for (Pool::Handle h = 0; h < 20; ++h) {
    pool_.release(h);
  }
  EXPECT_EQ(pool_.used(), 10U);
  EXPECT_EQ(pool_.high_water_mark(), 30U);
  pool_.clear();
  EXPECT_EQ(pool_.high_water_mark(), 30U);
}

TEST_F(ObjectPoolTest, ClearReleasesEverythingAndRestoresAscendingOrder) {
  // GIVEN a pool whose free list has been shuffled by releases
  for (int i = 0; i < 50; ++i) {
    static_cast<void>(pool_.acquire());
  }
  for (Pool::Handle h : {7U, 31U, 2U, 49U}) {
    pool_.release(h);
  }

  // WHEN it is cleared
  pool_.clear();

  // THEN nothing is in use and acquisition starts again from 0 in order
  EXPECT_EQ(pool_.used(), 0U);
  for (Pool::Handle h = 0; h < kCapacity; ++h) {
    EXPECT_FALSE(pool_.in_use(h));
  }
  for (Pool::Handle expected = 0; expected < kCapacity; ++expected) {
    EXPECT_EQ(pool_.acquire(), expected);
  }
  EXPECT_EQ(pool_.acquire(), Pool::kInvalid);
}

TEST_F(ObjectPoolTest, RandomAcquireReleaseMatchesASetModel) {
  std::set<Pool::Handle> model;
  std::uint64_t state = 12345;
  auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::uint32_t>(state >> 33);
  };
  for (int step = 0; step < 10000; ++step) {
    if (next() % 2 == 0 || model.empty()) {
      const Pool::Handle h = pool_.acquire();
      if (model.size() == kCapacity) {
        ASSERT_EQ(h, Pool::kInvalid);
      } else {
        ASSERT_NE(h, Pool::kInvalid);
        ASSERT_TRUE(model.insert(h).second) << "handle " << h << " handed out twice";
      }
    } else {
      auto it = model.begin();
      std::advance(it, static_cast<long>(next() % model.size()));
      pool_.release(*it);
      model.erase(it);
    }
    ASSERT_EQ(pool_.used(), model.size());
  }
  for (Pool::Handle h = 0; h < kCapacity; ++h) {
    EXPECT_EQ(pool_.in_use(h), model.count(h) == 1) << "handle " << h;
  }
}

TEST(ObjectPool, WithZeroCapacityAlwaysRefuses) {
  Pool pool(0);
  EXPECT_EQ(pool.acquire(), Pool::kInvalid);
  EXPECT_TRUE(pool.full());
  pool.clear();
  EXPECT_EQ(pool.acquire(), Pool::kInvalid);
}

TEST(ObjectPool, MoveTransfersTheSlotsAndEmptiesTheSource) {
  Pool a(4);
  const Pool::Handle h = a.acquire();
  a[h].cost_s = 9.0;

  Pool b(std::move(a));
  EXPECT_EQ(b.capacity(), 4U);
  EXPECT_EQ(b.used(), 1U);
  EXPECT_DOUBLE_EQ(b[h].cost_s, 9.0);
  EXPECT_EQ(b.acquire(), 1U);
  // The moved-from state is defined: checking it is the point.
  // NOLINTBEGIN(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
  EXPECT_EQ(a.capacity(), 0U);
  EXPECT_EQ(a.acquire(), Pool::kInvalid);
  // NOLINTEND(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
}

using ObjectPoolDeathTest = ObjectPoolTest;

TEST_F(ObjectPoolDeathTest, DoubleReleasePanics) {
  const Pool::Handle h = pool_.acquire();
  pool_.release(h);
  EXPECT_DEATH(pool_.release(h), "invariant violated");
}

TEST_F(ObjectPoolDeathTest, ReleasingAHandleThatWasNeverAcquiredPanics) {
  static_cast<void>(pool_.acquire());
  EXPECT_DEATH(pool_.release(1), "invariant violated");
}

TEST_F(ObjectPoolDeathTest, ReleasingAnOutOfRangeHandlePanics) {
  EXPECT_DEATH(pool_.release(kCapacity), "invariant violated");
  EXPECT_DEATH(pool_.release(Pool::kInvalid), "invariant violated");
}

TEST_F(ObjectPoolDeathTest, AccessingAFreeOrOutOfRangeSlotPanics) {
  const Pool::Handle h = pool_.acquire();
  pool_.release(h);
  EXPECT_DEATH(static_cast<void>(pool_[h]), "invariant violated");
  EXPECT_DEATH(static_cast<void>(pool_[kCapacity]), "invariant violated");
  EXPECT_DEATH(static_cast<void>(pool_[Pool::kInvalid]), "invariant violated");
}

}  // namespace
}  // namespace grip
