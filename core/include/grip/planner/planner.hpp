#pragma once
// The tree planner: GRIP's selection and propagation (the paper's Sec. III-B, Algorithm 1's main
// loop) with safety at low cost (Sec. III-C), and the baselines of the paper's Fig. 5/6 on
// the same tree, propagation and rho. Its parts in their own units: F on the grid
// (target_set.hpp), tree retainment at the start of a cycle (retainment.hpp) and the baselines'
// selection (baseline_selection.hpp).
//
// Reads like OMPL's planners: set a problem, then solve(termination condition) returns a
// status. Everything is reserved by create(); solve() allocates nothing, never blocks and
// never throws. When the pools run out it stops growing, says so, and keeps its best answer,
// or, when configured to, releases its worst subtrees and goes on.

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "grip/common/function_ref.hpp"
#include "grip/common/random.hpp"
#include "grip/common/result.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/memory/indexed_min_heap.hpp"
#include "grip/planner/baseline_selection.hpp"
#include "grip/planner/contingency.hpp"
#include "grip/planner/goal.hpp"
#include "grip/planner/plan_step.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/planner/planner_status.hpp"
#include "grip/planner/retainment.hpp"
#include "grip/planner/step_margin.hpp"
#include "grip/planner/target_set.hpp"
#include "grip/planner/tree.hpp"
#include "grip/planner/tree_state.hpp"
#include "grip/planner/turning_rho.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"
#include "grip/world/collision_checker.hpp"
#include "grip/world/distance_field.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

// Work counters, cumulative since the last set_problem().
struct PlannerStats {
  std::uint64_t iterations = 0;    // selections made
  std::uint64_t edges_added = 0;   // new edges (the paper's "edges added" metric)
  std::uint64_t propagations = 0;  // integration steps of random plans
  std::uint64_t collision_checks = 0;
  std::uint64_t contingency_checks = 0;  // braking maneuvers run
  bool pool_exhausted = false;           // the pools ran out at least once
  std::uint64_t pool_recycles = 0;       // and were recycled (PlannerConfig::recycle_full_pool)
};

// Whether a retainment recomputes rho toward F (a whole-map wavefront) or keeps the field of
// the previous call. kKeep is for a caller that passes the same F as last time and accepts rho
// computed on an older map: rho only orders the search, collisions are always checked on the
// current map.
enum class RhoUpdate { kRecompute, kKeep };

template <VehicleModel V>
class Planner {
 public:
  using State = typename V::State;
  using Control = typename V::Control;

  // Reserves every buffer for the configured budget. The grid must outlive the planner.
  static Result<Planner> create(const V& vehicle, const OccupancyGrid& grid,
                                const PlannerConfig& config);

  // Start-up: validates start and goal, computes rho's wavefront from the goal, resets the
  // tree to the start. Refuses NaN or out-of-limit states, a start in collision, a goal
  // outside the grid (for cells: an index >= cell_count()) or with no free cell. A cells
  // goal's span is read during the call only, here and in every call below.
  Status set_problem(const State& start, const Goal& goal);

  // Replanning (Algorithm 1, first half; allocation-free). Re-roots the tree at `new_root`,
  // the state the vehicle will be in when the next plan starts, and returns everything not
  // below it to the pools; prunes what the current grid invalidates (the grid may have changed
  // since the last call) and what cannot brake safely from the state reached at `horizon_s`
  // (T, the next cycle's duration; rounded to integration steps); once a path reaches the goal
  // keeps only paths that do; resets priorities (children of the root 1, then Eq. 2 down the
  // tree), recomputes rho against `goal` and rebuilds the heap. On an error the tree is as it
  // was. Needs steps_per_record == 1 so that every checked state is a recorded one.
  // Only cells that became non-free can invalidate an edge: when the caller knows where that
  // happened since the last call (`newly_blocked`, e.g. the union of a cycle's map updates),
  // only states within the chassis' reach of it are checked again; without it, every state is
  // when the grid changed at all.
  RetainStatus retain(TreeState new_root, const Goal& goal, double horizon_s,
                      const CellBox* newly_blocked = nullptr,
                      RhoUpdate rho = RhoUpdate::kRecompute) noexcept;
  // Starts a fresh tree at q (when q is not on the tree), allocation-free. Unlike
  // set_problem(), the random stream and the work counters go on: restarting in the same
  // state must not replay the samples that failed there. RhoUpdate as for retain(); the
  // first call after create() always computes rho.
  RetainStatus restart(const State& q, const Goal& goal, double horizon_s,
                       RhoUpdate rho = RhoUpdate::kRecompute) noexcept;
  const RetainStats& last_retain() const noexcept { return retainment_.last(); }
  // F as a set of cells with rho toward it computed elsewhere (beside the planning thread, on
  // a copy of the map: ExplorationTarget), so that no whole-map wavefront runs here: F becomes
  // `goal` and rho_field() becomes `rho`, which receives the previous field in exchange (no
  // copy). `rho` must be a field of this grid's size and rho_field()'s block computed toward
  // these cells with inflation rho_clearance_m; rho only orders the search, so one computed on
  // a map a cycle older will do. The next retain() or restart() with RhoUpdate::kKeep plans
  // toward it. Errors as for retain(), and kGoalNotCells for a disk (rho toward a disk is
  // computed here, by retain() or restart()); on an error nothing changes.
  RetainStatus adopt_goal(const Goal& goal, DistanceField& rho) noexcept;
  // Where cells changed between free and non-free since the last retain() or restart(), when
  // the caller knows (e.g. a cycle's map updates): the collision checker's clearance is then
  // refreshed only near them (ClearanceMap::update) rather than over the whole map. Notes add
  // up until the next retain() or restart(); without any, a changed grid is refreshed whole.
  void note_changed(const CellBox& box) noexcept {
    changed_.add(box);
    changed_noted_ = true;
  }

