// The planner's end of the link against what a second planner, a late start, a hostile stamp or
// an unusable map does: the vehicle executes one planner's plans and reports the other's; a
// planner started long after the goal takes the durable goal; a state stamped far in the future
// is rejected without locking the vehicle out; a map geometry the planner cannot plan on is
// rejected and counted, and the planner waits for a vehicle it can plan for; a map larger than
// the planner is sized for is refused with the parameter to raise.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "running_planner.hpp"
#include "vehicle_side.hpp"

namespace grip::rt::dds {
namespace {

using namespace std::chrono_literals;
using link::testing::VehicleSide;
using testing::eventually;
using testing::planner_config;
using testing::RunningPlanner;

PlannerParticipantConfig quiet_planner(platform::dds::DomainId domain) {
  PlannerParticipantConfig config = planner_config(domain, 0.0);
  config.on_warning = [](const std::string&) {};
  return config;
}

TEST(OnePlanSource, TheVehicleExecutesOnePlannersPlansAndReportsTheSecondOnes) {
  constexpr platform::dds::DomainId kDomain = 183;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  auto first = std::make_unique<RunningPlanner>(quiet_planner(kDomain));
  ASSERT_NE(first->planner, nullptr) << first->result->error().message;
  link::VehicleLink& link = vehicle->link();
  std::set<std::uint64_t> executed;  // the planner incarnations whose plans were taken
  const auto take = [&] {
    link.take_plans([&](const grip_msg_Plan& plan) { executed.insert(plan.incarnation); });
  };
  ASSERT_TRUE(eventually(
      [&] {
        take();
        return !executed.empty();
      },
      20000ms, vehicle.get()))
      << "no plan from the first planner";
  const std::uint64_t followed = link.planner_incarnation();
  ASSERT_NE(followed, 0U);

  // GIVEN a second planner on the domain, THEN its plans are rejected and counted.
  RunningPlanner second(quiet_planner(kDomain));
  ASSERT_NE(second.planner, nullptr) << second.result->error().message;
  EXPECT_TRUE(eventually(
      [&] {
        take();
        return link.plans_from_other_planner() > 20;
      },
      20000ms, vehicle.get()))
      << "the second planner's plans were not seen";
  EXPECT_EQ(executed, std::set<std::uint64_t>{followed}) << "plans of two planners executed";
  EXPECT_EQ(link.planner_incarnation(), followed);
  EXPECT_EQ(link.planner_failovers(), 0U);

  // WHEN the first dies, THEN the second is followed after one lease.
  first.reset();
  EXPECT_TRUE(eventually(
      [&] {
        take();
        return link.planner_incarnation() != followed;
      },
      10000ms, vehicle.get()))
      << "the standby was never taken over";
  EXPECT_EQ(link.planner_failovers(), 1U);
  EXPECT_EQ(executed.size(), 2U);
}

// The goal is durable (TRANSIENT_LOCAL): a planner that starts long after it was set takes it.
TEST(DurableGoal, APlannerStartedLongAfterTheGoalWasSetTakesIt) {
  constexpr platform::dds::DomainId kDomain = 184;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  EXPECT_FALSE(eventually([] { return false; }, 6500ms, vehicle.get()));  // > 5 s of age
  PlannerParticipantConfig config = quiet_planner(kDomain);
  config.explore_without_goal = false;  // without the goal, start-up would time out
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  std::optional<grip_msg_PlannerStatus> status;
  ASSERT_TRUE(eventually(
      [&] {
        if (auto s = vehicle->link().take_status()) status = s;
        return status && status->cycle > 5;
      },
      20000ms, vehicle.get()))
      << "the planner never planned";
  EXPECT_FALSE(status->exploring) << "the goal was ignored";
  EXPECT_EQ(status->rejected_goal, 0U);
  EXPECT_DOUBLE_EQ(status->target_x_m, vehicle->scene().goal_x_m);
  EXPECT_DOUBLE_EQ(status->target_y_m, vehicle->scene().goal_y_m);
}

TEST(StampLead, AVehicleStateStampedFarInTheFutureIsRejectedWithoutLockingTheVehicleOut) {
  constexpr platform::dds::DomainId kDomain = 185;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  RunningPlanner planner(quiet_planner(kDomain));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  std::optional<grip_msg_PlannerStatus> status;
  const auto latest = [&] {
    if (auto s = vehicle->link().take_status()) status = s;
    return status.has_value();
  };
  ASSERT_TRUE(eventually([&] { return latest() && status->cycle > 5; }, 20000ms, vehicle.get()));
  // A state of this very vehicle (its incarnation), stamped an hour ahead.
  grip_msg_VehicleState future = vehicle->state();
  future.stamp_ns += 3600ULL * 1'000'000'000ULL;
  future.sequence_number += 1000;
  ASSERT_TRUE(vehicle->link().publish_state(future).ok());
  // Alone for a moment: the state topic keeps only the newest sample.
  std::this_thread::sleep_for(300ms);
  ASSERT_TRUE(eventually([&] { return latest() && status->rejected_vehicle_state >= 1; }, 5000ms,
                         vehicle.get()))
      << "the future state was not rejected";
  const std::uint64_t rejected = status->rejected_vehicle_state;
  // The vehicle's own states go on being accepted: 50 more, none rejected.
  for (int i = 0; i < 50; ++i) {
    vehicle->service();
    std::this_thread::sleep_for(10ms);
  }
  const std::uint64_t cycle = status->cycle;
  ASSERT_TRUE(
      eventually([&] { return latest() && status->cycle > cycle + 5; }, 5000ms, vehicle.get()));
  EXPECT_EQ(status->rejected_vehicle_state, rejected) << "the vehicle was locked out";
}

TEST(UnusableGeometry, AMapThePlannerCannotPlanOnIsRejectedAndCountedAndThePlannerWaits) {
  constexpr platform::dds::DomainId kDomain = 186;
  std::mutex mutex;
  std::vector<std::string> warnings;
  PlannerParticipantConfig config = planner_config(kDomain, 0.0);
  config.on_warning = [&](const std::string& line) {
    const std::lock_guard<std::mutex> lock(mutex);
    warnings.push_back(line);
  };
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  const auto refused = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const std::string& w : warnings) {
      if (w.find("cannot plan on its geometry") != std::string::npos) return true;
    }
    return false;
  };
  {
    // Contract-valid, but 5 m cells: coarser than the frontier's approach range.
    link::VehicleLinkConfig link_config;
    link_config.domain = kDomain;
    link_config.topic_prefix = ::grip::testing::private_topic_prefix();
    link_config.vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
    OccupancyGrid coarse = OccupancyGrid::create(20, 20, 5.0, 0.0, 0.0, Cell::kFree).value();
    auto link = link::VehicleLink::create(link_config, std::move(coarse)).value();
    link->publish_map_updates(CellBox{0, 0, 19, 19}, 1);
    grip_msg_VehicleState state{};
    state.kind = grip_msg_DD_VELOCITY;
    state.state[0] = 50.0;
    state.state[1] = 50.0;
    state.state_dim = 3;
    state.time_scale = 1.0;
    ASSERT_TRUE(eventually(
        [&] {
          state.stamp_ns = static_cast<std::uint64_t>(platform::now_ns());
          ++state.sequence_number;
          static_cast<void>(link->publish_state(state));
          link->answer_map_requests(state.stamp_ns);
          return refused();
        },
        20000ms))
        << "the coarse map was never refused";
    EXPECT_FALSE(planner.returned.load()) << "the planner exited on a map it could not use";
  }
  // A vehicle whose map the planner can use, after the first is gone: planned for.
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  std::optional<grip_msg_PlannerStatus> status;
  ASSERT_TRUE(eventually(
      [&] {
        if (auto s = vehicle->link().take_status()) status = s;
        return status && status->cycle > 5;
      },
      30000ms, vehicle.get()))
      << "the planner never planned for the next vehicle";
  EXPECT_GE(status->rejected_map_update, 1U);
  EXPECT_FALSE(planner.returned.load());
}

