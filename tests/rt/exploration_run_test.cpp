// Exploration end to end without the simulator: a loop plays the sensor (it reveals the
// ground-truth cells within the sensing radius that are in sight through the ground truth),
// chooses the frontier target and the path of section 3 every cycle, runs the replanning cycle
// on a fake clock and drives the vehicle along the committed plan for T. The small room must be
// explored (coverage of the reachable free space) without a collision and in bounded cycles.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "grip/exploration/frontier.hpp"
#include "grip/exploration/path_selector.hpp"
#include "grip/planner/contingency.hpp"
#include "grip/rt/replanning_cycle.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip::rt {
namespace {

struct ExplorationReport {
  bool complete = false;  // the frontier map said kComplete
  int cycles = 0;
  int collisions = 0;      // executed steps whose chassis touched a true obstacle
  int braking_cycles = 0;  // cycles without a plan (the vehicle brakes)
  double coverage = 0.0;   // known cells among the truly free cells reachable from the start
  double distance_m = 0.0;
  double mean_speed_fraction = 0.0;  // distance / (cycles x T x top speed)
};

// Reveals the true value of every cell within radius_m of (x, y) whose centre is in sight: the
// points sampled every quarter cell on the way there lie in truly free cells.
void sense(const OccupancyGrid& truth, OccupancyGrid& map, double x, double y, double radius_m) {
  int rx = 0;
  int ry = 0;
  if (!truth.to_cell(x, y, rx, ry)) return;
  const double res = truth.resolution();
  const int r = static_cast<int>(radius_m / res);
  for (int cy = ry - r; cy <= ry + r; ++cy) {
    for (int cx = rx - r; cx <= rx + r; ++cx) {
      if (!truth.in_bounds(cx, cy) || map.at(cx, cy) != Cell::kUnknown) continue;
      const double tx = truth.cell_center_x(cx);
      const double ty = truth.cell_center_y(cy);
      const double length = std::hypot(tx - x, ty - y);
      if (length > radius_m) continue;
      const int samples = static_cast<int>(length / (0.25 * res));
      bool clear = true;
      for (int i = 1; i < samples && clear; ++i) {
        int sx = 0;
        int sy = 0;
        const double f = static_cast<double>(i) / samples;
        clear = truth.to_cell(x + f * (tx - x), y + f * (ty - y), sx, sy) &&
                ((sx == cx && sy == cy) || truth.at(sx, sy) == Cell::kFree);
      }
      if (clear) map.set(cx, cy, truth.at(cx, cy));
    }
  }
}

template <VehicleModel V>
ExplorationReport explore(const V& vehicle, const OccupancyGrid& truth, double start_x,
                          double start_y, double start_theta, int max_cycles) {
  ExplorationReport report;
  OccupancyGrid map = OccupancyGrid::create(truth.width(), truth.height(), truth.resolution(),
                                            truth.origin_x(), truth.origin_y(), Cell::kUnknown)
                          .value();
  const double sensing_m = truth.width_m() / 10.0;  // the paper's sensor
  // The start is seen, and the chassis' own footprint is known free (the vehicle stands there).
  map.fill_rect(start_x - 0.7, start_y - 0.7, start_x + 0.7, start_y + 0.7, Cell::kFree);
  sense(truth, map, start_x, start_y, sensing_m);

  CycleConfig config;
  config.cycle_s = 0.1;
  config.safety_margin_ns = 2'000'000;
  PlannerConfig planner_config;
  planner_config.max_edges = 20'000;
  planner_config.max_trajectories = 10'000;
  auto cycle = ReplanningCycle<V>::create(vehicle, map, planner_config, config).value();
  FrontierConfig frontier_config;
  frontier_config.clearance_m = planner_config.rho_clearance_m;
  auto frontiers =
      FrontierMap::create(map.width(), map.height(), map.resolution(), frontier_config).value();
  PathSelectionConfig selection;
  selection.sensing_radius_m = sensing_m;
  auto selector = PathSelector::create(map.width(), map.height(), map.resolution(),
                                       planner_config.max_edges, selection)
                      .value();
  auto clearance = ClearanceMap::create(map.width(), map.height(), map.resolution()).value();
  const CollisionChecker truth_checker =
      CollisionChecker::create(truth, vehicle.footprint(), 0.0).value();

  const typename V::State start = vehicle.rest_state(start_x, start_y, start_theta);
  EXPECT_TRUE(cycle.start(start, GoalRegion{start_x, start_y, 1.0}));
  std::int64_t now = 0;
  const double dt = planner_config.integration_step_s;
  const auto steps_per_cycle = static_cast<int>(std::lround(config.cycle_s / dt));
  for (; report.cycles < max_cycles; ++report.cycles) {
    // The vehicle is at the root of the tree: where this cycle's plan starts.
    const typename V::State here = cycle.plan_start();
    sense(truth, map, here[0], here[1], sensing_m);
    clearance.compute(map);
    if (frontiers.update(map, clearance, here[0], here[1]) != ExplorationStatus::kTarget) {
      report.complete = frontiers.status() == ExplorationStatus::kComplete;
      break;
    }
    cycle.set_goal(GoalCells{frontiers.approach_cells()});
    selector.set_target(map, frontiers.target_cells());
    // Map updates only turn unknown cells into known ones: nothing free becomes blocked.
    cycle.note_newly_blocked(CellBox{});
    const std::int64_t release = now;
    const CycleOutcome out = cycle.run([&now] { return now += 20'000; }, release + 25'000'000,
                                       [&](const Planner<V>& planner) {
                                         return selector.select(planner, cycle.cycle_steps()).state;
                                       });
    now = release + 25'000'000;
    // Execute the next T: along the committed plan, or braking.
    typename V::State q = cycle.plan_start();
    int left = steps_per_cycle;
    if (out.plan_available) {
      for (const PlanStep& step : cycle.plan()) {
        const typename V::Control u(step.control[0], step.control[1]);
        for (long i = 0; i < std::lround(step.duration_s / dt) && left > 0; ++i, --left) {
          const typename V::State next = vehicle.step(q, u, dt);
          report.distance_m += std::hypot(next[0] - q[0], next[1] - q[1]);
          q = next;
          if (!truth_checker.is_free(q[0], q[1], q[2])) ++report.collisions;
        }
      }
    } else {
      ++report.braking_cycles;
    }
    for (; left > 0; --left) {
      const typename V::State next = vehicle.brake_step(q, dt);
      report.distance_m += std::hypot(next[0] - q[0], next[1] - q[1]);
      q = next;
      if (!truth_checker.is_free(q[0], q[1], q[2])) ++report.collisions;
    }
  }
  // Coverage of the free space reachable from the start (8-connected, any width).
  auto reach = DistanceField::create(truth.width(), truth.height(), truth.resolution()).value();
  int sx = 0;
  int sy = 0;
  EXPECT_TRUE(truth.to_cell(start_x, start_y, sx, sy));
  const std::uint32_t start_cell[] = {truth.index(sx, sy)};
  reach.compute(truth, start_cell);
  double reachable = 0;
  double known = 0;
  for (std::uint32_t c = 0; c < truth.cell_count(); ++c) {
    if (!reach.reachable(c)) continue;
    ++reachable;
    if (map.at(c) != Cell::kUnknown) ++known;
  }
  report.coverage = known / reachable;
  report.mean_speed_fraction =
      report.distance_m / (report.cycles * config.cycle_s * vehicle.max_speed_m_s());
  return report;
}

void print(const char* scene, const char* vehicle, const ExplorationReport& r) {
  std::printf(
      "%-10s %-16s complete=%d cycles=%d coverage=%.4f collisions=%d braking=%d "
      "distance=%.1f m mean_speed_fraction=%.3f\n",
      scene, vehicle, r.complete ? 1 : 0, r.cycles, r.coverage, r.collisions, r.braking_cycles,
      r.distance_m, r.mean_speed_fraction);
}

// A 12 m room split by a wall from x = 6 up to y = 8, and a pillar.
OccupancyGrid small_scene() {
  OccupancyGrid grid = OccupancyGrid::create(120, 120, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.3, 0.3, 11.7, 11.7, Cell::kFree);
  grid.fill_rect(5.85, 0.0, 6.15, 8.0, Cell::kObstacle);
  grid.fill_rect(2.5, 6.5, 3.5, 7.5, Cell::kObstacle);
  return grid;
}

TEST(ExplorationRun, AVelocityControlledRobotExploresASmallSceneWithoutCollision) {
  const OccupancyGrid truth = small_scene();
  const DdVelocity robot = DdVelocity::create({}).value();
  const ExplorationReport r = explore(robot, truth, 1.5, 1.5, 0.0, 3000);
  print("small", "dd-velocity", r);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.collisions, 0);
  EXPECT_GE(r.coverage, 0.97);
}

}  // namespace
}  // namespace grip::rt
