// Peers restart cleanly and the vehicle has one plan source (idl/README.md, "Incarnations"):
// a simulator restarted under a running planner is explored for again, a planner restarted
// under a running simulator resumes, and a standby planner takes over when the active one dies.
// Each run is a lockstep exploration of a small room by the simulator participant.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "grip/planner/step_margin.hpp"
#include "grip/sim/map_file.hpp"
#include "grip/sim/sim_participant.hpp"
#include "grip/sim/start_pose.hpp"
#include "grip/vehicles/dd_velocity.hpp"
#include "running_planner.hpp"
#include "vehicle_side.hpp"

namespace grip::rt::dds {
namespace {

using namespace std::chrono_literals;
using testing::eventually;
using testing::planner_config;
using testing::RunningPlanner;

// The 8 m x 8 m room with a pillar and a wall that the explore command's tests explore.
struct Room {
  OccupancyGrid truth;
  sim::StartPose start;
};

constexpr const char* kSmallRoom =
    "type octile\nheight 10\nwidth 10\nmap\n"
    "@@@@@@@@@@\n@........@\n@........@\n@...@@...@\n@...@@...@\n"
    "@........@\n@.@@@@@..@\n@........@\n@........@\n@@@@@@@@@@\n";
// Two of those side by side with a door: long enough to explore that a standby planner is up
// before it ends.
constexpr const char* kTwoRooms =
    "type octile\nheight 10\nwidth 19\nmap\n"
    "@@@@@@@@@@@@@@@@@@@\n@........@........@\n"
    "@........@........@\n@...@@...@...@@...@\n"
    "@...@@.......@@...@\n@.................@\n"
    "@.@@@@@..@.@@@@@..@\n@........@........@\n"
    "@........@........@\n@@@@@@@@@@@@@@@@@@@\n";

Room small_room(const VehicleParams& params, const char* map = kSmallRoom) {
  auto loaded = sim::parse_movingai_map(map, "room");
  EXPECT_TRUE(loaded.ok()) << loaded.error().message;
  const auto vehicle = DdVelocity::create(std::get<DdVelocityParams>(params)).value();
  const double margin = step_collision_margin_m(vehicle, integration_step_for_cycle(0.05));
  const sim::StartPose start = sim::choose_start(*loaded, vehicle.footprint(), margin).value();
  return Room{std::move(loaded->grid), start};
}

sim::SimRunConfig lockstep_sim(platform::dds::DomainId domain, const VehicleParams& vehicle,
                               const Room& room) {
  sim::SimRunConfig config;
  config.domain = domain;
  config.topic_prefix = ::grip::testing::private_topic_prefix();
  config.vehicle = vehicle;
  config.world = "small room";
  config.start_x_m = room.start.x_m;
  config.start_y_m = room.start.y_m;
  config.start_theta_rad = room.start.theta_rad;
  config.lockstep = true;
  config.max_sim_time_s = 300.0;
  config.planner_wait = 60s;
  return config;
}

PlannerParticipantConfig exploring_planner(platform::dds::DomainId domain, std::uint64_t seed) {
  PlannerParticipantConfig config = planner_config(domain, 0.0);
  config.startup_timeout = 60s;
  config.seed = seed;
  config.on_warning = [](const std::string&) {};  // the rejections are expected here
  return config;
}

void expect_complete(const Result<sim::SimRunReport>& run, const char* which) {
  ASSERT_TRUE(run.ok()) << which << ": " << run.error().message;
  EXPECT_EQ(run->result, "complete") << which << ": " << run->reason;
  EXPECT_GE(run->coverage, sim::kCompleteCoverage) << which;
  EXPECT_GT(run->distance_m, 1.0) << which;
  EXPECT_EQ(run->collisions, 0U) << which;
}

TEST(PlannerRestart, ASimulatorRestartedUnderARunningPlannerIsExploredAgain) {
  constexpr platform::dds::DomainId kDomain = 180;
  const VehicleParams vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
  const Room room = small_room(vehicle);
  RunningPlanner planner(exploring_planner(kDomain, 3));
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  const std::atomic<bool> stop{false};

  // GIVEN a first simulator explored to the end, WHEN a second one starts in its place, THEN
  // the planner forgets the first (stamps, map, mode) and explores for the second to the end.
  const auto first = sim::run_simulation(lockstep_sim(kDomain, vehicle, room), room.truth, stop);
  expect_complete(first, "first simulator");
  const auto second = sim::run_simulation(lockstep_sim(kDomain, vehicle, room), room.truth, stop);
  expect_complete(second, "restarted simulator");
  ASSERT_TRUE(second.ok());
  ASSERT_TRUE(second->last_status.has_value());
  EXPECT_EQ(second->last_status->vehicle_restarts, 1U);
  EXPECT_FALSE(planner.returned.load()) << "the planner stopped";
  const auto& report = planner.stop();
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_EQ(report->vehicle_restarts, 1U);
}

// The simulator, on a thread of its own, and how far its planner got.
struct RunningSim {
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> planner_cycle{0};
  std::optional<Result<sim::SimRunReport>> result;
  std::thread thread;

