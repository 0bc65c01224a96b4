// Exploration end to end without the transport: a loop plays the sensor (it reveals the
// ground-truth cells within the sensing radius that are in sight through the ground truth) and
// the vehicle's controller (sim::PlanExecutor, as `grip sim` in lockstep), and the planner is the
// replanning session with the exploration driver, as the planner participant runs them. The small
// room must be explored (coverage of the reachable free space) without a collision and in bounded
// cycles.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <thread>

#include "grip/rt/exploration_driver.hpp"
#include "grip/rt/replanning_session.hpp"
#include "grip/sim/plan_executor.hpp"
#include "grip/vehicles/car.hpp"
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
  double slowest_m_s = 0.0;          // the most negative forward speed seen (reversing)
};

// Reveals the true value of every cell within radius_m of (x, y) whose centre is in sight: the
// points sampled every quarter cell on the way there lie in truly free cells.
void sense(const OccupancyGrid& truth, OccupancyGrid& map, double x, double y, double radius_m,
           MapChanges& changes) {
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
      if (clear) changes.apply(map, CellBox{cx, cy, cx, cy}, truth.at(cx, cy));
    }
  }
}

// With `target_thread`, a thread beside the loop chooses the targets requested, as the planner
// participant's target thread does; without, the loop's own update() chooses them.
template <VehicleModel V>
ExplorationReport explore(const V& vehicle, const OccupancyGrid& truth, double start_x,
                          double start_y, double start_theta, int max_cycles,
                          bool target_thread = false) {
  ExplorationReport report;
  OccupancyGrid unknown = OccupancyGrid::create(truth.width(), truth.height(), truth.resolution(),
                                                truth.origin_x(), truth.origin_y(), Cell::kUnknown)
                              .value();
  const double sensing_m = truth.width_m() / 10.0;  // the paper's sensor
  // The start is seen, and the chassis' own footprint is known free (the vehicle stands there).
  unknown.fill_rect(start_x - 0.7, start_y - 0.7, start_x + 0.7, start_y + 0.7, Cell::kFree);
  MapChanges first_sweep;
  sense(truth, unknown, start_x, start_y, sensing_m, first_sweep);

  SessionConfig config;
  config.cycle_s = 0.1;
  config.lockstep_edges = 1000;
  auto session = ReplanningSession<V>::create(vehicle, std::move(unknown), config).value();
  OccupancyGrid& map = session.grid();
  if (Status s = session.create_cycle(1.0, /*lockstep=*/true, /*explore=*/true); !s) {
    ADD_FAILURE() << s.error().message;
    return report;
  }
  ExplorationDriverConfig exploration;
  exploration.refresh_cycles = 1;
  exploration.path_weight.sensing_radius_m = sensing_m;
  auto driver =
      ExplorationDriver<V>::create(vehicle, map, exploration, session.sizing().planner).value();

  std::atomic<bool> stop{false};
  std::thread chooser;
  if (target_thread) {
    chooser = std::thread([&driver, &stop] {
      while (!stop.load(std::memory_order_acquire)) {
        if (!driver.serve_request()) std::this_thread::yield();
      }
    });
  }
  struct Join {
    std::atomic<bool>& stop;
    std::thread& thread;
    ~Join() {
      stop.store(true, std::memory_order_release);
      if (thread.joinable()) thread.join();
    }
  } join{stop, chooser};

  const typename V::State start = vehicle.rest_state(start_x, start_y, start_theta);
  sim::ExecutorConfig executor_config;
  executor_config.step_s = session.sizing().planner.integration_step_s;
  executor_config.refuse_start_mismatch = true;
  auto executor = sim::PlanExecutor<V>::create(vehicle, truth, start, 0, executor_config).value();
  VehicleSample sample;
  sample.lockstep = true;
  const auto measure = [&] {
    for (int i = 0; i < V::kStateDim; ++i) {
      sample.state[static_cast<std::size_t>(i)] = executor.state()[i];
    }
    sample.stamp_ns = static_cast<std::uint64_t>(executor.now_ns());
    ++sample.sequence_number;
    sample.plan_cycle = executor.executing_tag();
  };
  measure();
  EXPECT_TRUE(session.start(sample, Goal::disk(start_x, start_y, 1.0)));
  std::int64_t clock = 0;  // times the phases only: lockstep grows by edge count
  const auto now = [&clock] { return clock += 20'000; };
  const auto cycle_ns = static_cast<std::int64_t>(std::llround(config.cycle_s * 1e9));
  for (; report.cycles < max_cycles; ++report.cycles) {
    MapChanges changes;
    if (report.cycles > 0) {
      measure();
      sense(truth, map, sample.state[0], sample.state[1], sensing_m, changes);
    }
    session.note_state(sample);
    session.set_plan_start_after(sample);
    session.check_vehicle_follows();
    session.note_map_changes(changes);
    driver.update(session.cycle(), map, session.plan_start_ns(), changes, true);
    if (driver.explored()) {
      report.complete = true;
      break;
    }
    const CycleOutcome out = session.run(
        now, 0,
        [&](const Planner<V>& planner) {
          return driver.choose_plan_end(planner, session.cycle().cycle_steps(),
                                        session.cycle().committed());
        },
        [] {});
    const SentPlan<V> sent = session.send_plan(out);
    const auto start_ns = static_cast<std::int64_t>(sent.start_ns);
    if (sent.steps.empty()) {
      ++report.braking_cycles;
      executor.submit_empty(start_ns);
    } else {
      executor.submit(sent.steps, start_ns, sent.from, sent.cycle);
    }
    executor.run_until(executor.now_ns() + cycle_ns);
    if constexpr (V::kKind == VehicleKind::kCar) {
      report.slowest_m_s = std::min(report.slowest_m_s, executor.state()[3]);
    }
  }
  report.collisions = static_cast<int>(executor.stats().collisions);
  report.distance_m = executor.stats().distance_m;
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
  report.mean_speed_fraction = executor.mean_speed_fraction();
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

// Lockstep reproduces a run whichever thread chooses the targets: the last cycle before the next
// request takes the choice over, made by the target thread beside it or, not begun there, by
// itself.
TEST(ExplorationRun, ATargetThreadBesideTheLoopChangesNothingInLockstep) {
  const OccupancyGrid truth = small_scene();
  const DdVelocity robot = DdVelocity::create({}).value();
  const ExplorationReport alone = explore(robot, truth, 1.5, 1.5, 0.0, 300);
  const ExplorationReport beside = explore(robot, truth, 1.5, 1.5, 0.0, 300, true);
  ASSERT_GT(alone.distance_m, 5.0);
  EXPECT_EQ(beside.cycles, alone.cycles);
  EXPECT_EQ(beside.distance_m, alone.distance_m);
  EXPECT_EQ(beside.coverage, alone.coverage);
  EXPECT_EQ(beside.braking_cycles, alone.braking_cycles);
}

// A room (x < 5 m) and, off it, a corridor 1.4 m wide and 8.7 m long ending in a wall.
OccupancyGrid dead_end_scene() {
  OccupancyGrid grid = OccupancyGrid::create(140, 60, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.3, 0.3, 5.0, 5.7, Cell::kFree);
  grid.fill_rect(5.0, 2.3, 13.7, 3.7, Cell::kFree);
  return grid;
}

TEST(ExplorationRun, ACarFacingTheEndOfACorridorTooNarrowToTurnInGetsOutAndExplores) {
  // The car stands 0.6 m from the corridor's end, facing it. Turning round needs about 1.8 m
  // (the front corner's circle at full lock, 0.9 m in radius, beside the rear corner's): it
  // must reverse, whether to turn in several moves or to back out.
  const OccupancyGrid truth = dead_end_scene();
  const Car car = Car::create({}).value();
  const ExplorationReport r = explore(car, truth, 12.5, 3.0, 0.0, 6000);
  print("dead-end", "car", r);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.collisions, 0);
  EXPECT_GE(r.coverage, 0.97);
  EXPECT_LT(r.slowest_m_s, -0.1) << "the car never reversed";
}

}  // namespace
}  // namespace grip::rt
