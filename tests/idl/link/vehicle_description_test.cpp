// The vehicle's description: it holds the model and every parameter by its parameter-file key,
// and the planner's check refuses each kind of difference naming the field and both values,
// while values within the tolerance pass.

#include "grip/link/vehicle_description.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

namespace grip::link {
namespace {

// The index of `name` in `msg`, or -1.
int find(const grip_msg_VehicleDescription& msg, std::string_view name) {
  for (std::uint32_t i = 0; i < msg.parameter_count; ++i) {
    if (msg.parameters[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

double& value_of(grip_msg_VehicleDescription& msg, std::string_view name) {
  const int i = find(msg, name);
  EXPECT_GE(i, 0) << name;
  return msg.parameters[i < 0 ? 0 : i].value;
}

// The message the check returned, or "" when it accepted.
std::string refusal(const VehicleParams& mine, const grip_msg_VehicleDescription& theirs) {
  const Status s = check_vehicle_description(mine, theirs);
  if (s.ok()) return "";
  EXPECT_EQ(s.error().code, ErrorCode::kInvalidArgument);
  return s.error().message;
}

TEST(VehicleDescription, HoldsTheModelAndEveryParameterByItsKey) {
  CarParams car;
  car.wheelbase_m = 0.9;
  grip_msg_VehicleDescription msg = describe_vehicle(car);
  EXPECT_EQ(msg.model, grip_msg_CAR);
  EXPECT_EQ(msg.parameter_count, 11U);
  EXPECT_EQ(value_of(msg, "wheelbase_m"), 0.9);
  EXPECT_EQ(value_of(msg, "footprint.half_width_m"), 0.2);
  EXPECT_EQ(describe_vehicle(DdVelocityParams{}).model, grip_msg_DD_VELOCITY);
  EXPECT_EQ(describe_vehicle(DdAccelerationParams{}).model, grip_msg_DD_ACCELERATION);
}

TEST(VehicleDescription, TheSameParametersAreAccepted) {
  for (const VehicleParams& p :
       {VehicleParams{DdVelocityParams{}}, VehicleParams{DdAccelerationParams{}},
        VehicleParams{CarParams{}}}) {
    EXPECT_EQ(refusal(p, describe_vehicle(p)), "");
  }
}

TEST(VehicleDescription, AnotherWheelbaseIsRefusedNamingTheFieldAndBothValues) {
  CarParams theirs;
  theirs.wheelbase_m = 0.9;
  EXPECT_EQ(refusal(CarParams{}, describe_vehicle(theirs)),
            "the vehicle describes itself with vehicle.wheelbase_m 0.9, this planner's "
            "parameters say 0.5");
}

TEST(VehicleDescription, AFootprintValueIsNamedWithItsSection) {
  CarParams theirs;
  theirs.footprint.front_m = 0.8;
  EXPECT_EQ(refusal(CarParams{}, describe_vehicle(theirs)),
            "the vehicle describes itself with vehicle.footprint.front_m 0.8, this planner's "
            "parameters say 0.6");
}

TEST(VehicleDescription, ValuesWithinTheToleranceAgree) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  value_of(theirs, "wheelbase_m") = 0.5 * (1.0 + 0.9e-3);  // relative, of the larger
  value_of(theirs, "max_steer_rad") = std::numbers::pi / 4 * (1.0 - 0.9e-3);
  EXPECT_EQ(refusal(CarParams{}, theirs), "");
  value_of(theirs, "wheelbase_m") = 0.5 * (1.0 + 1.1e-3);
  EXPECT_NE(refusal(CarParams{}, theirs).find("vehicle.wheelbase_m 0.50055"), std::string::npos)
      << refusal(CarParams{}, theirs);
}

TEST(VehicleDescription, NearZeroTheAbsoluteFloorDecides) {
  DdVelocityParams mine;
  mine.footprint.rear_m = 0.0;
  grip_msg_VehicleDescription theirs = describe_vehicle(mine);
  value_of(theirs, "footprint.rear_m") = 0.9e-9;
  EXPECT_EQ(refusal(mine, theirs), "");
  value_of(theirs, "footprint.rear_m") = 1e-6;
  EXPECT_NE(refusal(mine, theirs).find("vehicle.footprint.rear_m 1e-06"), std::string::npos);
}

TEST(VehicleDescription, ANonFiniteValueIsRefused) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  value_of(theirs, "max_speed_m_s") = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(CarParams{}, theirs),
            "the vehicle describes itself with vehicle.max_speed_m_s nan, this planner's "
            "parameters say 3");
}

TEST(VehicleDescription, AnotherModelIsRefused) {
  EXPECT_EQ(refusal(CarParams{}, describe_vehicle(DdVelocityParams{})),
            "the vehicle describes itself with vehicle.model dd-vel, this planner's parameters "
            "say car");
}

TEST(VehicleDescription, AnUnknownModelIsRefused) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  const std::int32_t raw = 7;
  std::memcpy(&theirs.model, &raw, sizeof raw);
  EXPECT_EQ(refusal(CarParams{}, theirs),
            "the vehicle describes itself with vehicle.model unknown (7), this planner's "
            "parameters say car");
}

TEST(VehicleDescription, AMissingParameterIsRefused) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  const int i = find(theirs, "wheelbase_m");
  ASSERT_GE(i, 0);
  theirs.parameters[i] = theirs.parameters[theirs.parameter_count - 1];  // the last moved up
  --theirs.parameter_count;
  EXPECT_EQ(refusal(CarParams{}, theirs),
            "the vehicle's description lacks vehicle.wheelbase_m (this planner's parameters say "
            "0.5)");
}

TEST(VehicleDescription, AnUnknownParameterIsRefused) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  grip_msg_VehicleParameter& extra = theirs.parameters[theirs.parameter_count++];
  std::strcpy(extra.name, "wing_span_m");
  extra.value = 2.0;
  EXPECT_EQ(refusal(CarParams{}, theirs),
            "the vehicle describes itself with vehicle.wing_span_m, which this planner's car "
            "parameters do not have");
  // A key of another model is as unknown to this one.
  theirs = describe_vehicle(CarParams{});
  std::strcpy(theirs.parameters[find(theirs, "wheelbase_m")].name, "half_axle_m");
  EXPECT_NE(refusal(CarParams{}, theirs).find("vehicle.half_axle_m, which"), std::string::npos);
}

TEST(VehicleDescription, AParameterNamedTwiceIsRefused) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  theirs.parameters[theirs.parameter_count] = theirs.parameters[0];
  ++theirs.parameter_count;
  EXPECT_EQ(refusal(CarParams{}, theirs),
            "the vehicle's description names vehicle.max_speed_m_s twice");
}

TEST(VehicleDescription, ACountBeyondTheArrayAndAnUnterminatedNameAreHandled) {
  grip_msg_VehicleDescription theirs = describe_vehicle(CarParams{});
  theirs.parameter_count = grip_msg_kMaxVehicleParameters + 1;
  EXPECT_EQ(refusal(CarParams{}, theirs),
            "the vehicle's description holds 33 parameters, at most 32 fit");
  theirs = describe_vehicle(CarParams{});
  std::memset(theirs.parameters[0].name, 'x', sizeof theirs.parameters[0].name);
  const std::string why = refusal(CarParams{}, theirs);
  EXPECT_NE(why.find("vehicle." + std::string(40 + 1, 'x') + ", which"), std::string::npos) << why;
}

}  // namespace
}  // namespace grip::link