  // Grows the tree until the goal is reached, should_stop() returns true (checked once per
  // iteration), or the pools are exhausted.
  SolveResult solve(FunctionRef<bool()> should_stop) noexcept;

  bool solved() const noexcept { return solution_.edge != kNoHandle; }
  // Whether s (possibly from before splits) is a state of the current tree.
  bool contains(TreeState s) const noexcept;
  // The root: the state the tree grows from (the vehicle's state when the plan starts).
  TreeState root_state() const noexcept {
    return TreeState{tree_.root(), tree_.edge(tree_.root()).last};
  }
  // The solution if solved, else the state with the best estimated arrival: rho plus the time
  // from the root at a quarter of top speed (a plan should head to F and be short, Sec. II),
  // so that a meandering path that ends slightly closer does not win.
  TreeState best_state() const noexcept;
  double best_rho_m() const noexcept { return best_rho_; }

  // The state reached `step` integration steps from the root on the path to s, or an empty
  // TreeState when the path is shorter. With steps_per_record == 1 every step is recorded.
  TreeState state_at_step(TreeState s, std::uint32_t step) const noexcept;
  // Lazy safety for the plan about to be committed (Sec. III-C): the latest state on the path
  // to `target`, at `min_step` or later, whose braking contingency is collision-free (any such
  // state with SafetyCheck::kNone), or an empty TreeState when there is none.
  TreeState committable_state(TreeState target, std::uint32_t min_step) noexcept;
  // Writes the plan from the root to s into `out`; false if it does not fit.
  bool extract_plan(TreeState s, VectorView<PlanStep>& out) const noexcept;
  // Calls visit(state) for every recorded state from the root to s, in order (allocates).
  template <typename Visitor>
  void visit_path(TreeState s, Visitor&& visit) const;
  // Calls visit(edge handle, edge) for every edge in the tree.
  template <typename Visitor>
  void visit_edges(Visitor&& visit) const;

  // ln s(e) = p(e) ln a + ln rho(e, F) (Eq. 3 in log space; a^p overflows for real p).
  double log_score(EdgeHandle e) const noexcept { return score(tree_.edge(e)); }
  // The edge GRIP selects next (the heap's minimum), for tests and diagnostics.
  EdgeHandle peek_selection() const noexcept { return heap_.empty() ? kNoHandle : heap_.top(); }
  std::uint32_t heap_size() const noexcept { return static_cast<std::uint32_t>(heap_.size()); }

  const PlannerStats& stats() const noexcept { return stats_; }
  const Tree<State>& tree() const noexcept { return tree_; }
  const PlannerConfig& config() const noexcept { return config_; }
  const V& vehicle() const noexcept { return vehicle_; }
  const CollisionChecker& checker() const noexcept { return checker_; }
  const DistanceField& rho_field() const noexcept { return rho_field_; }
  // [m] rho(q, F): rho_A* from rho_field(), and for a vehicle with a turning radius the turn
  // q needs (PlannerConfig::rho_turning). Scores, the best state and path selection use it.
  double rho_m(const State& q) const noexcept {
    if (turning_rho_) {
      return turning_rho_->at(rho_field_, state_x(q), state_y(q), state_theta(q));
    }
    return rho_a_star_m(q);
  }
  // [m] rho_A* at q alone: a lower bound of rho_m(q), at the cost of one lookup.
  double rho_a_star_m(const State& q) const noexcept {
    return rho_field_.distance_m(state_x(q), state_y(q));
  }
  double collision_margin_m() const noexcept { return checker_.margin(); }
  // Whether the chassis at q is free as the planner checks it: grown by the margin of q's own
  // speed (state_collision_margin_m), at most collision_margin_m().
  bool chassis_free(const State& q) const noexcept {
    return chassis_free_at(vehicle_, checker_, q, config_.integration_step_s);
  }