  RunningSim(const sim::SimRunConfig& config, const OccupancyGrid& truth) {
    thread = std::thread([this, config, &truth] {
      result = sim::run_simulation(config, truth, stop, [this](const sim::SimProgress& p) {
        planner_cycle.store(p.planner_cycle);
      });
    });
  }
  const Result<sim::SimRunReport>& join() {
    if (thread.joinable()) thread.join();
    return *result;
  }
  ~RunningSim() {
    stop.store(true);
    if (thread.joinable()) thread.join();
  }
};

TEST(PlannerRestart, APlannerRestartedUnderARunningSimulatorResumesAndTheExplorationCompletes) {
  constexpr platform::dds::DomainId kDomain = 181;
  const VehicleParams vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
  const Room room = small_room(vehicle);
  RunningSim sim(lockstep_sim(kDomain, vehicle, room), room.truth);
  {
    RunningPlanner first(exploring_planner(kDomain, 3));
    ASSERT_NE(first.planner, nullptr) << first.result->error().message;
    ASSERT_TRUE(eventually([&] { return sim.planner_cycle.load() > 30; }, 60000ms))
        << "the first planner never got going";
  }  // killed: gone from DDS without a word
  RunningPlanner second(exploring_planner(kDomain, 4));
  ASSERT_NE(second.planner, nullptr) << second.result->error().message;
  expect_complete(sim.join(), "simulator under a restarted planner");
}

TEST(PlannerRestart, AStandbyPlannerIsNotFollowedUntilTheActiveOneDiesThenTakesOver) {
  constexpr platform::dds::DomainId kDomain = 182;
  const VehicleParams vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
  const Room room = small_room(vehicle, kTwoRooms);
  auto active = std::make_unique<RunningPlanner>(exploring_planner(kDomain, 3));
  ASSERT_NE(active->planner, nullptr) << active->result->error().message;
  RunningSim sim(lockstep_sim(kDomain, vehicle, room), room.truth);
  ASSERT_TRUE(eventually([&] { return sim.planner_cycle.load() > 5; }, 60000ms))
      << "the active planner never got going";
  // The standby plans all along: its plans are rejected, counted, never executed.
  std::atomic<bool> standby_ready{false};
  PlannerParticipantConfig standby_config = exploring_planner(kDomain, 4);
  standby_config.on_ready = [&](const std::string&) { standby_ready.store(true); };
  RunningPlanner standby(standby_config);
  ASSERT_NE(standby.planner, nullptr) << standby.result->error().message;
  ASSERT_TRUE(eventually([&] { return standby_ready.load(); }, 60000ms));
  const std::uint64_t before = sim.planner_cycle.load();
  ASSERT_TRUE(eventually([&] { return sim.planner_cycle.load() > before + 10; }, 60000ms));
  active.reset();  // killed
  const Result<sim::SimRunReport>& run = sim.join();
  expect_complete(run, "simulator after failover");
  ASSERT_TRUE(run.ok());
  EXPECT_GT(run->plans_from_other_planner, 0U) << "the standby's plans were never rejected";
  EXPECT_EQ(run->planner_failovers, 1U);
}

// A vehicle side replaced while it stands still sends its map only when asked: the snapshot
// may reach the planner before its new planning side exists, and must still reach that side.
TEST(PlannerRestart, AVehicleReplacedAtRestGetsItsMapHandedOverAndIsPlannedForAgain) {
  constexpr platform::dds::DomainId kDomain = 187;
  std::atomic<int> ready{0};
  PlannerParticipantConfig config = planner_config(kDomain, 0.0);
  config.on_warning = [](const std::string&) {};
  config.on_ready = [&](const std::string&) { ready.fetch_add(1); };
  RunningPlanner planner(config);
  ASSERT_NE(planner.planner, nullptr) << planner.result->error().message;
  for (int start = 1; start <= 3; ++start) {
    auto vehicle = link::testing::VehicleSide::create(kDomain, VehicleKind::kDdVelocity);
    ASSERT_NE(vehicle, nullptr);
    ASSERT_TRUE(vehicle->publish_goal());
    ASSERT_TRUE(eventually([&] { return ready.load() == start; }, 30000ms, vehicle.get()))
        << "vehicle side " << start << " was not planned for (" << ready.load() << " start-ups)";
  }
  EXPECT_FALSE(planner.returned.load()) << "the planner stopped";
}

}  // namespace
}  // namespace grip::rt::dds
