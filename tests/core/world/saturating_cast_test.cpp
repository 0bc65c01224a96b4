// The float-to-integer conversion of the world code: defined for every double, including the
// ones hostile input produces (huge, infinite, NaN).

#include "grip/common/saturating_cast.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace grip {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST(SaturatingCastTest, TruncatesInRangeValuesLikeStaticCast) {
  EXPECT_EQ(saturating_cast<int>(3.9), 3);
  EXPECT_EQ(saturating_cast<int>(-3.9), -3);
  EXPECT_EQ(saturating_cast<std::uint32_t>(4e9), 4'000'000'000U);
  EXPECT_EQ(saturating_cast<std::int64_t>(-1e18), -1'000'000'000'000'000'000);
}

TEST(SaturatingCastTest, ClampsHugeAndInfiniteValuesToTheTypesRange) {
  EXPECT_EQ(saturating_cast<int>(1e300), std::numeric_limits<int>::max());
  EXPECT_EQ(saturating_cast<int>(-kInf), std::numeric_limits<int>::min());
  EXPECT_EQ(saturating_cast<int>(2147483647.5), std::numeric_limits<int>::max());
  EXPECT_EQ(saturating_cast<std::uint32_t>(-5.0), 0U);
  EXPECT_EQ(saturating_cast<std::int64_t>(9.3e18), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(saturating_cast<std::uint64_t>(kInf), std::numeric_limits<std::uint64_t>::max());
}

TEST(SaturatingCastTest, NanGivesTheChosenValue) {
  EXPECT_EQ(saturating_cast<int>(kNan), 0);
  EXPECT_EQ(saturating_cast<int>(kNan, -1), -1);
}

TEST(SaturatingCastTest, CellCoordinatesStayInTheirRange) {
  EXPECT_EQ(floor_to_cell(2.5, -1, 10), 2);
  EXPECT_EQ(floor_to_cell(-0.5, -1, 10), -1);
  EXPECT_EQ(floor_to_cell(-1e300, -1, 10), -1);
  EXPECT_EQ(floor_to_cell(1e300, -1, 10), 10);
  EXPECT_EQ(floor_to_cell(kNan, -1, 10), -1);
  EXPECT_EQ(ceil_to_count(2.1, 1, 16), 3);
  EXPECT_EQ(ceil_to_count(kInf, 1, 16), 16);
  EXPECT_EQ(ceil_to_count(kNan, 1, 16), 16);
  EXPECT_EQ(ceil_to_count(-7.0, 1, 16), 1);
}

}  // namespace
}  // namespace grip
