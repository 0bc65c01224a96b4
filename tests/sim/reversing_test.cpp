// The share of a run spent reversing against hand-computed routes: forward, backward, a
// three-point turn, standing still, and routes whose sizes do not fit.

#include "grip/sim/reversing.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numbers>
#include <vector>

namespace grip::sim {
namespace {

using Route = std::vector<std::array<double, 2>>;

TEST(ReversingFraction, ADriveAlongTheHeadingIsForwardAndAgainstItReverse) {
  // Along +x: facing +x it drives forward, facing -x (pi) it backs up.
  const Route route{{0.0, 0.0}, {0.1, 0.0}, {0.2, 0.0}, {0.3, 0.0}};
  const std::vector<double> facing_on(4, 0.0);
  const std::vector<double> facing_back(4, std::numbers::pi);
  EXPECT_EQ(reversing_fraction(route, facing_on, 4).value(), 0.0);
  // The first tick has no move: 3 of 4 ticks reverse.
  EXPECT_EQ(reversing_fraction(route, facing_back, 4).value(), 0.75);
  EXPECT_EQ(reversing_fraction(route, facing_back, 3).value(), 1.0);
}

TEST(ReversingFraction, AThreePointTurnBacksUpInItsMiddleLeg) {
  // Facing +y throughout (the heading changes little on a turn's short legs): 2 ticks forward
  // up, 3 back down, 2 up again. Standing still (the last tick) is not reversing.
  const Route route{{0, 0.0},  {0, 0.1}, {0, 0.2}, {0, 0.1}, {0, 0.0},
                    {0, -0.1}, {0, 0.0}, {0, 0.1}, {0, 0.1}};
  const std::vector<double> up(route.size(), std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(reversing_fraction(route, up, 8).value(), 3.0 / 8.0);
  EXPECT_EQ(reversing_fraction(route, up, 3).value(), 0.0);  // the last leg and the stop
  EXPECT_EQ(reversing_fraction(route, up, 4).value(), 0.25);
  EXPECT_EQ(reversing_fraction(route, up, 0).value(), 0.0);
}

TEST(ReversingFraction, HeadingsOrTicksThatDoNotFitTheRouteAreRefusedByName) {
  const Route route{{0.0, 0.0}, {0.1, 0.0}};
  const auto short_headings = reversing_fraction(route, std::vector<double>{0.0}, 2);
  ASSERT_FALSE(short_headings.ok());
  EXPECT_NE(short_headings.error().message.find("1 headings for a route of 2 ticks"),
            std::string::npos)
      << short_headings.error().message;
  const auto too_many = reversing_fraction(route, std::vector<double>{0.0, 0.0}, 3);
  ASSERT_FALSE(too_many.ok());
  EXPECT_NE(too_many.error().message.find("the last 3 ticks of a route of 2"), std::string::npos)
      << too_many.error().message;
}

}  // namespace
}  // namespace grip::sim
