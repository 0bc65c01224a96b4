// The path weight an exploration runs with: what the configuration gives, and where it leaves a
// value to the vehicle (< 0), the vehicle's: the duration at two thirds of top speed and a kept
// course for an acceleration-limited vehicle that turns in place, the paper's weight otherwise.

#include "grip/rt/exploration_driver.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip::rt {
namespace {

OccupancyGrid room() {
  return OccupancyGrid::create(80, 60, 0.1, 0.0, 0.0, Cell::kUnknown).value();
}

template <VehicleModel V>
Result<PathSelectionConfig> path_weight_of(const V& vehicle,
                                           const ExplorationDriverConfig& config) {
  const OccupancyGrid grid = room();
  PlannerConfig planner;
  planner.max_edges = 500;
  auto driver = ExplorationDriver<V>::create(vehicle, grid, config, planner);
  if (!driver) return driver.error();
  return driver->path_weight();
}

TEST(ExplorationDriver, LeftToTheVehicleTheWeightIsTheDurationAndTheCourseOnlyForDdAccel) {
  const ExplorationDriverConfig left{};
  const DdAcceleration dd_accel = DdAcceleration::create({}).value();
  const auto accel = path_weight_of(dd_accel, left);
  ASSERT_TRUE(accel.ok()) << accel.error().message;
  EXPECT_DOUBLE_EQ(accel->reference_speed_m_s, 2.0 / 3.0 * dd_accel.max_speed_m_s());
  EXPECT_EQ(accel->course_change_m, 2.0);
  EXPECT_EQ(accel->length_weight_per_m, PathSelectionConfig{}.length_weight_per_m);
  // The sensing radius left at 0 is a tenth of the map's width.
  EXPECT_DOUBLE_EQ(accel->sensing_radius_m, 0.8);

  for (const auto& weight : {path_weight_of(Car::create({}).value(), left),
                             path_weight_of(DdVelocity::create({}).value(), left)}) {
    ASSERT_TRUE(weight.ok()) << weight.error().message;
    EXPECT_EQ(weight->reference_speed_m_s, 0.0);
    EXPECT_EQ(weight->course_change_m, 0.0);
  }
}

TEST(ExplorationDriver, GivenValuesAreTakenAsTheyAreForEveryVehicle) {
  ExplorationDriverConfig given;
  given.path_weight.sensing_radius_m = 2.5;
  given.path_weight.length_weight_per_m = 0.08;
  given.path_weight.reference_speed_m_s = 1.25;
  given.path_weight.course_change_m = 0.5;
  const auto car = path_weight_of(Car::create({}).value(), given);
  ASSERT_TRUE(car.ok()) << car.error().message;
  EXPECT_EQ(car->sensing_radius_m, 2.5);
  EXPECT_EQ(car->length_weight_per_m, 0.08);
  EXPECT_EQ(car->reference_speed_m_s, 1.25);
  EXPECT_EQ(car->course_change_m, 0.5);

  // 0 turns dd-accel's duration and course off: the paper's weight.
  given.path_weight.reference_speed_m_s = 0.0;
  given.path_weight.course_change_m = 0.0;
  const auto accel = path_weight_of(DdAcceleration::create({}).value(), given);
  ASSERT_TRUE(accel.ok()) << accel.error().message;
  EXPECT_EQ(accel->reference_speed_m_s, 0.0);
  EXPECT_EQ(accel->course_change_m, 0.0);
}

TEST(ExplorationDriver, ABadPathWeightIsRefusedByName) {
  ExplorationDriverConfig bad;
  bad.path_weight.length_weight_per_m = std::numeric_limits<double>::quiet_NaN();
  const auto weight = path_weight_of(DdVelocity::create({}).value(), bad);
  ASSERT_FALSE(weight.ok());
  EXPECT_NE(weight.error().message.find("length_weight_per_m"), std::string::npos)
      << weight.error().message;

  // Only kPathWeightOfVehicle stands for the vehicle's value: another negative one is an error.
  ExplorationDriverConfig negative;
  negative.path_weight.reference_speed_m_s = -0.5;
  const auto refused = path_weight_of(DdAcceleration::create({}).value(), negative);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("reference_speed_m_s"), std::string::npos)
      << refused.error().message;
}

}  // namespace
}  // namespace grip::rt
