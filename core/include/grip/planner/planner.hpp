#pragma once
// The tree planner: GRIP's selection and propagation (GRIP.md section 2.2, Algorithm 1's main
// loop) with safety at low cost (section 2.3), and the baselines of the paper's Fig. 5/6 on
// the same tree, propagation and rho.
//
// Reads like OMPL's planners: set a problem, then solve(termination condition) returns a
// status. Everything is reserved by create(); solve() allocates nothing, never blocks and
// never throws. When the pools run out it stops growing, says so, and keeps its best answer.

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "grip/common/function_ref.hpp"
#include "grip/common/random.hpp"
#include "grip/common/result.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/memory/indexed_min_heap.hpp"
#include "grip/planner/contingency.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/planner/step_margin.hpp"
#include "grip/planner/tree.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"
#include "grip/world/collision_checker.hpp"
#include "grip/world/distance_field.hpp"
#include "grip/world/nearest_source_field.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

// The goal region F: the reference point within radius of a workspace point.
struct GoalRegion {
  double x_m = 0.0;
  double y_m = 0.0;
  double radius_m = 1.0;
  bool contains(double x, double y) const noexcept {
    const double dx = x - x_m;
    const double dy = y - y_m;
    return dx * dx + dy * dy <= radius_m * radius_m;
  }
};

// The goal region F given as a set of grid cells (indices, cell_y * width + cell_x), e.g. the
// approach cells of a frontier group (exploration/frontier.hpp): the reference point is in F
// when the cell containing it is one of them. Cells that are not kFree are ignored.
struct GoalCells {
  std::span<const std::uint32_t> cells;
};

// One piece of a plan: a control held for a duration (section 1, p = {(u1, dt1), ...}).
struct PlanStep {
  std::array<double, 2> control{};
  double duration_s = 0.0;
};

enum class SolveStatus { kExactSolution, kApproximateSolution, kNoSolution };
enum class StopReason { kGoalReached, kTerminationCondition, kPoolExhausted };

std::string_view solve_status_name(SolveStatus s) noexcept;
std::string_view stop_reason_name(StopReason r) noexcept;

struct SolveResult {
  SolveStatus status = SolveStatus::kNoSolution;
  StopReason reason = StopReason::kTerminationCondition;
};

// Work counters, cumulative since the last set_problem().
struct PlannerStats {
  std::uint64_t iterations = 0;    // selections made
  std::uint64_t edges_added = 0;   // new edges (the paper's "edges added" metric)
  std::uint64_t propagations = 0;  // integration steps of random plans
  std::uint64_t collision_checks = 0;
  std::uint64_t contingency_checks = 0;  // braking maneuvers run
  bool pool_exhausted = false;
};

// Outcome of the allocation-free replanning calls (retain, restart).
enum class RetainStatus {
  kOk,
  kUnsupportedSelection,  // retainment is GRIP's; the baselines are standalone planners
  kRootNotInTree,
  kRootInCollision,  // the new map puts the chassis at the new root in collision
  kInvalidState,     // NaN or outside the vehicle's limits
  kGoalOutsideGrid,
  kGoalWithoutFreeCell,
};
std::string_view retain_status_name(RetainStatus s) noexcept;

// What one retainment kept and pruned (edge counts).
struct RetainStats {
  std::uint32_t edges_before = 0;
  std::uint32_t cut_by_map = 0;       // edges cut where their trajectory now collides
  std::uint32_t cut_unsafe = 0;       // edges cut where the state at T cannot brake safely
  std::uint32_t pruned_off_goal = 0;  // not leading to the goal once a path does
  std::uint32_t pruned_for_room = 0;  // the worst subtrees, when the pool was filling up
  std::uint32_t released = 0;         // returned to the pool: above the new root, cut or pruned
  std::uint32_t edges_kept = 0;       // the tree carried over into the cycle
};

// Whether a retainment recomputes rho toward F (a whole-map wavefront) or keeps the field of
// the previous call. kKeep is for a caller that passes the same F as last time and accepts rho
// computed on an older map: rho only orders the search, collisions are always checked on the
// current map.
enum class RhoUpdate { kRecompute, kKeep };

