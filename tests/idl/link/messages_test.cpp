// Every kind of bad input the planner or the controller can receive is rejected with its reason
// and the field it concerns; good input passes.

#include "grip/link/messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "grip/vehicles/car.hpp"

namespace grip::link {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

grip_msg_VehicleState car_state() {
  grip_msg_VehicleState msg{};
  msg.stamp_ns = 1000;
  msg.sequence_number = 1;
  msg.kind = grip_msg_CAR;
  msg.state[0] = 2.0;
  msg.state[1] = 3.0;
  msg.state[2] = 0.5;
  msg.state_dim = 5;
  msg.time_scale = 1.0;
  return msg;
}

Car car() { return Car::create(CarParams{}).value(); }

// A value outside the enum, as a corrupt or newer peer may put on the wire.
void set_raw_kind(grip_msg_VehicleKind& kind, std::int32_t raw) {
  static_assert(sizeof kind == sizeof raw);
  std::memcpy(&kind, &raw, sizeof raw);
}

TEST(Messages, AValidVehicleStatePasses) {
  EXPECT_TRUE(check_vehicle_state(car_state(), car(), 0).ok());
  const Car::State q = state_from_wire<Car>(car_state());
  EXPECT_EQ(q[0], 2.0);
  EXPECT_EQ(q[2], 0.5);
}

TEST(Messages, BadVehicleStatesAreRejectedWithTheirReason) {
  struct Case {
    const char* what;
    void (*mutate)(grip_msg_VehicleState&);
    Rejection expected;
  };
  const std::vector<Case> cases{
      {"unknown kind", [](auto& m) { set_raw_kind(m.kind, 7); }, Rejection::kUnknownVehicleKind},
      {"other kind", [](auto& m) { m.kind = grip_msg_DD_VELOCITY; }, Rejection::kWrongVehicleKind},
      {"dim", [](auto& m) { m.state_dim = 3; }, Rejection::kWrongStateDim},
      {"NaN", [](auto& m) { m.state[1] = kNaN; }, Rejection::kNotFinite},
      {"inf", [](auto& m) { m.state[3] = kInf; }, Rejection::kNotFinite},
      {"speed", [](auto& m) { m.state[3] = 50.0; }, Rejection::kOutOfLimits},
      {"time scale", [](auto& m) { m.time_scale = 0.0; }, Rejection::kOutOfLimits},
      {"time scale NaN", [](auto& m) { m.time_scale = kNaN; }, Rejection::kNotFinite},
      {"stale", [](auto& m) { m.stamp_ns = 500; }, Rejection::kStampNotIncreasing},
  };
  for (const Case& c : cases) {
    grip_msg_VehicleState msg = car_state();
    c.mutate(msg);
    const Verdict v = check_vehicle_state(msg, car(), 999);
    EXPECT_EQ(v.reason, c.expected) << c.what << ": got " << rejection_name(v.reason);
    EXPECT_STRNE(v.field, "") << c.what;
  }
}

TEST(Messages, FreshnessRejectsTheFutureAndTheFarPast) {
  const FreshnessLimits limits;
  EXPECT_TRUE(check_freshness(1'000'000'000, 1'000'500'000, limits).ok());
  EXPECT_EQ(check_freshness(3'000'000'000, 1'000'000'000, limits).reason,
            Rejection::kStampInFuture);
  EXPECT_EQ(check_freshness(1'000'000'000, 7'000'000'000, limits).reason, Rejection::kStampTooOld);
}

struct Patch {
  grip_msg_MapUpdate msg{};
  std::vector<std::uint8_t> cells;
  Patch() : cells(16, grip_msg_kCellFree) {
    msg.sequence_number = 1;
    msg.map_width_cells = 10;
    msg.map_height_cells = 8;
    msg.resolution_m = 0.1;
    msg.origin_x_cell = 2;
    msg.origin_y_cell = 3;
    msg.width_cells = 4;
    msg.height_cells = 4;
    sync();
  }
  void sync() {
    msg.cells._buffer = cells.data();
    msg.cells._length = static_cast<std::uint32_t>(cells.size());
    msg.cells._maximum = msg.cells._length;
  }
};

TEST(Messages, BadMapUpdatesAreRejectedWithTheirReason) {
  const MapGeometry expected{10, 8, 0.1, 0.0, 0.0};
  EXPECT_TRUE(check_map_update(Patch().msg, &expected, 1U << 20).ok());
  struct Case {
    const char* what;
    void (*mutate)(Patch&);
    Rejection expected;
  };
  const std::vector<Case> cases{
      {"outside in x", [](Patch& p) { p.msg.origin_x_cell = 7; }, Rejection::kPatchOutsideMap},
      {"outside in y", [](Patch& p) { p.msg.origin_y_cell = 0xFFFFFFFFU; },
       Rejection::kPatchOutsideMap},
      {"empty patch", [](Patch& p) { p.msg.width_cells = 0; }, Rejection::kPatchOutsideMap},
      {"short",
       [](Patch& p) {
         p.cells.resize(15);
         p.sync();
       },
       Rejection::kWrongLength},
      {"long",
       [](Patch& p) {
         p.cells.resize(17);
         p.sync();
       },
       Rejection::kWrongLength},
      {"cell 3", [](Patch& p) { p.cells[5] = 3; }, Rejection::kBadCellValue},
      {"resolution NaN", [](Patch& p) { p.msg.resolution_m = kNaN; }, Rejection::kNotFinite},
      {"resolution 0", [](Patch& p) { p.msg.resolution_m = 0.0; }, Rejection::kBadGeometry},
      {"origin inf", [](Patch& p) { p.msg.map_origin_x_m = kInf; }, Rejection::kNotFinite},
      {"other map", [](Patch& p) { p.msg.map_width_cells = 12; }, Rejection::kGeometryMismatch},
      {"huge map", [](Patch& p) { p.msg.map_height_cells = 100000; }, Rejection::kBadGeometry},
      // A real map, larger than this receiver's 1 M cells: told apart from a nonsensical one.
      {"larger than the receiver",
       [](Patch& p) { p.msg.map_width_cells = 2048, p.msg.map_height_cells = 1024; },
       Rejection::kMapTooLarge},
      // Valid-looking geometry the planner's grids are not sized for (the issue's "unusual
      // resolution" that made the planner exit at start-up): rejected and counted instead.
      {"resolution 1e-300", [](Patch& p) { p.msg.resolution_m = 1e-300; }, Rejection::kBadGeometry},
      {"resolution below 1 mm", [](Patch& p) { p.msg.resolution_m = 0.0009; },
       Rejection::kBadGeometry},
      {"resolution above 10 m", [](Patch& p) { p.msg.resolution_m = 10.5; },
       Rejection::kBadGeometry},
      {"resolution 1e300", [](Patch& p) { p.msg.resolution_m = 1e300; }, Rejection::kBadGeometry},
      {"origin far away", [](Patch& p) { p.msg.map_origin_y_m = -2e6; }, Rejection::kBadGeometry},
      {"snapshot part",
       [](Patch& p) { p.msg.snapshot_id = 1, p.msg.snapshot_part = 2, p.msg.snapshot_parts = 2; },
       Rejection::kBadSnapshot},
      {"part without id", [](Patch& p) { p.msg.snapshot_part = 1; }, Rejection::kBadSnapshot},
  };
  for (const Case& c : cases) {
    Patch p;
    c.mutate(p);
    EXPECT_EQ(check_map_update(p.msg, &expected, 1U << 20).reason, c.expected)
        << c.what << ": got "
        << rejection_name(check_map_update(p.msg, &expected, 1U << 20).reason);
  }
}

TEST(Messages, BadGoalsAreRejected) {
  const OccupancyGrid grid = OccupancyGrid::create(100, 100, 0.1).value();
  grip_msg_Goal goal{};
  goal.x_m = 5.0;
  goal.y_m = 5.0;
  goal.radius_m = 1.0;
  EXPECT_TRUE(check_goal(goal, grid).ok());
  grip_msg_Goal bad = goal;
  bad.x_m = kNaN;
  EXPECT_EQ(check_goal(bad, grid).reason, Rejection::kNotFinite);
  bad = goal;
  bad.radius_m = -1.0;
  EXPECT_EQ(check_goal(bad, grid).reason, Rejection::kOutOfLimits);
  bad = goal;
  bad.y_m = 10.5;
  EXPECT_EQ(check_goal(bad, grid).reason, Rejection::kGoalOutsideMap);
}

TEST(Messages, BadPlansAreRejectedByTheController) {
  std::vector<grip_msg_PlanStep> steps(3, grip_msg_PlanStep{{0.2, 0.1}, 0.5});
  grip_msg_Plan plan{};
  plan.kind = grip_msg_CAR;
  plan.state_dim = 5;
  plan.contingency = contingency_of(VehicleKind::kCar);
  plan.steps._buffer = steps.data();
  plan.steps._length = 3;
  plan.steps._maximum = 3;
  EXPECT_TRUE(check_plan(plan, VehicleKind::kCar).ok());

  steps[1].duration_s = 0.0;
  EXPECT_EQ(check_plan(plan, VehicleKind::kCar).reason, Rejection::kNonPositiveDuration);
  steps[1].duration_s = -0.05;
  EXPECT_EQ(check_plan(plan, VehicleKind::kCar).reason, Rejection::kNonPositiveDuration);
  steps[1].duration_s = kNaN;
  EXPECT_EQ(check_plan(plan, VehicleKind::kCar).reason, Rejection::kNotFinite);
  steps[1].duration_s = 0.5;
  steps[2].control[0] = kInf;
  EXPECT_EQ(check_plan(plan, VehicleKind::kCar).reason, Rejection::kNotFinite);
  steps[2].control[0] = 0.0;
  EXPECT_EQ(check_plan(plan, VehicleKind::kDdVelocity).reason, Rejection::kWrongVehicleKind);
  set_raw_kind(plan.kind, 9);
  EXPECT_EQ(check_plan(plan, VehicleKind::kCar).reason, Rejection::kUnknownVehicleKind);
  plan.kind = grip_msg_CAR;
  plan.steps._length = 0;
  EXPECT_TRUE(check_plan(plan, VehicleKind::kCar).ok())
      << "no steps: nothing new from the start time";
  plan.steps._length = 3;
  plan.start_state[0] = kNaN;
  EXPECT_EQ(check_plan(plan, VehicleKind::kCar).reason, Rejection::kNotFinite);
}

TEST(Messages, APlanWithAContingencyOutsideItsEnumIsRejected) {
  grip_msg_Plan plan{};
  plan.kind = grip_msg_CAR;
  plan.state_dim = 5;
  plan.contingency = contingency_of(VehicleKind::kCar);
  ASSERT_TRUE(check_plan(plan, VehicleKind::kCar).ok());
  // Read as the integer on the wire: loading a value outside the enum as the enum is undefined.
  const std::int32_t raw = 77;
  std::memcpy(&plan.contingency, &raw, sizeof raw);
  const Verdict v = check_plan(plan, VehicleKind::kCar);
  EXPECT_EQ(v.reason, Rejection::kOutOfLimits);
  EXPECT_STREQ(v.field, "contingency");
}

TEST(Messages, PlannerStatusesWithBrokenFieldsAreRejected) {
  grip_msg_PlannerStatus status{};
  std::strcpy(status.policy, "grip");
  status.cycle_time_s = 0.01;
  EXPECT_TRUE(check_planner_status(status).ok());
  grip_msg_PlannerStatus bad = status;
  std::memset(bad.policy, 'x', sizeof bad.policy);  // no terminating NUL
  EXPECT_EQ(check_planner_status(bad).reason, Rejection::kWrongLength);
  bad = status;
  bad.cycle_time_s = kNaN;
  EXPECT_EQ(check_planner_status(bad).reason, Rejection::kNotFinite);
  bad.cycle_time_s = -1.0;
  EXPECT_EQ(check_planner_status(bad).reason, Rejection::kOutOfLimits);
  bad = status;
  bad.target_y_m = kInf;
  EXPECT_EQ(check_planner_status(bad).reason, Rejection::kNotFinite);
}

}  // namespace
}  // namespace grip::link