 private:
  struct Propagated {
    std::uint16_t last = 0;        // recorded states kept: [0, last]; 0 means nothing usable
    std::uint16_t goal_index = 0;  // first recorded state in the goal region, 0 if none
    double rho_m = std::numeric_limits<double>::infinity();  // Eq. 1 over the kept states
    double best_cost_m = std::numeric_limits<double>::infinity();
    double best_rho_m = std::numeric_limits<double>::infinity();
    std::uint16_t best_index = 0;
  };

  // Retainment works on the planner's tree, heap, best state and solution.
  friend class Retainment<V>;

  Planner(const V& vehicle, const OccupancyGrid& grid, const PlannerConfig& config,
          CollisionChecker checker, DistanceField field, BaselineSelection<V> baseline,
          std::optional<TurningRho> turning_rho);

  bool iterate() noexcept;
  bool recycle_pool() noexcept;  // true if it made room
  Status problem_status(RetainStatus status, const State& start, const std::string& goal);
  RetainStatus set_target(const Goal& goal) noexcept;  // F, then rho's wavefront toward it
  bool in_goal_region(const State& q) const noexcept {
    return target_.contains(state_x(q), state_y(q));
  }
  void set_horizon(double horizon_s) noexcept;
  void reset_tree(const State& q) noexcept;
  void offer_solution(TreeState s) noexcept;
  TreeState resolve(TreeState s) const noexcept { return grip::resolve(tree_, s); }
  EdgeHandle expand_from(TreeState from) noexcept;
  Propagated propagate(TrajectoryHandle t, const State& from, std::uint32_t from_step,
                       const Control& u, std::uint32_t steps) noexcept;
  bool contingency_safe(const State& q) noexcept;
  bool is_free(const State& q) noexcept;  // chassis_free, counted in stats_
  double sampled_rho(EdgeHandle e, std::uint32_t stride, bool* in_goal) const noexcept;
  double score(const Edge& e) const noexcept;
  void push_scored(EdgeHandle e) noexcept;
  double step_time(std::uint32_t step) const noexcept {
    return static_cast<double>(step) * config_.integration_step_s;
  }
  void refresh_checker() noexcept;

  V vehicle_;
  PlannerConfig config_;
  const OccupancyGrid* grid_;
  CollisionChecker checker_;
  CellBox changed_;  // note_changed() since the last refresh of the checker
  bool changed_noted_ = false;
  DistanceField rho_field_;
  std::optional<TurningRho> turning_rho_;  // for a vehicle with a turning radius
  Tree<State> tree_;
  IndexedMinHeap heap_;  // GRIP's selection: the edges by score
  BaselineSelection<V> baseline_;
  TargetSet target_;
  Retainment<V> retainment_;
  Random rng_;
  PlannerStats stats_;
  std::uint64_t cycle_edges_ = 0;         // i of Eq. 2: edges propagated before, this cycle
  std::uint64_t validated_revision_ = 0;  // the grid revision the tree was last checked against
  TreeState solution_;
  TreeState best_;
  double best_rho_ = std::numeric_limits<double>::infinity();
  double best_cost_m_ = std::numeric_limits<double>::infinity();  // rho + top speed x time
  double log_a_;
  std::uint32_t horizon_step_;
  double cost_speed_;  // [m/s] converts time from the root into metres for the arrival estimate
  std::uint32_t min_edge_records_;
  std::uint32_t min_plan_steps_;
  std::uint32_t max_plan_steps_;
  bool problem_set_ = false;
};

// The planners of the three vehicles, instantiated once in planner.cpp.
using DdVelocityPlanner = Planner<DdVelocity>;
using DdAccelerationPlanner = Planner<DdAcceleration>;
using CarPlanner = Planner<Car>;

extern template class Planner<DdVelocity>;
extern template class Planner<DdAcceleration>;
extern template class Planner<Car>;

template <VehicleModel V>
template <typename Visitor>
void Planner<V>::visit_path(TreeState s, Visitor&& visit) const {
  // For drawing and tests, not the planning loop: it allocates the chain of edges.
  s = resolve(s);
  if (s.edge == kNoHandle) return;
  std::vector<EdgeHandle> chain;
  for (EdgeHandle e = s.edge; e != kNoHandle; e = tree_.edge(e).parent) chain.push_back(e);
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const Edge& edge = tree_.edge(*it);
    const std::uint16_t last = (*it == s.edge) ? s.index : edge.last;
    const int first = (edge.parent == kNoHandle) ? edge.first : edge.first + 1;
    for (int k = first; k <= last; ++k) {
      visit(tree_.state(edge.trajectory, static_cast<std::uint32_t>(k)));
    }
  }
}

template <VehicleModel V>
template <typename Visitor>
void Planner<V>::visit_edges(Visitor&& visit) const {
  for (EdgeHandle e = 0; e < tree_.edge_capacity(); ++e) {
    if (tree_.contains(e)) visit(e, tree_.edge(e));
  }
}

}  // namespace grip
