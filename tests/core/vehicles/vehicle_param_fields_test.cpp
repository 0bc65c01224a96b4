// The parameter table names every field of each model once: a field added to a params struct
// and forgotten in the table would go undescribed to the planner, and a difference in it
// unnoticed.

#include "grip/vehicles/vehicle_param_fields.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>

namespace grip {
namespace {

// Sets each named field to its position in the table, then reads them back through the struct.
template <typename P>
void expect_every_field_named_once(P params) {
  std::set<std::string> names;
  int position = 0;
  for_each_param(params, [&](std::string_view key, double& value) {
    EXPECT_TRUE(names.insert(std::string(key)).second) << key << " named twice";
    value = ++position;
  });
  // Every field of these structs is a double (the footprint three of them): as many names as
  // doubles, and each one a different field.
  EXPECT_EQ(static_cast<std::size_t>(position), sizeof(P) / sizeof(double));
  position = 0;
  const P& read = params;
  for_each_param(read, [&](std::string_view key, const double& value) {
    EXPECT_EQ(value, ++position) << key;
  });
}

TEST(VehicleParamFields, EveryFieldOfEachModelIsNamedOnce) {
  expect_every_field_named_once(DdVelocityParams{});
  expect_every_field_named_once(DdAccelerationParams{});
  expect_every_field_named_once(CarParams{});
}

TEST(VehicleParamFields, NamesAreTheStructsFieldNamesAndTheFootprintIsNested) {
  CarParams car;
  car.wheelbase_m = 0.9;
  car.footprint.rear_m = 0.3;
  double wheelbase = 0.0;
  double rear = 0.0;
  const VehicleParams params = car;
  for_each_param(params, [&](std::string_view key, double value) {
    if (key == "wheelbase_m") wheelbase = value;
    if (key == "footprint.rear_m") rear = value;
  });
  EXPECT_EQ(wheelbase, 0.9);
  EXPECT_EQ(rear, 0.3);
}

}  // namespace
}  // namespace grip
