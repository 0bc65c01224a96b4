// The planner plans with its own vehicle parameters and refuses a vehicle that describes itself
// otherwise (grip_vehicle_description): start-up fails naming the field and nothing is planned
// or published; a vehicle that does not describe itself is waited for, and start-up times out
// saying so; a new incarnation of the vehicle with other parameters stops planning. Each test
// keeps to a topic prefix of its own within its domain.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "grip/link/map_sync.hpp"
#include "grip/link/topics.hpp"
#include "grip/link/vehicle_description.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/rt/dds/planner_participant.hpp"
#include "private_topics.hpp"
#include "running_planner.hpp"
#include "vehicle_side.hpp"

namespace grip::rt::dds {
namespace {

namespace pdds = platform::dds;
using namespace std::chrono_literals;
using link::testing::VehicleSide;
using testing::eventually;
using testing::planner_config;
using testing::RunningPlanner;

constexpr const char* kRefusedWheelbase =
    "the vehicle describes itself with vehicle.wheelbase_m 0.9, this planner's parameters say 0.5";

PlannerParticipantConfig car_planner(pdds::DomainId domain, const std::string& prefix) {
  PlannerParticipantConfig config = planner_config(domain, 0.0);
  config.vehicle = CarParams{};  // the paper's car
  config.topic_prefix = prefix;
  return config;
}

// Services `vehicle` until the planner's run() has returned or `timeout` passed; the plans the
// vehicle received meanwhile.
std::size_t plans_until_returned(RunningPlanner& planner, VehicleSide& vehicle,
                                 std::chrono::milliseconds timeout) {
  std::size_t plans = 0;
  eventually(
      [&] {
        plans += vehicle.link().take_plans([](const grip_msg_Plan&) {});
        return planner.returned.load();
      },
      timeout, &vehicle);
  return plans;
}

TEST(PlannerDescription, ACarWithAnotherWheelbaseIsRefusedAndNothingIsPlanned) {
  constexpr pdds::DomainId kDomain = 97;
  CarParams longer;
  longer.wheelbase_m = 0.9;
  auto vehicle = VehicleSide::create(kDomain, longer, ::grip::testing::private_topic("wheelbase"));
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());

  RunningPlanner planner(car_planner(kDomain, ::grip::testing::private_topic("wheelbase")));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  const std::size_t plans = plans_until_returned(planner, *vehicle, 20s);
  ASSERT_TRUE(planner.returned) << "the planner did not refuse the vehicle";
  const Result<PlannerParticipantReport>& result = planner.join();
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(result.error().message, kRefusedWheelbase);
  // Nothing was planned: no plan and no status came, even a moment later.
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(plans + vehicle->link().take_plans([](const grip_msg_Plan&) {}), 0U);
  EXPECT_FALSE(vehicle->link().take_status().has_value());
}

TEST(PlannerDescription, AMatchingCarIsPlannedForAsBefore) {
  constexpr pdds::DomainId kDomain = 97;
  auto vehicle =
      VehicleSide::create(kDomain, CarParams{}, ::grip::testing::private_topic("matching"));
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  RunningPlanner planner(car_planner(kDomain, ::grip::testing::private_topic("matching")));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  std::size_t plans = 0;
  EXPECT_TRUE(eventually(
      [&] {
        plans += vehicle->link().take_plans([](const grip_msg_Plan&) {});
        return plans >= 5 || planner.returned;
      },
      20000ms, vehicle.get()))
      << "no plans came";
  EXPECT_GE(plans, 5U);
  const Result<PlannerParticipantReport>& result = planner.stop();
  ASSERT_TRUE(result.ok()) << result.error().message;
}

// What a controller written before the description existed does: state and map, no description.
class UndescribedVehicle {
 public:
  UndescribedVehicle(pdds::DomainId domain, const std::string& prefix)
      : scene_(make_scene("rooms").value()),
        participant_(pdds::Participant::create(domain).value()),
        sender_(scene_.grid) {
    const link::TopicNames topics = link::TopicNames::create(prefix).value();
    const link::LinkTiming timing;
    states_.emplace(pdds::Writer<grip_msg_VehicleState>::create(
                        participant_, &grip_msg_VehicleState_desc, topics.vehicle_state,
                        link::vehicle_state_qos(timing, link::Endpoint::kWriter))
                        .value());
    maps_.emplace(pdds::Writer<grip_msg_MapUpdate>::create(participant_, &grip_msg_MapUpdate_desc,
                                                           topics.map_update,
                                                           link::map_update_qos(timing))
                      .value());
  }
  // A state at the scene's start and, every so often, a snapshot of the map.
  void service() {
    grip_msg_VehicleState state{};
    state.stamp_ns = static_cast<std::uint64_t>(platform::now_ns());
    state.sequence_number = ++sequence_;
    state.kind = grip_msg_DD_VELOCITY;
    state.state[0] = scene_.start_x_m;
    state.state[1] = scene_.start_y_m;
    state.state[2] = scene_.start_theta_rad;
    state.state_dim = 3;
    state.time_scale = 1.0;
    state.incarnation = kIncarnation;
    ASSERT_TRUE(states_->write(state).ok());
    if (sequence_ % 20 == 1) {
      sender_.send_snapshot(state.stamp_ns, [&](const grip_msg_MapUpdate& update) {
        grip_msg_MapUpdate stamped = update;
        stamped.incarnation = kIncarnation;
        ASSERT_TRUE(maps_->write(stamped).ok());
      });
    }
  }

