#include "grip/memory/fixed_vector.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <type_traits>
#include <utility>

namespace grip {
namespace {

struct Point {
  double x_m;
  double y_m;
};

// Counts live instances, to check that only live elements are constructed and all are destroyed.
struct Tracked {
  static inline int live = 0;
  explicit Tracked(int v) noexcept : value(v) { ++live; }
  Tracked(const Tracked& other) noexcept : value(other.value) { ++live; }
  Tracked(Tracked&& other) noexcept : value(other.value) { ++live; }
  Tracked& operator=(const Tracked&) = default;
  ~Tracked() { --live; }
  int value;
};

// A function that takes the capacity-free view, as planner code does.
int sum(const VectorView<int>& values) { return std::accumulate(values.begin(), values.end(), 0); }
bool append_squares(VectorView<int>& out, int count) {
  for (int i = 0; i < count; ++i) {
    if (!out.push_back(i * i)) {
      return false;
    }
  }
  return true;
}

static_assert(!std::is_copy_constructible_v<FixedVector<int, 4>>);
static_assert(!std::is_copy_constructible_v<BoundedVector<int>>);
static_assert(!std::is_copy_constructible_v<VectorView<int>>);
static_assert(std::is_nothrow_move_constructible_v<BoundedVector<int>>);

TEST(FixedVector, StartsEmptyWithItsTypeCapacity) {
  FixedVector<int, 4> v;
  EXPECT_TRUE(v.empty());
  EXPECT_FALSE(v.full());
  EXPECT_EQ(v.size(), 0U);
  EXPECT_EQ(v.capacity(), 4U);
  EXPECT_EQ(v.begin(), v.end());
}

TEST(FixedVector, RefusesPushWhenFullAndKeepsItsContents) {
  // GIVEN a vector filled to capacity
  FixedVector<int, 3> v;
  EXPECT_TRUE(v.push_back(10));
  EXPECT_TRUE(v.push_back(20));
  EXPECT_TRUE(v.push_back(30));
  ASSERT_TRUE(v.full());

  // WHEN one more element is pushed or emplaced
  const bool pushed = v.push_back(40);
  int* emplaced = v.emplace_back(50);

  // THEN both are refused and nothing changed
  EXPECT_FALSE(pushed);
  EXPECT_EQ(emplaced, nullptr);
  ASSERT_EQ(v.size(), 3U);
  EXPECT_EQ(v[0], 10);
  EXPECT_EQ(v[1], 20);
  EXPECT_EQ(v[2], 30);
}

TEST(FixedVector, EmplaceBackReturnsTheNewElement) {
  FixedVector<Point, 2> v;
  Point* p = v.emplace_back(1.0, 2.0);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p, &v.back());
  EXPECT_DOUBLE_EQ(v.front().x_m, 1.0);
  EXPECT_DOUBLE_EQ(v.front().y_m, 2.0);
}

TEST(FixedVector, PopBackTruncateAndClearShrinkTheSize) {
  FixedVector<int, 8> v;
  for (int i = 0; i < 6; ++i) {
    ASSERT_TRUE(v.push_back(i));
  }
  v.pop_back();
  EXPECT_EQ(v.size(), 5U);
  EXPECT_EQ(v.back(), 4);

  v.truncate(3);
  EXPECT_EQ(v.size(), 3U);
  EXPECT_EQ(v.back(), 2);

  v.resize_down(1);
  EXPECT_EQ(v.size(), 1U);
  EXPECT_EQ(v.front(), 0);

  v.clear();
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.capacity(), 8U);
}

TEST(FixedVector, SpanCoversExactlyTheLiveElements) {
  FixedVector<int, 8> v;
  ASSERT_TRUE(v.push_back(7));
  ASSERT_TRUE(v.push_back(8));
  const std::span<int> s = v.span();
  EXPECT_EQ(s.data(), v.data());
  ASSERT_EQ(s.size(), 2U);
  EXPECT_EQ(s[1], 8);
  const auto& cv = v;
  EXPECT_EQ(cv.span().size(), 2U);
}

TEST(FixedVector, ConstructsOnlyLiveElementsAndDestroysThemAll) {
  Tracked::live = 0;
  {
    FixedVector<Tracked, 16> v;
    EXPECT_EQ(Tracked::live, 0);  // no default construction of the 16 slots
    ASSERT_NE(v.emplace_back(1), nullptr);
    ASSERT_TRUE(v.push_back(Tracked{2}));
    EXPECT_EQ(Tracked::live, 2);
    v.pop_back();
    EXPECT_EQ(Tracked::live, 1);
    ASSERT_NE(v.emplace_back(3), nullptr);
    ASSERT_NE(v.emplace_back(4), nullptr);
    v.truncate(1);
    EXPECT_EQ(Tracked::live, 1);
    ASSERT_NE(v.emplace_back(5), nullptr);
  }
  EXPECT_EQ(Tracked::live, 0);
}

