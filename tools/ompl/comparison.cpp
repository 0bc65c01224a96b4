#include "comparison.hpp"

#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/control/PathControl.h>
#include <ompl/util/RandomNumbers.h>
#include <chrono>
#include <cmath>
#include <exception>

#include "adapter.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/scenes/scenes.hpp"
#include "plan_check.hpp"
#include "standalone.hpp"

namespace grip::ompl_bridge {

namespace {

using Clock = std::chrono::steady_clock;

// GRIP's pools: room for this many edges added (memory grows with it: ~1.6 kB per trajectory
// for the 5-dimensional models). Running out ends a run as unsolved, and says so.
constexpr std::uint64_t kGripEdgeCap = 200'000;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void record_check(RunResult& out, const PlanCheck& check) {
  out.verified = check.ok;
  out.failure = check.ok ? "" : "re-check: " + check.failure;
  out.duration_s = check.duration_s;
  out.length_m = check.length_m;
  out.max_fine_deviation_m = check.max_fine_deviation_m;
}

template <VehicleModel V>
void run_grip(const V& vehicle, const Scene& scene, RunResult& out) {
  PlannerConfig config;
  config.seed = out.spec.seed;
  config = tools::config_for_edge_cap(config, kGripEdgeCap);
  // Like OMPL's planners, which grow until the time limit, GRIP is not stopped by its memory.
  config.recycle_full_pool = true;
  auto planner = Planner<V>::create(vehicle, scene.grid, config);
  if (!planner) {
    out.error = planner.error().message;
    return;
  }
  const auto start = vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad);
  const Goal goal = tools::scene_goal(scene);
  if (auto s = planner->set_problem(start, goal); !s) {
    out.error = s.error().message;
    return;
  }
  const auto t0 = Clock::now();
  const auto deadline = t0 + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(out.spec.time_limit_s));
  std::uint32_t calls = 0;
  // The clock is read every 16 iterations, as in `grip bench paper`.
  const auto should_stop = [&]() { return (++calls & 15U) == 0 && Clock::now() >= deadline; };
  const SolveResult result = planner->solve(should_stop);
  out.solve_time_s = seconds_between(t0, Clock::now());

  const PlannerStats& stats = planner->stats();
  // Braking maneuvers step the vehicle too (one check per braking step, one per random-plan
  // step): they count as propagations as well.
  const std::uint64_t braking_steps = stats.collision_checks - stats.propagations;
  out.propagations = stats.propagations + braking_steps;
  out.collision_checks = stats.collision_checks;
  out.tree_size = stats.edges_added;
  out.exact = result.status == SolveStatus::kExactSolution;
  if (!out.exact) {
    out.failure = result.reason == StopReason::kPoolExhausted ? "pool exhausted" : "time limit";
    return;
  }
  BoundedVector<PlanStep> steps(100'000);
  if (!planner->extract_plan(planner->best_state(), steps)) {
    out.failure = "plan longer than 100,000 pieces";
    return;
  }
  const double dt = config.integration_step_s;
  std::vector<PlanPiece> plan;
  std::vector<std::uint32_t> end_records;  // recorded-state index at each piece's end
  std::uint32_t total_steps = 0;
  for (const PlanStep& s : steps) {
    const auto n = static_cast<std::uint32_t>(std::llround(s.duration_s / dt));
    plan.push_back(PlanPiece{s.control, n});
    total_steps += n;
    end_records.push_back(total_steps / config.steps_per_record);
  }
  std::vector<std::array<double, 2>> visited;
  planner->visit_path(planner->best_state(), [&](const typename V::State& q) {
    visited.push_back({state_x(q), state_y(q)});
  });
  std::vector<std::array<double, 2>> claimed;
  for (std::uint32_t r : end_records) {
    claimed.push_back(r < visited.size() ? visited[r] : std::array<double, 2>{NAN, NAN});
  }
  auto fine = make_fine_checker(vehicle, scene.grid, dt);
  if (!fine) {
    out.error = fine.error().message;
    return;
  }
  record_check(out, check_plan(vehicle, *fine, goal, start, plan, dt, claimed));
}