 private:
  static constexpr std::uint64_t kIncarnation = 7;
  Scene scene_;
  pdds::Participant participant_;
  std::optional<pdds::Writer<grip_msg_VehicleState>> states_;
  std::optional<pdds::Writer<grip_msg_MapUpdate>> maps_;
  link::MapSender sender_;
  std::uint64_t sequence_ = 0;
};

TEST(PlannerDescription, AVehicleThatDoesNotDescribeItselfTimesOutStartUpSayingSo) {
  constexpr pdds::DomainId kDomain = 97;
  UndescribedVehicle vehicle(kDomain, ::grip::testing::private_topic("silent"));
  PlannerParticipantConfig config = planner_config(kDomain, 0.0);
  config.topic_prefix = ::grip::testing::private_topic("silent");
  config.startup_timeout = 3s;
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  while (!planner.returned) {
    vehicle.service();
    std::this_thread::sleep_for(10ms);
  }
  const Result<PlannerParticipantReport>& result = planner.join();
  ASSERT_FALSE(result.ok());
  // The map and the state came; only the description is missing.
  EXPECT_EQ(result.error().message,
            "start-up timed out waiting for a vehicle description (the vehicle did not describe "
            "itself)");
}

TEST(PlannerDescription, AVehicleDescribingItselfAnewWithOtherParametersStopsPlanning) {
  constexpr pdds::DomainId kDomain = 98;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  PlannerParticipantConfig config = planner_config(kDomain, 0.0);
  std::mutex warnings_mutex;
  std::vector<std::string> warnings;
  config.on_warning = [&](const std::string& line) {
    const std::lock_guard lock(warnings_mutex);
    warnings.push_back(line);
  };
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  std::size_t plans = 0;
  ASSERT_TRUE(eventually(
      [&] {
        plans += vehicle->link().take_plans([](const grip_msg_Plan&) {});
        return plans >= 5;
      },
      20000ms, vehicle.get()))
      << "the planner never planned for the vehicle it matches";

  // A new incarnation of the vehicle, with a wider axle, says what it is.
  DdVelocityParams wider;
  wider.half_axle_m = 0.3;
  auto participant = pdds::Participant::create(kDomain).value();
  auto description = link::publish_vehicle_description(
      participant, link::TopicNames::create(::grip::testing::private_topic_prefix()).value(),
      link::LinkTiming{}, wider);
  ASSERT_TRUE(description.ok()) << description.error().message;

  plans_until_returned(planner, *vehicle, 5s);
  ASSERT_TRUE(planner.returned) << "planning went on for a vehicle described otherwise";
  const Result<PlannerParticipantReport>& result = planner.join();
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(result.error().message,
            "the vehicle describes itself with vehicle.half_axle_m 0.3, this planner's "
            "parameters say 0.2");
  {
    const std::lock_guard lock(warnings_mutex);
    const std::string warning =
        "the vehicle described itself anew and differs: " + result.error().message +
        "; planning stops";
    EXPECT_EQ(std::count(warnings.begin(), warnings.end(), warning), 1);
  }
  // The planning thread has stopped: no plan comes any more.
  std::this_thread::sleep_for(300ms);
  vehicle->link().take_plans([](const grip_msg_Plan&) {});
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(vehicle->link().take_plans([](const grip_msg_Plan&) {}), 0U);
}

}  // namespace
}  // namespace grip::rt::dds