TEST(MapTooLarge, ARealMapLargerThanThePlannerIsSizedForIsRefusedNamingTheParameter) {
  constexpr platform::dds::DomainId kDomain = 188;
  std::mutex mutex;
  std::vector<std::string> warnings;
  PlannerParticipantConfig config = planner_config(kDomain, 0.0);
  config.max_map_cells = 10'000;
  config.on_warning = [&](const std::string& line) {
    const std::lock_guard<std::mutex> lock(mutex);
    warnings.push_back(line);
  };
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  const auto told = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const std::string& w : warnings) {
      if (w.find("200 x 200 cells (40000)") != std::string::npos &&
          w.find("planner.max_map_cells 10000") != std::string::npos) {
        return true;
      }
    }
    return false;
  };
  link::VehicleLinkConfig link_config;
  link_config.domain = kDomain;
  link_config.topic_prefix = ::grip::testing::private_topic_prefix();
  link_config.vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
  OccupancyGrid big = OccupancyGrid::create(200, 200, 0.1, 0.0, 0.0, Cell::kFree).value();
  auto link = link::VehicleLink::create(link_config, std::move(big)).value();
  ASSERT_TRUE(eventually(
      [&] {
        link->publish_map_updates(CellBox{0, 0, 199, 199}, 1);
        return told();
      },
      20000ms))
      << "the planner never said which parameter to raise";
  const std::lock_guard<std::mutex> lock(mutex);
  const auto said = std::count_if(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("raise planner.max_map_cells") != std::string::npos;
  });
  EXPECT_EQ(said, 1) << "said once per map, not per sample";
  EXPECT_FALSE(planner.returned.load()) << "the planner exited on a map it was not sized for";
}

}  // namespace
}  // namespace grip::rt::dds
