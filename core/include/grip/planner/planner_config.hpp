#pragma once
// Parameters of the tree planner: its memory budget, its propagation and GRIP's selection.
// Capacity is decided here, at start-up; the planning loop then allocates nothing.

#include <cstdint>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip {

// How the edge to propagate from is chosen. kGrip is the paper's planner; the others are
// the baselines of its Fig. 5/6, run on the same tree, propagation and rho.
enum class Selection {
  kGrip,     // minimum score s(e) = a^p(e) rho(e, F) from the heap (Eq. 2, 3)
  kRandom,   // a uniformly random edge
  kRrt,      // RRT-EXTEND: the tree state nearest (by rho_A*) to a random free point
  kRrtBias,  // RRT-EXTEND-BIAS: as kRrt, with the goal as the attractor a fraction of the time
};

// Where braking contingencies are checked (the paper's Sec. III-C).
enum class SafetyCheck {
  kAtHorizon,  // only states reached at time T from the root (the paper's theorem)
  kAllLeaves,  // every new leaf must be safe (the Fig. 7 comparison)
  kNone,       // no contingency check (the --no-safety ablation)
};

std::string_view selection_name(Selection s) noexcept;
Result<Selection> selection_from_name(std::string_view name);

struct PlannerConfig {
  Selection selection = Selection::kGrip;
  SafetyCheck safety = SafetyCheck::kAtHorizon;

  // Memory budget. Each propagation uses one trajectory and up to two edge records (the new
  // edge and the head of the split one).
  std::uint32_t max_edges = 40'000;
  std::uint32_t max_trajectories = 20'000;

  // Integration: the dynamics and the chassis are checked every integration step; a state is
  // recorded every `steps_per_record` steps (the states edges are split at and rho is taken
  // over).
  double integration_step_s = 0.05;
  std::uint32_t steps_per_record = 2;

  // Random plans: one control held for a duration uniform in [min, max] (Sec. III-B).
  double min_plan_duration_s = 1.0;
  double max_plan_duration_s = 4.0;
  // New edges shorter than this (t_free below the threshold) are discarded.
  double min_edge_duration_s = 0.1;

  // GRIP's trade-off a > 1 between greed (rho) and the priority counters (Eq. 3).
  double score_base_a = 1.00001;
  // T: the time from the root at which contingencies are checked; in replanning, the
  // duration of the next cycle. Rounded to a whole number of integration steps.
  double safety_horizon_s = 1.0;
  // rho_A* is computed in the configuration space of a disk of this radius: cells closer than
  // this to an obstacle or unknown space are not traversed by the wavefront, so the heuristic
  // leads through passages rather than along walls and around corners a vehicle cannot take.
  // States in such cells have rho = +infinity and are selected last. 0 = the plain grid.
  double rho_clearance_m = 0.3;
  // rho's wavefront runs on cells of at most this size [m] (and half rho_clearance_m): on a
  // finer map, on blocks of its cells (world/distance_field.hpp), so that a whole-map wavefront
  // costs what it costs on a map of this resolution; rho then steps every block rather than
  // every cell. 0: the map's cells.
  double rho_cell_m = 0.1;
  // For a vehicle with a minimum turning radius (the car): rho also counts the turn a state
  // needs to head along its path (planner/turning_rho.hpp). Vehicles that turn in place have
  // rho_A* alone either way.
  bool rho_turning = true;
  // rho below this compares as equal in the score. In log space a metre near the goal would
  // otherwise outweigh hundreds of thousands of priority steps, and the search would keep
  // expanding states that pass the goal region at a speed that cannot turn into it.
  double rho_floor_m = 4.0;
  // The fraction of propagations that apply the braking maneuver instead of a random control.
  // Replanning needs it (near an inevitable collision only braking keeps the state at T safe,
  // and a uniform sample almost never draws it); standalone search does not.
  double braking_control_fraction = 0.0;
  // RRT-EXTEND-BIAS: the fraction of samples that are the goal.
  double rrt_goal_bias = 0.2;

  // Whether solve() returns as soon as a state in the goal region is reached. Replanning and
  // timing runs keep growing the tree.
  bool stop_at_goal = true;
  // Whether solve() goes on when the pools run out, after releasing the worst subtrees to them
  // (as retainment does between cycles): fixed memory must not end a standalone search, whose
  // caller holds no state of the tree across solve(). Replanning leaves it off: the plan it
  // committed before solve() must stay in the tree, and retainment makes room every cycle.
  bool recycle_full_pool = false;

  std::uint64_t seed = 1;

  double record_step_s() const noexcept { return integration_step_s * steps_per_record; }
  // States a trajectory holds at most: the start plus one per record step of the longest plan.
  std::uint32_t states_per_trajectory() const noexcept;

  Status validate() const;
};

// What a vehicle's parameter file tunes of GRIP's search (Sec. III-B, Eq. 3); the rest of
// PlannerConfig follows from the cycle (rt/cycle_sizing.hpp). Checked by PlannerConfig::validate.
struct GripTuning {
  double score_base_a = PlannerConfig{}.score_base_a;
  double min_plan_duration_s = PlannerConfig{}.min_plan_duration_s;
  double max_plan_duration_s = PlannerConfig{}.max_plan_duration_s;
  // rho's space and grain: what a chassis and a map of another size need.
  double rho_clearance_m = PlannerConfig{}.rho_clearance_m;
  double rho_cell_m = PlannerConfig{}.rho_cell_m;

  void apply_to(PlannerConfig& config) const noexcept {
    config.score_base_a = score_base_a;
    config.min_plan_duration_s = min_plan_duration_s;
    config.max_plan_duration_s = max_plan_duration_s;
    config.rho_clearance_m = rho_clearance_m;
    config.rho_cell_m = rho_cell_m;
  }
  bool operator==(const GripTuning&) const = default;
};

}  // namespace grip
