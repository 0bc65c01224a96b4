// The planner's estimate of the vehicle's clock on stamps a hostile or broken vehicle sends:
// validation only checks that stamps increase, so any 64-bit stamp reaches the clock.

#include "grip/rt/vehicle_clock.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace grip::rt {
namespace {

TEST(VehicleClockTest, FollowsTheStampsOfAnOrdinaryVehicle) {
  VehicleClock clock;
  clock.observe(5'000'000'000, 1'000'000'000, 1.0);
  EXPECT_EQ(clock.vehicle_ns(2'000'000'000, 1.0), 6'000'000'000);
}

TEST(VehicleClockTest, AStampBeyondInt64SaturatesInsteadOfOverflowing) {
  VehicleClock clock;
  clock.observe(std::numeric_limits<std::uint64_t>::max(), 1'000'000'000, 1000.0);
  EXPECT_EQ(clock.vehicle_ns(2'000'000'000, 1000.0), std::numeric_limits<std::int64_t>::max());
  EXPECT_GT(clock.vehicle_ns(0, 1.0), 0);
}

}  // namespace
}  // namespace grip::rt