// A state reached in the tree: recorded state k of edge e.
struct TreeState {
  EdgeHandle edge = kNoHandle;
  std::uint16_t index = 0;
};

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
  // outside the grid or with no free cell.
  Status set_problem(const State& start, const GoalRegion& goal);
  // The same with F as a set of cells; an index >= cell_count() is refused like a goal outside
  // the grid. The span is read during the call only.
  Status set_problem(const State& start, GoalCells goal);

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
  RetainStatus retain(TreeState new_root, const GoalRegion& goal, double horizon_s,
                      const CellBox* newly_blocked = nullptr,
                      RhoUpdate rho = RhoUpdate::kRecompute) noexcept;
  // Starts a fresh tree at q (when q is not on the tree), allocation-free. Unlike
  // set_problem(), the random stream and the work counters go on: restarting in the same
  // state must not replay the samples that failed there. RhoUpdate as for retain(); the
  // first call after create() always computes rho.
  RetainStatus restart(const State& q, const GoalRegion& goal, double horizon_s,
                       RhoUpdate rho = RhoUpdate::kRecompute) noexcept;
  // retain() and restart() with F as a set of cells (kGoalOutsideGrid for an index outside the
  // grid, kGoalWithoutFreeCell when none is free); the span is read during the call only.
  RetainStatus retain(TreeState new_root, GoalCells goal, double horizon_s,
                      const CellBox* newly_blocked = nullptr,
                      RhoUpdate rho = RhoUpdate::kRecompute) noexcept;
  RetainStatus restart(const State& q, GoalCells goal, double horizon_s,
                       RhoUpdate rho = RhoUpdate::kRecompute) noexcept;
  const RetainStats& last_retain() const noexcept { return retain_stats_; }
  // F as a set of cells with rho toward it computed elsewhere (beside the planning thread, on
  // a copy of the map: ExplorationTarget), so that no whole-map wavefront runs here: F becomes
  // `goal` and rho_field() becomes `rho`, which receives the previous field in exchange (no
  // copy). `rho` must be a field of this grid's size computed toward these cells with inflation
  // rho_clearance_m; rho only orders the search, so one computed on a map a cycle older will
  // do. The next retain() or restart() with RhoUpdate::kKeep plans toward it. Errors as for
  // retain() with cells; on an error nothing changes.
  RetainStatus adopt_goal(GoalCells goal, DistanceField& rho) noexcept;
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
  // from the root at a quarter of top speed (a plan should head to F and be short, section 1),
  // so that a meandering path that ends slightly closer does not win.
  TreeState best_state() const noexcept;
  double best_rho_m() const noexcept { return best_rho_; }

  // The state reached `step` integration steps from the root on the path to s, or an empty
  // TreeState when the path is shorter. With steps_per_record == 1 every step is recorded.
  TreeState state_at_step(TreeState s, std::uint32_t step) const noexcept;
  // Lazy safety for the plan about to be committed (section 2.3): the latest state on the path
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
  double collision_margin_m() const noexcept { return checker_.margin(); }

 private:
  struct Propagated {
    std::uint16_t last = 0;        // recorded states kept: [0, last]; 0 means nothing usable
    std::uint16_t goal_index = 0;  // first recorded state in the goal region, 0 if none
    double rho_m = std::numeric_limits<double>::infinity();  // Eq. 1 over the kept states
    double best_cost_m = std::numeric_limits<double>::infinity();
    double best_rho_m = std::numeric_limits<double>::infinity();
    std::uint16_t best_index = 0;
  };

  Planner(const V& vehicle, const OccupancyGrid& grid, const PlannerConfig& config,
          CollisionChecker checker, DistanceField field,
          std::optional<NearestSourceField> tree_cells);

  // F as the caller gave it: a disk (disk != nullptr) or a set of cells.
  struct GoalSpec {
    const GoalRegion* disk = nullptr;
    std::span<const std::uint32_t> cells;
  };

  bool iterate() noexcept;
  Status problem_status(RetainStatus status, const State& start, const std::string& goal);
  void begin_problem() noexcept;
  RetainStatus restart_towards(const State& q, GoalSpec goal, double horizon_s,
                               RhoUpdate rho) noexcept;
  RetainStatus retain_towards(TreeState new_root, GoalSpec goal, double horizon_s,
                              const CellBox* newly_blocked, RhoUpdate rho) noexcept;
  RetainStatus set_goal(GoalSpec goal) noexcept;        // F, then rho's wavefront toward it
  RetainStatus set_goal_cells(GoalSpec goal) noexcept;  // F alone
  bool in_goal_region(const State& q) const noexcept;
  void set_horizon(double horizon_s) noexcept;
  void reset_tree(const State& q) noexcept;
  void prune_and_order(EdgeHandle root, std::uint32_t shift, bool map_changed,
                       const CellBox* newly_blocked, TreeState known_solution) noexcept;
  TreeState kept_goal_state(TreeState s) const noexcept;
  void offer_solution(TreeState s) noexcept;
  void rescore_tree(TreeState known_solution) noexcept;
  void make_room(EdgeHandle root) noexcept;
  TreeState select() noexcept;
  TreeState select_rrt() noexcept;
  TreeState random_state_along(EdgeHandle e) noexcept;
  TreeState resolve(TreeState s) const noexcept;
  EdgeHandle expand_from(TreeState from) noexcept;
  Propagated propagate(TrajectoryHandle t, const State& from, std::uint32_t from_step,
                       const Control& u, std::uint32_t steps) noexcept;
  bool contingency_safe(const State& q) noexcept;
  bool is_free(const State& q) noexcept;
  double sampled_rho(EdgeHandle e, std::uint32_t stride, bool* in_goal) const noexcept;
  double score(const Edge& e) const noexcept;
  // Makes a new edge selectable by the baseline strategies.
  void register_edge(EdgeHandle e) noexcept;
  void push_scored(EdgeHandle e) noexcept;
  double step_time(std::uint32_t step) const noexcept {
    return static_cast<double>(step) * config_.integration_step_s;
  }
  double rho_at(const State& q) const noexcept {
    return rho_field_.distance_m(state_x(q), state_y(q));
  }

  V vehicle_;
  PlannerConfig config_;
  const OccupancyGrid* grid_;
  CollisionChecker checker_;
  CellBox changed_;  // note_changed() since the last refresh of the checker
  bool changed_noted_ = false;
  void refresh_checker() noexcept;
  DistanceField rho_field_;
  Tree<State> tree_;
  IndexedMinHeap heap_;
  BoundedVector<EdgeHandle> live_edges_;          // random selection
  BoundedVector<std::uint32_t> free_cells_;       // RRT samples: cells rho_A* can reach
  BoundedVector<TreeState> cell_state_;           // RRT: a tree state in each grid cell
  std::optional<NearestSourceField> tree_cells_;  // RRT: nearest tree cell under rho_A*
  BoundedVector<std::uint32_t> goal_cells_;
  BoundedVector<std::uint8_t> goal_mask_;  // per grid cell: 1 in F (cell-set goals only)
  BoundedVector<EdgeHandle> order_;        // retainment: the kept tree in pre-order
  BoundedVector<EdgeHandle> stack_;        // retainment: depth-first walk
  BoundedVector<std::uint8_t> keep_;       // retainment: per edge handle, see prune_and_order
  BoundedVector<double> subtree_cost_;     // retainment: best estimated arrival below an edge
  Random rng_;
  GoalRegion goal_;
  bool goal_is_disk_ = true;  // else F is goal_cells_ (goal_mask_)
  PlannerStats stats_;
  RetainStats retain_stats_;
  std::uint64_t cycle_edges_ = 0;         // i of Eq. 2: edges propagated before, this cycle
  std::uint64_t validated_revision_ = 0;  // the grid revision the tree was last checked against
  TreeState solution_;
  TreeState best_;
  double best_rho_ = std::numeric_limits<double>::infinity();
  double best_cost_m_ = std::numeric_limits<double>::infinity();  // rho + top speed x time
  double log_a_;
  std::uint32_t horizon_step_;
  double cost_speed_;  // [m/s] converts time from the root into metres for the arrival estimate
  std::uint32_t rescore_stride_;
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
