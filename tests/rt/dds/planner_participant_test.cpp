// The planner participant with a vehicle controller over DDS on loopback: plans arrive intact
// and in order; the map heals after dropped updates and ends equal to the mapper's; every kind
// of bad input is rejected and counted; a killed controller is noticed through liveliness.

#include "grip/rt/dds/planner_participant.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "private_topics.hpp"
#include "running_planner.hpp"
#include "test_paths.hpp"
#include "vehicle_side.hpp"

namespace grip::rt::dds {
namespace {

using namespace std::chrono_literals;
using link::testing::VehicleSide;
using testing::eventually;
using testing::planner_config;
using testing::RunningPlanner;
using namespace ::grip::link;

TEST(PlannerParticipant, PlansArriveIntactInOrderAndTheMapHealsAfterDrops) {
  constexpr platform::dds::DomainId kDomain = 70;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  RunningPlanner planner(planner_config(kDomain, 4.0));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;

  // The mapper changes its map while every third update is lost on the way.
  VehicleLink& link = vehicle->link();
  std::uint64_t dropped = 0;
  const auto drop_every_third = [&](const grip_msg_MapUpdate& m) {
    const bool drop = m.snapshot_id == 0 && m.sequence_number % 3 == 0;
    dropped += drop ? 1 : 0;
    return drop;
  };
  std::vector<std::uint64_t> cycles;
  std::vector<std::uint64_t> start_times;
  std::size_t moving_plans = 0;
  std::optional<grip_msg_PlannerStatus> status;
  int tick = 0;
  const auto until = std::chrono::steady_clock::now() + 30s;
  while (!planner.returned && std::chrono::steady_clock::now() < until) {
    vehicle->service();
    if (++tick % 10 == 0 && tick < 300) {
      // An obstacle far from the start appears, or a cell flips: real changes, away from the
      // vehicle so that the start stays free.
      const int x = 200 + (tick / 10) % 80;
      link.map().set(x, 250, (tick / 10) % 2 == 0 ? Cell::kObstacle : Cell::kFree);
      link.publish_map_updates(CellBox{x, 250, x, 250}, static_cast<std::uint64_t>(tick),
                               drop_every_third);
    }
    link.take_plans([&](const grip_msg_Plan& plan) {
      cycles.push_back(plan.cycle);
      start_times.push_back(plan.start_time_ns);
      double duration = 0.0;
      for (std::uint32_t i = 0; i < plan.steps._length; ++i)
        duration += plan.steps._buffer[i].duration_s;
      // A plan covers at least the next cycle, or has no steps: nothing new from its start.
      if (plan.steps._length > 0) {
        EXPECT_GE(duration, 0.05 - 1e-9) << "a plan covers at least the next cycle";
        ++moving_plans;
      }
      EXPECT_EQ(plan.kind, grip_msg_DD_VELOCITY);
    });
    if (auto s = link.take_status()) status = s;
    std::this_thread::sleep_for(10ms);
  }
  const Result<PlannerParticipantReport>& result = planner.join();
  ASSERT_TRUE(result.ok()) << result.error().message;
  const PlannerParticipantReport& report = *result;

  EXPECT_EQ(link.plans_rejected(), 0U);
  ASSERT_GT(cycles.size(), 20U);
  EXPECT_GT(moving_plans, 10U) << "the planner hardly ever found a plan";
  for (std::size_t i = 1; i < cycles.size(); ++i) {
    EXPECT_GT(cycles[i], cycles[i - 1]) << "plans out of order";
    EXPECT_GT(start_times[i], start_times[i - 1]);
  }
  EXPECT_GE(report.plans_published, cycles.size());
  EXPECT_EQ(report.write_failures, 0U);
  // Every written plan's way out was timed (the report may be taken while the publish thread
  // writes the last plan: one either way).
  EXPECT_NEAR(static_cast<double>(report.plan_handoff.count()),
              static_cast<double>(report.plans_published), 1.0);
  EXPECT_EQ(report.plan_write.count(), report.plan_handoff.count());
  EXPECT_GT(report.plan_write.min(), 0) << "a write takes time";

  EXPECT_GT(dropped, 5U);
  EXPECT_GE(report.map_gaps, 1U);
  EXPECT_GE(report.map_heals, 1U);
  EXPECT_EQ(report.map_checksum, map_checksum(link.map())) << "the planner's map diverged";
  ASSERT_TRUE(status.has_value());
  EXPECT_TRUE(status->map_in_sync);
  EXPECT_EQ(status->map_checksum, map_checksum(link.map()));
  EXPECT_TRUE(status->vehicle_alive);
  EXPECT_EQ(status->plan_subscribers, 1U);

  if (report.allocations_counted) {
    EXPECT_EQ(report.heap_allocations_in_loop, 0U) << "the planning thread allocated";
  }
}

TEST(PlannerParticipant, EveryKindOfBadInputIsRejectedAndCounted) {
  constexpr platform::dds::DomainId kDomain = 71;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  RunningPlanner planner(planner_config(kDomain, 0.0));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  VehicleLink& link = vehicle->link();
  std::optional<grip_msg_PlannerStatus> status;
  const auto latest = [&] {
    if (auto s = link.take_status()) status = s;
    return status.has_value();
  };
  ASSERT_TRUE(eventually(latest, 20000ms, vehicle.get())) << "the planner never started";

  // A second writer of each topic, for what VehicleLink would never send.
  auto participant = platform::dds::Participant::create(kDomain).value();
  const LinkTiming timing;
  auto states = platform::dds::Writer<grip_msg_VehicleState>::create(
                    participant, &grip_msg_VehicleState_desc,
                    ::grip::testing::private_topic(kVehicleStateTopic),
                    vehicle_state_qos(timing, Endpoint::kWriter))
                    .value();
  auto maps = platform::dds::Writer<grip_msg_MapUpdate>::create(
                  participant, &grip_msg_MapUpdate_desc,
                  ::grip::testing::private_topic(kMapUpdateTopic), map_update_qos(timing))
                  .value();
  auto goals = platform::dds::Writer<grip_msg_Goal>::create(
                   participant, &grip_msg_Goal_desc, ::grip::testing::private_topic(kGoalTopic),
                   goal_qos(timing))
                   .value();

  // Sends one bad sample and waits until the status counts it: one at a time, so that a
  // keep-last-1 reader cannot lose one behind another.
  const auto rejected = [&](std::uint64_t grip_msg_PlannerStatus::*counter, auto&& send) {
    ASSERT_TRUE(latest());
    const std::uint64_t before = (*status).*counter;
    send();
    EXPECT_TRUE(eventually([&] { return latest() && (*status).*counter == before + 1; }, 5000ms))
        << "not counted";
  };
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const auto bad_state = [&](auto&& mutate, std::optional<dds_time_t> at = std::nullopt) {
    grip_msg_VehicleState msg = vehicle->state();
    msg.stamp_ns += 1'000'000'000;         // newer than any good one so far
    msg.incarnation = link.incarnation();  // the vehicle's own: rejected for what is wrong
    mutate(msg);
    if (at) {
      ASSERT_TRUE(states.write_at(msg, *at).ok());
    } else {
      ASSERT_TRUE(states.write(msg).ok());
    }
  };
  using S = grip_msg_PlannerStatus;
  rejected(&S::rejected_vehicle_state, [&] { bad_state([&](auto& m) { m.state[0] = nan; }); });
  rejected(&S::rejected_vehicle_state, [&] {
    bad_state([](auto& m) {
      const std::int32_t raw = 42;
      std::memcpy(&m.kind, &raw, sizeof raw);
    });
  });
  rejected(&S::rejected_vehicle_state, [&] { bad_state([](auto& m) { m.kind = grip_msg_CAR; }); });
  rejected(&S::rejected_vehicle_state, [&] { bad_state([](auto& m) { m.state_dim = 5; }); });
  rejected(&S::rejected_vehicle_state,
           [&] { bad_state([](auto&) {}, dds_time() + DDS_SECS(60)); });  // from the future
  rejected(&S::rejected_vehicle_state,
           [&] { bad_state([](auto&) {}, dds_time() - DDS_SECS(60)); });  // long ago
  rejected(&S::rejected_vehicle_state, [&] { bad_state([](auto& m) { m.stamp_ns = 1; }); });
  // No incarnation, or another one while the vehicle followed speaks (a second vehicle side).
  rejected(&S::rejected_vehicle_state, [&] { bad_state([](auto& m) { m.incarnation = 0; }); });
  rejected(&S::rejected_vehicle_state,
           [&] { bad_state([](auto& m) { m.incarnation = ~m.incarnation; }); });

  grip_msg_MapUpdate patch{};
  link.map_sender();  // geometry of the real map
  std::vector<std::uint8_t> cells(16, grip_msg_kCellFree);
  const auto bad_patch = [&](auto&& mutate) {
    patch = grip_msg_MapUpdate{};
    patch.sequence_number = 1'000'000;
    const MapGeometry g = geometry_of(link.map());
    patch.map_width_cells = g.width_cells;
    patch.map_height_cells = g.height_cells;
    patch.resolution_m = g.resolution_m;
    patch.map_origin_x_m = g.origin_x_m;
    patch.map_origin_y_m = g.origin_y_m;
    patch.origin_x_cell = 10;
    patch.origin_y_cell = 10;
    patch.width_cells = 4;
    patch.height_cells = 4;
    patch.cells._buffer = cells.data();
    patch.cells._length = 16;
    patch.cells._maximum = 16;
    patch.incarnation = link.incarnation();
    mutate(patch);
    ASSERT_TRUE(maps.write(patch).ok());
  };
  rejected(&S::rejected_map_update, [&] { bad_patch([](auto& m) { m.origin_x_cell = 299; }); });
  rejected(&S::rejected_map_update, [&] { bad_patch([](auto& m) { m.cells._length = 15; }); });
  rejected(&S::rejected_map_update, [&] { bad_patch([](auto& m) { m.resolution_m = nan; }); });
  rejected(&S::rejected_map_update, [&] { bad_patch([](auto& m) { m.map_width_cells = 301; }); });
  rejected(&S::rejected_map_update, [&] { bad_patch([&](auto&) { cells[3] = 7; }); });

  const auto bad_goal = [&](double x, double y, double r) {
    grip_msg_Goal goal{};
    goal.x_m = x;
    goal.y_m = y;
    goal.radius_m = r;
    ASSERT_TRUE(goals.write(goal).ok());
  };
  rejected(&S::rejected_goal, [&] { bad_goal(nan, 5.0, 1.0); });
  rejected(&S::rejected_goal, [&] { bad_goal(5.0, 5.0, -1.0); });
  rejected(&S::rejected_goal, [&] { bad_goal(500.0, 5.0, 1.0); });

  // None of it disturbed the planner: its map still equals the mapper's and it still plans.
  const std::uint64_t cycle = status->cycle;
  EXPECT_TRUE(
      eventually([&] { return latest() && status->cycle > cycle + 5; }, 5000ms, vehicle.get()));
  EXPECT_TRUE(status->map_in_sync);
  EXPECT_EQ(status->map_checksum, map_checksum(link.map()));
  EXPECT_EQ(status->map_gaps, 0U) << "a rejected update is not a gap";
  const Result<PlannerParticipantReport>& result = planner.stop();
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(result->rejected_vehicle_state, 9U);
  EXPECT_EQ(result->rejected_map_update, 5U);
  EXPECT_EQ(result->rejected_goal, 3U);
}

TEST(PlannerParticipant, ALockstepVehicleThatRepeatsAnAnsweredStateGetsItsPlanAgain) {
  // A lockstep vehicle repeats the state it waits on until its plan comes. A plan written before
  // the vehicle's reader matched it (a secured handshake completes endpoint by endpoint) never
  // comes: here the vehicle drops the first one, as if it had not arrived.
  constexpr platform::dds::DomainId kDomain = 74;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  RunningPlanner planner(planner_config(kDomain, 0.0));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  VehicleLink& link = vehicle->link();
  grip_msg_VehicleState waiting = vehicle->state();
  waiting.lockstep = true;
  std::vector<std::uint64_t> cycles;  // of the plans answering `waiting`, as they came
  const auto repeat_until = [&](std::size_t answers) {
    return [&, answers] {
      static_cast<void>(link.publish_state(waiting));
      link.answer_map_requests(waiting.stamp_ns);
      link.take_plans([&](const grip_msg_Plan& plan) {
        EXPECT_EQ(plan.state_sequence, waiting.sequence_number) << "a plan for no state sent";
        cycles.push_back(plan.cycle);
      });
      std::this_thread::sleep_for(240ms);  // the simulator repeats every 250 ms
      return cycles.size() >= answers;
    };
  };
  ASSERT_TRUE(eventually(repeat_until(1), 20000ms)) << "no plan answered the state";
  // WHEN the vehicle goes on repeating the state THEN the same plan comes again
  ASSERT_TRUE(eventually(repeat_until(2), 5000ms)) << "the plan was not written again";
  EXPECT_EQ(cycles[1], cycles[0]);
  const Result<PlannerParticipantReport>& result = planner.stop();
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_GE(result->plans_rewritten, 1U);
  EXPECT_EQ(result->plans_published, 1U) << "planned for the repeat as for a new state";
  EXPECT_EQ(result->rejected_vehicle_state, 0U);
}

TEST(PlannerParticipant, AVehicleBrakingOffItsPlansIsPlannedForFromWhereBrakingTakesIt) {
  // The controller reports that it follows no plan (it brakes on its contingency, say after a
  // plan came late) while moving at 1 m/s: the planner must plan the next cycle from where
  // braking puts the vehicle at that plan's start, not from where its tree says.
  constexpr platform::dds::DomainId kDomain = 73;
  auto vehicle = VehicleSide::create(kDomain, VehicleKind::kDdAcceleration);
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(vehicle->publish_goal());
  PlannerParticipantConfig config = planner_config(kDomain, 0.0);
  config.vehicle = default_vehicle_params(VehicleKind::kDdAcceleration);
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  VehicleLink& link = vehicle->link();
  // First it rests (it executes none of the plans: the planner starts its tree again and again
  // from the resting vehicle).
  std::size_t plans = 0;
  const auto count_plans = [&] {
    link.take_plans([&](const grip_msg_Plan&) { ++plans; });
    vehicle->service();
    return plans >= 5;
  };
  ASSERT_TRUE(eventually(count_plans, 20000ms)) << "no plans came";

  grip_msg_VehicleState braking = vehicle->state();
  braking.state[3] = 1.0;  // both wheels at 1 m/s: driving straight on
  braking.state[4] = 1.0;
  braking.plan_cycle = 0;  // executing no plan
  ASSERT_TRUE(link.publish_state(braking).ok());
  std::optional<grip_msg_Plan> replanned;
  const auto find_replanned = [&] {
    link.take_plans([&](const grip_msg_Plan& plan) {
      if (!replanned && plan.state_sequence == braking.sequence_number) replanned = plan;
    });
    return replanned.has_value();
  };
  ASSERT_TRUE(eventually(find_replanned, 5000ms)) << "no plan answered the braking state";
  const Result<PlannerParticipantReport>& result = planner.stop();
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_GE(result->resyncs, 1U);

  // Braking as the controller does, in ticks of the integration step from the state's stamp
  // (the last one cut short where the plan starts).
  const DdAcceleration model = DdAcceleration::create(DdAccelerationParams{}).value();
  ASSERT_GE(replanned->start_time_ns, braking.stamp_ns);
  constexpr std::uint64_t kStepNs = 50'000'000;
  const std::uint64_t ahead_ns = replanned->start_time_ns - braking.stamp_ns;
  DdAcceleration::State q;
  for (int i = 0; i < 5; ++i) q[i] = braking.state[i];
  for (std::uint64_t i = 0; i < ahead_ns / kStepNs && !model.is_stopped(q); ++i) {
    q = model.brake_step(q, 0.05);
  }
  if (ahead_ns % kStepNs != 0 && !model.is_stopped(q)) {
    q = model.brake_step(q, static_cast<double>(ahead_ns % kStepNs) / 1e9);
  }
  EXPECT_GT(std::hypot(q[0] - braking.state[0], q[1] - braking.state[1]), 0.01)
      << "braking from 1 m/s moves the vehicle on";
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(replanned->start_state[i], q[i], 1e-9) << "state component " << i;
  }
}

TEST(PlannerParticipant, AKilledControllerIsNoticedThroughLiveliness) {
  constexpr platform::dds::DomainId kDomain = 72;
  std::string program = GRIP_BINARY_DIR "/bin/grip_vehicle_controller_probe";
  ASSERT_EQ(access(program.c_str(), X_OK), 0) << program;

  // The planner's status, watched from here.
  auto participant = platform::dds::Participant::create(kDomain).value();
  auto status_reader =
      platform::dds::Reader<grip_msg_PlannerStatus>::create(
          participant, &grip_msg_PlannerStatus_desc,
          ::grip::testing::private_topic(kPlannerStatusTopic), planner_status_qos(LinkTiming{}))
          .value();
  platform::dds::SampleBuffer<grip_msg_PlannerStatus, 4> buffer(&grip_msg_PlannerStatus_desc);
  std::optional<grip_msg_PlannerStatus> status;
  const auto latest = [&] {
    auto taken = status_reader.take(buffer);
    if (taken.ok() && *taken > 0) status = buffer[*taken - 1];
    return status.has_value();
  };

  RunningPlanner planner(planner_config(kDomain, 0.0));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  auto child = grip::testing::ChildProcess::spawn({program, std::to_string(kDomain)});
  ASSERT_TRUE(child.has_value()) << program;

  ASSERT_TRUE(eventually(
      [&] { return latest() && status->vehicle_alive && status->plan_subscribers == 1; }, 20000ms))
      << "the controller process never came up";
  child->kill(SIGKILL);
  const auto killed = std::chrono::steady_clock::now();
  EXPECT_TRUE(eventually(
      [&] { return latest() && !status->vehicle_alive && status->plan_subscribers == 0; }, 5000ms))
      << "the controller's loss went unnoticed";
  const auto noticed = std::chrono::steady_clock::now() - killed;
  // The planner goes on planning on its last map.
  const std::uint64_t cycle = status->cycle;
  EXPECT_TRUE(eventually([&] { return latest() && status->cycle > cycle + 5; }, 5000ms));
  const Result<PlannerParticipantReport>& result = planner.stop();
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(result->vehicle_losses, 1U);
  RecordProperty(
      "loss_noticed_ms",
      std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(noticed).count()));
}

}  // namespace
}  // namespace grip::rt::dds
