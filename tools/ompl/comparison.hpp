#pragma once
// One run of the GRIP-versus-OMPL comparison: a planner, a vehicle, a built-in scene, a seed
// and a time limit, from the scene's start (at rest) to its goal disk. Held equal for every
// planner: the vehicle model and its step, the collision checker and its margin, the goal
// region, the control distribution, the control duration range, the seed, one thread, and the
// timing (setup excluded: only the solve call is timed). Tools only: allocates, may throw.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace grip::ompl_bridge {

// "grip" and the OMPL planners of adapter.hpp.
std::vector<std::string> all_planners();

struct RunSpec {
  std::string scene;    // meandros, labyrinth, rooms
  std::string vehicle;  // dd-vel, dd-accel, car
  std::string planner;  // grip, pdst, kpiece1, sst, rrt, est
  std::uint32_t seed = 1;
  double time_limit_s = 30.0;
};

struct RunResult {
  RunSpec spec;
  bool exact = false;              // the planner reported an exact solution within the limit
  bool verified = false;           // ... and its plan passed check_plan: what counts as solved
  double solve_time_s = 0.0;       // the solve call: time to the first exact solution when exact
  std::uint64_t propagations = 0;  // vehicle.step calls during the solve
  std::uint64_t collision_checks = 0;  // CollisionChecker::is_free calls during the solve
  std::uint64_t tree_size = 0;         // GRIP: edges added; OMPL: vertices of the planner data
  double duration_s = 0.0;             // of the returned plan (verified runs)
  double length_m = 0.0;               // of its reference point, on the fine re-propagation
  double max_fine_deviation_m = 0.0;
  std::string failure;  // why a run is not verified (no solution, or the re-check's reason)
  std::string error;    // a run that could not be set up, or crashed
};

// Runs one spec in this process. OMPL's global seed is set here, before anything of OMPL is
// built, so call it in a fresh process per run to make OMPL runs reproducible (the bench
// forks one per run).
RunResult run_one(const RunSpec& spec);

nlohmann::json to_json(const RunResult& r);
RunResult run_result_from_json(const nlohmann::json& j);

}  // namespace grip::ompl_bridge