template <VehicleModel V>
void run_ompl(const V& vehicle, const Scene& scene, RunResult& out) {
  // Before anything of OMPL exists: every RNG it creates (planner, samplers) derives from this.
  ::ompl::RNG::setSeed(out.spec.seed);
  const PlannerConfig config;  // the step and control durations GRIP uses
  const double dt = config.integration_step_s;
  auto checker = CollisionChecker::create(scene.grid, vehicle.footprint(),
                                          step_collision_margin_m(vehicle, dt));
  if (!checker) {
    out.error = checker.error().message;
    return;
  }
  const auto start = vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad);
  const Goal goal = tools::scene_goal(scene);
  OmplProblem problem = make_problem(vehicle, *checker, start, goal, settings_for(config));
  if (auto s = set_planner(problem, out.spec.planner); !s) {
    out.error = s.error().message;
    return;
  }
  problem.setup->setup();
  *problem.counters = WorkCounters{};
  const ob::PlannerTerminationCondition ptc =
      ob::timedPlannerTerminationCondition(out.spec.time_limit_s);
  const auto t0 = Clock::now();
  problem.setup->solve(ptc);
  out.solve_time_s = seconds_between(t0, Clock::now());
  out.propagations = problem.counters->propagations;
  out.collision_checks = problem.counters->collision_checks;
  ob::PlannerData data(problem.setup->getSpaceInformation());
  problem.setup->getPlannerData(data);
  out.tree_size = data.numVertices();
  out.exact = problem.setup->haveExactSolutionPath();
  if (!out.exact) {
    out.failure =
        problem.setup->haveSolutionPath() ? "time limit (approximate solution only)" : "time limit";
    return;
  }
  const oc::PathControl& path = problem.setup->getSolutionPath();
  std::vector<PlanPiece> plan;
  std::vector<std::array<double, 2>> claimed;
  for (unsigned i = 0; i < static_cast<unsigned>(path.getControlCount()); ++i) {
    const typename V::Control u = to_core_control<V>(path.getControl(i));
    const auto n = static_cast<std::uint32_t>(std::llround(path.getControlDuration(i) / dt));
    plan.push_back(PlanPiece{{u[0], u[1]}, n});
    const auto& pose = pose_of(path.getState(i + 1));
    claimed.push_back({pose.getX(), pose.getY()});
  }
  auto fine = make_fine_checker(vehicle, scene.grid, dt);
  if (!fine) {
    out.error = fine.error().message;
    return;
  }
  record_check(out, check_plan(vehicle, *fine, goal, start, plan, dt, claimed));
}

}  // namespace

std::vector<std::string> all_planners() {
  std::vector<std::string> names{"grip"};
  for (std::string_view n : kOmplPlanners) names.emplace_back(n);
  return names;
}

RunResult run_one(const RunSpec& spec) {
  RunResult out;
  out.spec = spec;
  auto scene = make_scene(spec.scene);
  if (!scene) {
    out.error = scene.error().message;
    return out;
  }
  auto kind = vehicle_kind_from_name(spec.vehicle);
  if (!kind) {
    out.error = kind.error().message;
    return out;
  }
  try {
    with_default_vehicle(*kind, [&](const auto& vehicle) {
      if (spec.planner == "grip") {
        run_grip(vehicle, *scene, out);
      } else {
        run_ompl(vehicle, *scene, out);
      }
    });
  } catch (const std::exception& e) {  // OMPL reports misuse by throwing
    out.error = e.what();
  }
  return out;
}

nlohmann::json to_json(const RunResult& r) {
  return {{"scene", r.spec.scene},
          {"vehicle", r.spec.vehicle},
          {"planner", r.spec.planner},
          {"seed", r.spec.seed},
          {"time_limit_s", r.spec.time_limit_s},
          {"exact", r.exact},
          {"verified", r.verified},
          {"solve_time_s", r.solve_time_s},
          {"propagations", r.propagations},
          {"collision_checks", r.collision_checks},
          {"tree_size", r.tree_size},
          {"duration_s", r.duration_s},
          {"length_m", r.length_m},
          {"max_fine_deviation_m", r.max_fine_deviation_m},
          {"failure", r.failure},
          {"error", r.error}};
}

RunResult run_result_from_json(const nlohmann::json& j) {
  RunResult r;
  r.spec.scene = j.at("scene");
  r.spec.vehicle = j.at("vehicle");
  r.spec.planner = j.at("planner");
  r.spec.seed = j.at("seed");
  r.spec.time_limit_s = j.at("time_limit_s");
  r.exact = j.at("exact");
  r.verified = j.at("verified");
  r.solve_time_s = j.at("solve_time_s");
  r.propagations = j.at("propagations");
  r.collision_checks = j.at("collision_checks");
  r.tree_size = j.at("tree_size");
  r.duration_s = j.at("duration_s");
  r.length_m = j.at("length_m");
  r.max_fine_deviation_m = j.at("max_fine_deviation_m");
  r.failure = j.at("failure");
  r.error = j.at("error");
  return r;
}

}  // namespace grip::ompl_bridge