TEST(FixedVector, MoveTransfersTheElementsAndEmptiesTheSource) {
  Tracked::live = 0;
  {
    FixedVector<Tracked, 4> a;
    ASSERT_NE(a.emplace_back(1), nullptr);
    ASSERT_NE(a.emplace_back(2), nullptr);

    FixedVector<Tracked, 4> b(std::move(a));
    // The moved-from state is defined: checking it is the point.
    // NOLINTBEGIN(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
    EXPECT_TRUE(a.empty());
    // NOLINTEND(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
    ASSERT_EQ(b.size(), 2U);
    EXPECT_EQ(b[0].value, 1);
    EXPECT_EQ(b[1].value, 2);
    EXPECT_EQ(Tracked::live, 2);

    FixedVector<Tracked, 4> c;
    ASSERT_NE(c.emplace_back(9), nullptr);
    c = std::move(b);
    ASSERT_EQ(c.size(), 2U);
    EXPECT_EQ(c[1].value, 2);
    EXPECT_EQ(Tracked::live, 2);
  }
  EXPECT_EQ(Tracked::live, 0);
}

TEST(FixedVector, IsUsableThroughTheCapacityFreeView) {
  FixedVector<int, 4> small;
  FixedVector<int, 64> large;
  EXPECT_FALSE(append_squares(small, 5));  // refuses the fifth
  EXPECT_TRUE(append_squares(large, 5));
  EXPECT_EQ(sum(small), 0 + 1 + 4 + 9);
  EXPECT_EQ(sum(large), 0 + 1 + 4 + 9 + 16);
}

TEST(BoundedVector, TakesItsCapacityAtConstruction) {
  BoundedVector<std::uint64_t> v(5);
  EXPECT_EQ(v.capacity(), 5U);
  EXPECT_TRUE(v.empty());
  for (std::uint64_t i = 0; i < 5; ++i) {
    EXPECT_TRUE(v.push_back(i));
  }
  EXPECT_TRUE(v.full());
  EXPECT_FALSE(v.push_back(99));
  EXPECT_EQ(v.size(), 5U);
  EXPECT_EQ(v.back(), 4U);
}

TEST(BoundedVector, WithZeroCapacityRefusesEverything) {
  BoundedVector<int> v(0);
  EXPECT_TRUE(v.empty());
  EXPECT_TRUE(v.full());
  EXPECT_FALSE(v.push_back(1));
  EXPECT_EQ(v.emplace_back(1), nullptr);
}

TEST(BoundedVector, RespectsTheAlignmentOfOverAlignedElements) {
  struct alignas(64) Block {
    double values[4];
  };
  BoundedVector<Block> v(3);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % 64, 0U);
}

TEST(BoundedVector, MoveTransfersStorageAndLeavesTheSourceWithoutCapacity) {
  Tracked::live = 0;
  {
    BoundedVector<Tracked> a(8);
    ASSERT_NE(a.emplace_back(1), nullptr);
    ASSERT_NE(a.emplace_back(2), nullptr);
    const Tracked* storage = a.data();

    BoundedVector<Tracked> b(std::move(a));
    EXPECT_EQ(b.data(), storage);  // no copy of the elements, no new allocation
    EXPECT_EQ(b.size(), 2U);
    EXPECT_EQ(b.capacity(), 8U);
    // The moved-from state is defined: checking it is the point.
    // NOLINTBEGIN(bugprone-use-after-move,clang-analyzer-cplusplus.Move)
    EXPECT_EQ(a.size(), 0U);
    EXPECT_EQ(a.capacity(), 0U);
    EXPECT_FALSE(a.push_back(Tracked{3}));
    // NOLINTEND(bugprone-use-after-move,clang-analyzer-cplusplus.Move)

    BoundedVector<Tracked> c(1);
    c = std::move(b);
    EXPECT_EQ(c.data(), storage);
    EXPECT_EQ(c[1].value, 2);
    EXPECT_EQ(Tracked::live, 2);
  }
  EXPECT_EQ(Tracked::live, 0);
}

TEST(VectorViewDeathTest, IndexingPastTheSizePanics) {
  FixedVector<int, 4> v;
  ASSERT_TRUE(v.push_back(1));
  EXPECT_DEATH(static_cast<void>(v[1]), "invariant violated");
  EXPECT_DEATH(static_cast<void>(v[4]), "invariant violated");
}

TEST(VectorViewDeathTest, AccessOrPopOnAnEmptyVectorPanics) {
  BoundedVector<int> v(2);
  EXPECT_DEATH(static_cast<void>(v.front()), "invariant violated");
  EXPECT_DEATH(static_cast<void>(v.back()), "invariant violated");
  EXPECT_DEATH(v.pop_back(), "invariant violated");
}

TEST(VectorViewDeathTest, TruncatingToMoreThanTheSizePanics) {
  FixedVector<int, 4> v;
  ASSERT_TRUE(v.push_back(1));
  EXPECT_DEATH(v.truncate(2), "invariant violated");
}

}  // namespace
}  // namespace grip
