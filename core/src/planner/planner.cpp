#include "grip/planner/planner.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "grip/common/enum_names.hpp"

namespace grip {

namespace {
constexpr std::array<NamedValue<SolveStatus>, 3> kSolveStatusNames{{
    {SolveStatus::kExactSolution, "exact"},
    {SolveStatus::kApproximateSolution, "approximate"},
    {SolveStatus::kNoSolution, "none"},
}};
constexpr std::array<NamedValue<RetainStatus>, 7> kRetainStatusNames{{
    {RetainStatus::kOk, "ok"},
    {RetainStatus::kUnsupportedSelection, "unsupported-selection"},
    {RetainStatus::kRootNotInTree, "root-not-in-tree"},
    {RetainStatus::kRootInCollision, "root-in-collision"},
    {RetainStatus::kInvalidState, "invalid-state"},
    {RetainStatus::kGoalOutsideGrid, "goal-outside-grid"},
    {RetainStatus::kGoalWithoutFreeCell, "goal-without-free-cell"},
}};
constexpr std::array<NamedValue<StopReason>, 3> kStopReasonNames{{
    {StopReason::kGoalReached, "goal-reached"},
    {StopReason::kTerminationCondition, "terminated"},
    {StopReason::kPoolExhausted, "pool-exhausted"},
}};
}  // namespace

std::string_view solve_status_name(SolveStatus s) noexcept { return name_in(kSolveStatusNames, s); }
std::string_view retain_status_name(RetainStatus s) noexcept {
  return name_in(kRetainStatusNames, s);
}
std::string_view stop_reason_name(StopReason r) noexcept { return name_in(kStopReasonNames, r); }

namespace {

std::uint32_t to_steps(double seconds, double step) noexcept {
  return static_cast<std::uint32_t>(std::llround(seconds / step));
}

template <typename State>
std::array<double, 2> to_array(const Eigen::Matrix<double, 2, 1>& u) noexcept {
  return {u[0], u[1]};
}
}  // namespace

template <VehicleModel V>
Result<Planner<V>> Planner<V>::create(const V& vehicle, const OccupancyGrid& grid,
                                      const PlannerConfig& config) {
  if (auto s = config.validate(); !s) return s.error();
  // Chassis checks happen every integration step; inflating the footprint by half the largest
  // motion between two checks makes them cover the continuous trajectory.
  // rho's wavefront shares the checker's clearance (its inflation is rho_clearance_m).
  auto checker = CollisionChecker::create(
      grid, vehicle.footprint(), step_collision_margin_m(vehicle, config.integration_step_s),
      config.rho_clearance_m);
  if (!checker) return checker.error();
  auto field = DistanceField::create(grid.width(), grid.height(), grid.resolution());
  if (!field) return field.error();
  std::optional<NearestSourceField> tree_cells;
  if (config.selection == Selection::kRrt || config.selection == Selection::kRrtBias) {
    auto voronoi = NearestSourceField::create(grid.width(), grid.height());
    if (!voronoi) return voronoi.error();
    tree_cells.emplace(std::move(voronoi).value());
  }
  return Planner(vehicle, grid, config, std::move(checker).value(), std::move(field).value(),
                 std::move(tree_cells));
}

template <VehicleModel V>
Planner<V>::Planner(const V& vehicle, const OccupancyGrid& grid, const PlannerConfig& config,
                    CollisionChecker checker, DistanceField field,
                    std::optional<NearestSourceField> tree_cells)
    : vehicle_(vehicle),
      config_(config),
      grid_(&grid),
      checker_(std::move(checker)),
      rho_field_(std::move(field)),
      tree_(config.max_edges, config.max_trajectories, config.states_per_trajectory(),
            config.steps_per_record),
      heap_(config.max_edges),
      live_edges_(config.selection == Selection::kRandom ? config.max_edges : 0),
      free_cells_(tree_cells ? grid.cell_count() : 0),
      cell_state_(free_cells_.capacity()),
      tree_cells_(std::move(tree_cells)),
      goal_cells_(grid.cell_count()),
      goal_mask_(grid.cell_count()),
      order_(config.max_edges),
      stack_(config.max_edges),
      keep_(config.max_edges),
      subtree_cost_(config.max_edges),
      rng_(config.seed),
      log_a_(std::log(config.score_base_a)),
      horizon_step_(1),
      // Time weighs a quarter of top speed: a vehicle accelerating from rest at 0.6 m/s^2
      // would otherwise never look better than its start, and a long meander still loses.
      cost_speed_(0.25 * vehicle.max_speed_m_s()),
      // Retainment samples rho every 0.2 s of trajectory: Eq. 1 takes states "sampled along
      // e", and a full scan of every state of a big tree would not fit a cycle.
      rescore_stride_(std::max<std::uint32_t>(
          1U, static_cast<std::uint32_t>(std::lround(0.2 / config.record_step_s())))),
      min_edge_records_(std::max<std::uint32_t>(
          1U, static_cast<std::uint32_t>(
                  std::ceil(config.min_edge_duration_s / config.record_step_s() - 1e-9)))),
      min_plan_steps_(
          std::max<std::uint32_t>(config.steps_per_record,
                                  to_steps(config.min_plan_duration_s, config.integration_step_s))),
      max_plan_steps_(std::min<std::uint32_t>(
          to_steps(config.max_plan_duration_s, config.integration_step_s),
          (config.states_per_trajectory() - 1U) * config.steps_per_record)) {
  for (std::uint32_t e = 0; e < config.max_edges; ++e) {
    GRIP_ASSERT(subtree_cost_.push_back(std::numeric_limits<double>::infinity()));
  }
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) GRIP_ASSERT(goal_mask_.push_back(0));
}

template <VehicleModel V>
Status Planner<V>::set_problem(const State& start, const GoalRegion& goal) {
  // The messages are built here, at start-up; restart() below is the allocation-free core.
  // Appended piecewise: GCC 12 at -O3 warns falsely (-Wrestrict) on "(" + std::string.
  std::string where = "at (";
  where += std::to_string(goal.x_m);
  where += ", ";
  where += std::to_string(goal.y_m);
  where += ") radius ";
  where += std::to_string(goal.radius_m);
  begin_problem();
  return problem_status(restart(start, goal, config_.safety_horizon_s), start, where);
}

template <VehicleModel V>
void Planner<V>::begin_problem() noexcept {
  // A new problem replays the seed's samples and counts work from zero; restart() does not,
  // or a vehicle restarted in the same state would replay the samples that failed there.
  rng_.reseed(config_.seed);
  stats_ = PlannerStats{};
}

template <VehicleModel V>
Status Planner<V>::set_problem(const State& start, GoalCells goal) {
  std::string what = "of ";
  what += std::to_string(goal.cells.size());
  what += " cells";
  begin_problem();
  return problem_status(restart(start, goal, config_.safety_horizon_s), start, what);
}

template <VehicleModel V>
Status Planner<V>::problem_status(RetainStatus status, const State& start,
                                  const std::string& where) {
  switch (status) {
    case RetainStatus::kOk:
      return Ok{};
    case RetainStatus::kInvalidState:
      return invalid_argument("start: " + vehicle_.validate_state(start).error().message);
    case RetainStatus::kGoalOutsideGrid:
      return invalid_argument("goal " + where + " is not finite with a radius > 0, or lies " +
                              "outside the grid (" + std::to_string(grid_->width_m()) + " m x " +
                              std::to_string(grid_->height_m()) + " m)");
    case RetainStatus::kGoalWithoutFreeCell:
      return invalid_argument("goal region " + where + " contains no free cell");
    case RetainStatus::kRootInCollision:
      return invalid_argument("start (" + std::to_string(state_x(start)) + ", " +
                              std::to_string(state_y(start)) +
                              ") puts the chassis in an obstacle or unknown space");
    case RetainStatus::kUnsupportedSelection:
    case RetainStatus::kRootNotInTree:
      break;
  }
  return invalid_argument("start: unexpected state");
}

template <VehicleModel V>
RetainStatus Planner<V>::restart(const State& q, const GoalRegion& goal, double horizon_s,
                                 RhoUpdate rho) noexcept {
  return restart_towards(q, GoalSpec{&goal, {}}, horizon_s, rho);
}

template <VehicleModel V>
RetainStatus Planner<V>::restart(const State& q, GoalCells goal, double horizon_s,
                                 RhoUpdate rho) noexcept {
  return restart_towards(q, GoalSpec{nullptr, goal.cells}, horizon_s, rho);
}

template <VehicleModel V>
RetainStatus Planner<V>::restart_towards(const State& q, GoalSpec goal, double horizon_s,
                                         RhoUpdate rho) noexcept {
  if (!vehicle_.validate_state(q)) return RetainStatus::kInvalidState;
  if (!problem_set_) {
    checker_.refresh();
    changed_ = CellBox{};
    changed_noted_ = false;
  } else {
    refresh_checker();
  }
  if (!checker_.is_free(state_x(q), state_y(q), state_theta(q))) {
    return RetainStatus::kRootInCollision;
  }
  if (rho == RhoUpdate::kRecompute || !problem_set_) {
    if (const RetainStatus s = set_goal(goal); s != RetainStatus::kOk) return s;
  }
  set_horizon(horizon_s);

  free_cells_.clear();
  if (tree_cells_) {
    // RRT samples the cells rho_A* reaches from the goal, so every sample has a nearest state.
    for (std::uint32_t c = 0; c < grid_->cell_count(); ++c) {
      if (rho_field_.reachable(c)) GRIP_ASSERT(free_cells_.push_back(c));
    }
    tree_cells_->reset();
    cell_state_.clear();
    for (std::uint32_t c = 0; c < cell_state_.capacity(); ++c) {
      GRIP_ASSERT(cell_state_.push_back(TreeState{}));
    }
  }
  reset_tree(q);
  validated_revision_ = grid_->revision();
  problem_set_ = true;
  return RetainStatus::kOk;
}

template <VehicleModel V>
void Planner<V>::refresh_checker() noexcept {
  if (checker_.stale()) {
    if (changed_noted_) {
      checker_.refresh(changed_);
    } else {
      checker_.refresh();
    }
  }
  changed_ = CellBox{};
  changed_noted_ = false;
}

template <VehicleModel V>
RetainStatus Planner<V>::set_goal_cells(GoalSpec goal) noexcept {
  const std::uint32_t cell_count = grid_->cell_count();
  int gx = 0;
  int gy = 0;
  if (goal.disk != nullptr) {
    const GoalRegion& disk = *goal.disk;
    if (!std::isfinite(disk.radius_m) || disk.radius_m <= 0.0 ||
        !grid_->to_cell(disk.x_m, disk.y_m, gx, gy)) {
      return RetainStatus::kGoalOutsideGrid;
    }
  } else {
    // Checked before anything changes, so that a refused goal leaves the current one intact.
    bool any_free = false;
    for (const std::uint32_t c : goal.cells) {
      if (c >= cell_count) return RetainStatus::kGoalOutsideGrid;
      any_free = any_free || grid_->at(c) == Cell::kFree;
    }
    if (!any_free) return RetainStatus::kGoalWithoutFreeCell;
  }
  for (const std::uint32_t c : goal_cells_) goal_mask_[c] = 0;
  goal_cells_.clear();
  if (goal.disk != nullptr) {
    // The target set F: free cells whose centres lie in the goal disk.
    const GoalRegion& disk = *goal.disk;
    const int reach = static_cast<int>(std::ceil(disk.radius_m / grid_->resolution())) + 1;
    for (int cy = gy - reach; cy <= gy + reach; ++cy) {
      for (int cx = gx - reach; cx <= gx + reach; ++cx) {
        if (!grid_->in_bounds(cx, cy) || grid_->at(cx, cy) != Cell::kFree) continue;
        if (disk.contains(grid_->cell_center_x(cx), grid_->cell_center_y(cy))) {
          GRIP_ASSERT(goal_cells_.push_back(grid_->index(cx, cy)));  // sized to the grid
        }
      }
    }
  } else {
    // The given free cells, each once (the mask drops repeats).
    for (const std::uint32_t c : goal.cells) {
      if (grid_->at(c) != Cell::kFree || goal_mask_[c] != 0) continue;
      goal_mask_[c] = 1;
      GRIP_ASSERT(goal_cells_.push_back(c));  // sized to the grid
    }
  }
  if (goal_cells_.empty()) return RetainStatus::kGoalWithoutFreeCell;
  goal_is_disk_ = goal.disk != nullptr;
  if (goal_is_disk_) goal_ = *goal.disk;
  return RetainStatus::kOk;
}

template <VehicleModel V>
RetainStatus Planner<V>::set_goal(GoalSpec goal) noexcept {
  if (const RetainStatus s = set_goal_cells(goal); s != RetainStatus::kOk) return s;
  rho_field_.compute(*grid_, checker_.clearance(), goal_cells_.span(), config_.rho_clearance_m);
  return RetainStatus::kOk;
}

template <VehicleModel V>
RetainStatus Planner<V>::adopt_goal(GoalCells goal, DistanceField& rho) noexcept {
  GRIP_ASSERT(rho.width() == grid_->width() && rho.height() == grid_->height() &&
              rho.resolution() == grid_->resolution());
  if (const RetainStatus s = set_goal_cells(GoalSpec{nullptr, goal.cells});
      s != RetainStatus::kOk) {
    return s;
  }
  std::swap(rho_field_, rho);
  return RetainStatus::kOk;
}

template <VehicleModel V>
bool Planner<V>::in_goal_region(const State& q) const noexcept {
  if (goal_is_disk_) return goal_.contains(state_x(q), state_y(q));
  int cx = 0;
  int cy = 0;
  return grid_->to_cell(state_x(q), state_y(q), cx, cy) && goal_mask_[grid_->index(cx, cy)] != 0;
}

template <VehicleModel V>
void Planner<V>::set_horizon(double horizon_s) noexcept {
  horizon_step_ = std::max<std::uint32_t>(1U, to_steps(horizon_s, config_.integration_step_s));
}

template <VehicleModel V>
void Planner<V>::reset_tree(const State& q) noexcept {
  solution_ = TreeState{};
  heap_.clear();
  live_edges_.clear();
  cycle_edges_ = 0;
  const EdgeHandle root = tree_.reset(q);
  Edge& r = tree_.edge(root);
  r.priority = 1.0;
  r.rho_m = rho_at(q);
  best_ = TreeState{root, 0};  // until a state at least T away exists
  best_rho_ = r.rho_m;
  best_cost_m_ = std::numeric_limits<double>::infinity();
  register_edge(root);
  if (config_.selection == Selection::kGrip) push_scored(root);
  if (in_goal_region(q)) solution_ = best_;
}

template <VehicleModel V>
RetainStatus Planner<V>::retain(TreeState new_root, const GoalRegion& goal, double horizon_s,
                                const CellBox* newly_blocked, RhoUpdate rho) noexcept {
  return retain_towards(new_root, GoalSpec{&goal, {}}, horizon_s, newly_blocked, rho);
}

template <VehicleModel V>
RetainStatus Planner<V>::retain(TreeState new_root, GoalCells goal, double horizon_s,
                                const CellBox* newly_blocked, RhoUpdate rho) noexcept {
  return retain_towards(new_root, GoalSpec{nullptr, goal.cells}, horizon_s, newly_blocked, rho);
}

template <VehicleModel V>
RetainStatus Planner<V>::retain_towards(TreeState new_root, GoalSpec goal, double horizon_s,
                                        const CellBox* newly_blocked, RhoUpdate rho) noexcept {
  if (config_.selection != Selection::kGrip) return RetainStatus::kUnsupportedSelection;
  GRIP_ASSERT(config_.steps_per_record == 1);
  if (!problem_set_ || new_root.edge == kNoHandle || !tree_.contains(new_root.edge) ||
      new_root.index > tree_.edge(new_root.edge).last) {
    return RetainStatus::kRootNotInTree;
  }
  new_root = resolve(new_root);
  if (new_root.edge == kNoHandle) return RetainStatus::kRootNotInTree;
  const State& q = tree_.edge_state(new_root.edge, new_root.index);
  refresh_checker();
  if (!checker_.is_free(state_x(q), state_y(q), state_theta(q))) {
    return RetainStatus::kRootInCollision;
  }
  if (rho == RhoUpdate::kRecompute) {
    if (const RetainStatus s = set_goal(goal); s != RetainStatus::kOk) return s;
  }
  set_horizon(horizon_s);
  retain_stats_ = RetainStats{};
  retain_stats_.edges_before = tree_.edge_count();
  // The earliest goal state found so far: rho and F are sampled along edges, and a path that
  // crosses F between two samples must not be lost to one that lingers there.
  const TreeState known_solution = solution_;

  // Re-root: the part of the edge up to the new root becomes the root (reduced to its last
  // state); the rest of the tree above is unreachable, since no vehicle drives back in time.
  const std::uint32_t shift = tree_.step_of(new_root.edge, new_root.index);
  EdgeHandle root = new_root.edge;
  if (new_root.index < tree_.edge(root).last) root = tree_.split(root, new_root.index);
  tree_.unlink(root);
  tree_.make_root(root);
  const bool map_changed = grid_->revision() != validated_revision_;
  prune_and_order(root, shift, map_changed, newly_blocked, known_solution);
  validated_revision_ = grid_->revision();
  // Everything the walk did not keep goes back to the pools.
  const std::uint32_t before_release = tree_.edge_count();
  for (EdgeHandle e = 0; e < tree_.edge_capacity(); ++e) {
    if (tree_.contains(e) && keep_[e] == 0) tree_.release_edge(e);
  }
  retain_stats_.released = before_release - tree_.edge_count();
  rescore_tree(known_solution);
  retain_stats_.edges_kept = tree_.edge_count();
  cycle_edges_ = 0;
  return RetainStatus::kOk;
}

template <VehicleModel V>
void Planner<V>::prune_and_order(EdgeHandle root, std::uint32_t shift, bool map_changed,
                                 const CellBox* newly_blocked, TreeState known_solution) noexcept {
  // keep_[e]: 0 released, 1 kept, 2 kept but its children released (it was cut short);
  // kInGoal marks edges with a sampled state in F, then those with one below them.
  constexpr std::uint8_t kInGoal = 4;
  keep_.clear();
  for (std::uint32_t e = 0; e < tree_.edge_capacity(); ++e) GRIP_ASSERT(keep_.push_back(0));
  order_.clear();
  stack_.clear();
  GRIP_ASSERT(stack_.push_back(root));
  while (!stack_.empty()) {
    const EdgeHandle e = stack_.back();
    stack_.pop_back();
    GRIP_ASSERT(order_.push_back(e));
    for (EdgeHandle c = tree_.edge(e).first_child; c != kNoHandle; c = tree_.edge(c).next_sibling) {
      GRIP_ASSERT(stack_.push_back(c));
    }
  }

  // Which states the new map can have invalidated: none when it did not change; those within
  // the chassis' reach of the newly blocked cells when the caller says where; else all.
  const bool check_all = map_changed && newly_blocked == nullptr;
  const bool check_some = map_changed && newly_blocked != nullptr && !newly_blocked->empty();
  double box_x0 = 0.0, box_y0 = 0.0, box_x1 = 0.0, box_y1 = 0.0;
  if (check_some) {
    const double reach = checker_.checked_footprint().circumscribed_radius() + grid_->resolution();
    box_x0 = grid_->origin_x() + newly_blocked->x0 * grid_->resolution() - reach;
    box_y0 = grid_->origin_y() + newly_blocked->y0 * grid_->resolution() - reach;
    box_x1 = grid_->origin_x() + (newly_blocked->x1 + 1) * grid_->resolution() + reach;
    box_y1 = grid_->origin_y() + (newly_blocked->y1 + 1) * grid_->resolution() + reach;
  }

  // Pre-order: every parent comes before its children, so one pass re-times the edges,
  // checks them against the new map and T, and propagates removals downwards.
  for (const EdgeHandle e : order_) {
    Edge& edge = tree_.edge(e);
    if (e == root) {
      edge.start_step = 0;
      keep_[e] = 1;
      continue;
    }
    if (keep_[edge.parent] != 1) continue;  // below a removed or shortened edge
    edge.start_step -= shift;               // times are from the new root
    std::uint16_t last = edge.last;
    bool unsafe = false;
    if (check_all || check_some) {
      for (std::uint16_t k = static_cast<std::uint16_t>(edge.first + 1); k <= edge.last; ++k) {
        const State& qk = tree_.state(edge.trajectory, k);
        const double x = state_x(qk);
        const double y = state_y(qk);
        const bool near = check_all || (x >= box_x0 && x <= box_x1 && y >= box_y0 && y <= box_y1);
        if (near && !is_free(qk)) {
          last = static_cast<std::uint16_t>(k - 1);
          break;
        }
      }
    }
    // The state reached at T, if this edge holds it, must be able to brake (one state, found
    // by its time, not by a scan).
    const std::uint32_t t_offset = horizon_step_ - std::min(horizon_step_, edge.start_step);
    if (config_.safety == SafetyCheck::kAtHorizon && edge.start_step < horizon_step_ &&
        t_offset <= static_cast<std::uint32_t>(last - edge.first)) {
      const auto k = static_cast<std::uint16_t>(edge.first + t_offset);
      if (!contingency_safe(tree_.state(edge.trajectory, k))) {
        last = static_cast<std::uint16_t>(k - 1);
        unsafe = true;
      }
    }
    if (last == edge.last) {
      keep_[e] = 1;
      continue;
    }
    ++(unsafe ? retain_stats_.cut_unsafe : retain_stats_.cut_by_map);
    if (last > edge.first) {
      edge.last = last;
      keep_[e] = 2;
    }
  }

  // Rho against the new target (Eq. 1 over states sampled along each edge) and membership of
  // F, in one pass; reverse pre-order then carries "leads to F" up to the root.
  bool reaches_goal = false;
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0) continue;
    Edge& edge = tree_.edge(e);
    bool in_goal = false;
    edge.rho_m = e == root ? rho_at(tree_.edge_state(e, edge.last))
                           : sampled_rho(e, rescore_stride_, &in_goal);
    if (in_goal) {
      keep_[e] = static_cast<std::uint8_t>(keep_[e] | kInGoal);
      reaches_goal = true;
    }
  }
  if (const TreeState s = kept_goal_state(known_solution); s.edge != kNoHandle) {
    keep_[s.edge] = static_cast<std::uint8_t>(keep_[s.edge] | kInGoal);
    reaches_goal = true;
  }
  // Once a path reaches F, every path that does not is pruned, so that the cycle improves
  // the solution (Algorithm 1).
  if (reaches_goal) {
    for (auto it = order_.end(); it != order_.begin();) {
      const EdgeHandle e = *--it;
      if (keep_[e] == 0 || e == root || (keep_[e] & kInGoal) == 0) continue;
      const EdgeHandle parent = tree_.edge(e).parent;
      keep_[parent] = static_cast<std::uint8_t>(keep_[parent] | kInGoal);
    }
    for (const EdgeHandle e : order_) {
      if (keep_[e] == 0 || e == root) continue;
      if ((keep_[e] & kInGoal) == 0) {
        keep_[e] = 0;
        ++retain_stats_.pruned_off_goal;
      }
    }
  }
  for (const EdgeHandle e : order_) keep_[e] = static_cast<std::uint8_t>(keep_[e] & ~kInGoal);
  keep_[root] = 1;
  make_room(root);

  // Repair the links of what stays: drop released children from the child lists.
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0) continue;
    Edge& edge = tree_.edge(e);
    EdgeHandle previous = kNoHandle;
    EdgeHandle first = kNoHandle;
    for (EdgeHandle c = edge.first_child; c != kNoHandle; c = tree_.edge(c).next_sibling) {
      if (keep_[e] != 1 || keep_[c] == 0) continue;
      tree_.edge(c).prev_sibling = previous;
      if (previous == kNoHandle) {
        first = c;
      } else {
        tree_.edge(previous).next_sibling = c;
      }
      previous = c;
    }
    if (previous != kNoHandle) tree_.edge(previous).next_sibling = kNoHandle;
    edge.first_child = first;
  }
}

template <VehicleModel V>
void Planner<V>::make_room(EdgeHandle root) noexcept {
  // Memory is fixed and a replanning tree only loses what falls behind the root, so a long run
  // would fill the pools and stop growing. Past 60% of the edge pool, the subtrees whose best
  // estimated arrival (rho + time at a quarter of top speed) is worst are released until about
  // 40% remain. A subtree's best is never better than its parent's, so what stays is a tree.
  std::uint32_t kept = 0;
  for (const EdgeHandle e : order_) kept += keep_[e] != 0 ? 1U : 0U;
  const auto capacity = static_cast<double>(tree_.edge_capacity());
  if (kept <= static_cast<std::uint32_t>(0.6 * capacity)) return;
  const auto target = static_cast<std::uint32_t>(0.4 * capacity);
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  for (auto it = order_.end(); it != order_.begin();) {
    const EdgeHandle e = *--it;
    if (keep_[e] == 0) continue;
    const Edge& edge = tree_.edge(e);
    const double own = edge.rho_m + cost_speed_ * step_time(tree_.end_step(e));
    subtree_cost_[e] = std::min(subtree_cost_[e], own);  // children came first: min over them
    if (e != root)
      subtree_cost_[edge.parent] = std::min(subtree_cost_[edge.parent], subtree_cost_[e]);
    if (std::isfinite(subtree_cost_[e])) {
      low = std::min(low, subtree_cost_[e]);
      high = std::max(high, subtree_cost_[e]);
    }
  }
  // The threshold that keeps about `target` edges, by bisection over the costs.
  for (int i = 0; i < 40 && low < high; ++i) {
    const double middle = 0.5 * (low + high);
    std::uint32_t below = 0;
    for (const EdgeHandle e : order_)
      below += keep_[e] != 0 && subtree_cost_[e] <= middle ? 1U : 0U;
    (below > target ? high : low) = middle;
  }
  for (const EdgeHandle e : order_) {
    if (keep_[e] != 0 && e != root && !(subtree_cost_[e] <= high)) {
      keep_[e] = 0;
      ++retain_stats_.pruned_for_room;
    }
    subtree_cost_[e] = std::numeric_limits<double>::infinity();  // ready for the next cycle
  }
}

template <VehicleModel V>
TreeState Planner<V>::kept_goal_state(TreeState s) const noexcept {
  // During retainment, after the walk: s if it is still in the kept tree below the root (not
  // cut off, not released) and in the current F.
  if (s.edge == kNoHandle || !tree_.contains(s.edge)) return TreeState{};
  s = resolve(s);
  if (s.edge == kNoHandle || s.edge == tree_.root() || keep_[s.edge] == 0) return TreeState{};
  const Edge& edge = tree_.edge(s.edge);
  if (s.index <= edge.first || s.index > edge.last) return TreeState{};
  if (!in_goal_region(tree_.state(edge.trajectory, s.index))) return TreeState{};
  return s;
}

template <VehicleModel V>
void Planner<V>::rescore_tree(TreeState known_solution) noexcept {
  // Children of the root get priority 1, then Eq. 2 down the tree; the heap is rebuilt; the
  // best state and the solution are found again (over the same sampled states as rho).
  heap_.clear();
  solution_ = TreeState{};
  const EdgeHandle root = tree_.root();
  best_ = TreeState{root, tree_.edge(root).last};
  best_rho_ = tree_.edge(root).rho_m;
  best_cost_m_ = std::numeric_limits<double>::infinity();
  EdgeHandle best_edge = root;
  double best_edge_cost = best_cost_m_;
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0) continue;
    Edge& edge = tree_.edge(e);
    if (e == root) {
      edge.priority = 1.0;
    } else {
      edge.priority =
          edge.parent == root ? 1.0 : std::fma(2.0, tree_.edge(edge.parent).priority, 1.0);
    }
    push_scored(e);
    // Estimated from the edge's rho and the time at its end; refined on the chosen edge below.
    const double cost = edge.rho_m + cost_speed_ * step_time(tree_.end_step(e));
    if (tree_.end_step(e) >= horizon_step_ && cost < best_edge_cost) {
      best_edge_cost = cost;
      best_edge = e;
    }
  }
  if (best_edge != root) {
    const Edge& edge = tree_.edge(best_edge);
    for (int k = edge.first + 1; k <= edge.last; ++k) {
      const auto index = static_cast<std::uint16_t>(k);
      const double rho = rho_at(tree_.state(edge.trajectory, index));
      const std::uint32_t step = tree_.step_of(best_edge, index);
      const double cost = rho + cost_speed_ * step_time(step);
      if (step >= horizon_step_ && cost < best_cost_m_) {
        best_cost_m_ = cost;
        best_rho_ = rho;
        best_ = TreeState{best_edge, index};
      }
    }
  }
  // The solution: the earliest goal state among the edges kept (all lead to F when one does).
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0 || e == root) continue;
    const Edge& edge = tree_.edge(e);
    for (int k = edge.first + 1; k <= edge.last; k += static_cast<int>(rescore_stride_)) {
      const State& qk = tree_.state(edge.trajectory, static_cast<std::uint32_t>(k));
      if (!in_goal_region(qk)) continue;
      // Back to the first state of this edge in F, between the samples.
      while (k > edge.first + 1) {
        const State& earlier = tree_.state(edge.trajectory, static_cast<std::uint32_t>(k - 1));
        if (!in_goal_region(earlier)) break;
        --k;
      }
      offer_solution(TreeState{e, static_cast<std::uint16_t>(k)});
      break;
    }
  }
  if (const TreeState s = kept_goal_state(known_solution); s.edge != kNoHandle) {
    offer_solution(s);
  }
}

template <VehicleModel V>
void Planner<V>::offer_solution(TreeState s) noexcept {
  // A goal state becomes the solution when there is none or it is reached sooner.
  const TreeState current = resolve(solution_);
  if (!solved() || tree_.step_of(s.edge, s.index) < tree_.step_of(current.edge, current.index)) {
    solution_ = s;
  }
}

template <VehicleModel V>
SolveResult Planner<V>::solve(FunctionRef<bool()> should_stop) noexcept {
  SolveResult result;
  if (!problem_set_) return result;
  for (;;) {
    if (solved() && config_.stop_at_goal) {
      result.reason = StopReason::kGoalReached;
      break;
    }
    if (should_stop()) {
      result.reason = StopReason::kTerminationCondition;
      break;
    }
    if (!tree_.has_room_for_propagation()) {
      stats_.pool_exhausted = true;
      result.reason = StopReason::kPoolExhausted;
      break;
    }
    iterate();
  }
  result.status = solved() ? SolveStatus::kExactSolution
                           : (best_.edge != kNoHandle ? SolveStatus::kApproximateSolution
                                                      : SolveStatus::kNoSolution);
  return result;
}

template <VehicleModel V>
bool Planner<V>::iterate() noexcept {
  ++stats_.iterations;
  if (config_.selection != Selection::kGrip) return expand_from(select()) != kNoHandle;

  // GRIP (section 2.2): pop the minimum score, propagate from a random state along it, and
  // apply Eq. 2 to the parts of the selected edge whether or not the propagation succeeded.
  const EdgeHandle selected = heap_.pop();
  const double new_priority = std::fma(2.0, tree_.edge(selected).priority, 1.0);
  const double selected_rho_m = tree_.edge(selected).rho_m;
  const EdgeHandle added = expand_from(random_state_along(selected));
  tree_.edge(selected).priority = new_priority;
  if (added != kNoHandle) {
    // expand_from split `selected` at k when k was inside it: the head took its place.
    const EdgeHandle head = tree_.edge(added).parent;
    if (head != selected) {
      Edge& h = tree_.edge(head);
      h.priority = new_priority;
      h.rho_m = sampled_rho(head, 1, nullptr);
      tree_.edge(selected).rho_m = sampled_rho(selected, 1, nullptr);
      push_scored(head);
    }
    Edge& n = tree_.edge(added);
    // p(e) = i, the edges before it (Eq. 2), for an edge that gets closer to F than the one it
    // grew from. One that does not counts as another selection of that edge: otherwise every
    // failed attempt out of a dead end hands it a fresh, low priority, and the dead end keeps
    // winning the heap long after its own edges have been penalised.
    n.priority = n.rho_m < selected_rho_m ? static_cast<double>(cycle_edges_ - 1) : new_priority;
    push_scored(added);
  }
  push_scored(selected);
  return added != kNoHandle;
}

template <VehicleModel V>
TreeState Planner<V>::select() noexcept {
  if (config_.selection == Selection::kRandom) {
    return random_state_along(
        live_edges_[rng_.below(static_cast<std::uint32_t>(live_edges_.size()))]);
  }
  return select_rrt();
}

template <VehicleModel V>
TreeState Planner<V>::random_state_along(EdgeHandle e) noexcept {
  // A recorded state of e other than its first, which belongs to the parent (the root edge
  // holds a single state).
  const Edge& edge = tree_.edge(e);
  if (edge.first == edge.last) return TreeState{e, edge.last};
  return TreeState{e,
                   static_cast<std::uint16_t>(edge.first + 1 + rng_.below(edge.last - edge.first))};
}

template <VehicleModel V>
TreeState Planner<V>::select_rrt() noexcept {
  // RRT-EXTEND: a random free point, and the tree state nearest to it under rho_A*: the
  // geodesic Voronoi field of the tree's cells answers in O(1).
  std::uint32_t sample = 0;
  if (config_.selection == Selection::kRrtBias && rng_.uniform01() < config_.rrt_goal_bias) {
    sample = goal_cells_[rng_.below(static_cast<std::uint32_t>(goal_cells_.size()))];
  } else {
    sample = free_cells_[rng_.below(static_cast<std::uint32_t>(free_cells_.size()))];
  }
  const std::uint32_t cell = tree_cells_->nearest_source(sample);
  if (cell == NearestSourceField::kNoCell) return TreeState{tree_.root(), 0};
  return resolve(cell_state_[cell]);
}

template <VehicleModel V>
TreeState Planner<V>::resolve(TreeState s) const noexcept {
  // Splitting keeps the tail under the old handle; states before its first index now belong
  // to the heads above it.
  if (s.edge == kNoHandle) return s;
  while (s.index < tree_.edge(s.edge).first) {
    s.edge = tree_.edge(s.edge).parent;
    if (s.edge == kNoHandle) return TreeState{};  // before the root: not in the tree
  }
  const Edge& edge = tree_.edge(s.edge);
  if (s.index == edge.first && edge.parent != kNoHandle) {
    return TreeState{edge.parent, tree_.edge(edge.parent).last};
  }
  return s;
}

template <VehicleModel V>
EdgeHandle Planner<V>::expand_from(TreeState from) noexcept {
  const TrajectoryHandle t = tree_.acquire_trajectory();
  GRIP_ASSERT(t != kNoHandle);  // solve() checked the room
  // Random controls (section 2.2), and, if configured, now and then the braking maneuver (the
  // paper allows controls from a maneuver set; see braking_control_fraction).
  const bool brake =
      config_.braking_control_fraction > 0.0 && rng_.uniform01() < config_.braking_control_fraction;
  const State start = tree_.edge_state(from.edge, from.index);
  const auto draw_hold_steps = [this] {
    return min_plan_steps_ + rng_.below(max_plan_steps_ - min_plan_steps_ + 1U);
  };
  Control u;
  std::uint32_t steps = 0;
  if constexpr (SteersToVelocityTarget<V>) {
    // The control depends on the hold, so the hold is drawn first.
    steps = draw_hold_steps();
    u = brake ? vehicle_.braking_control(start)
              : vehicle_.sample_control(start, step_time(steps), rng_);
  } else {
    u = brake ? vehicle_.braking_control(start) : vehicle_.sample_control(rng_);
    steps = draw_hold_steps();
  }
  const std::uint32_t start_step = tree_.step_of(from.edge, from.index);
  const Propagated p = propagate(t, start, start_step, u, steps);
  if (p.last < min_edge_records_) {
    tree_.release_trajectory(t);
    return kNoHandle;
  }
  Trajectory& traj = tree_.trajectory(t);
  traj.control = {u[0], u[1]};
  traj.state_count = static_cast<std::uint16_t>(p.last + 1);

  EdgeHandle attach = from.edge;
  if (from.index < tree_.edge(from.edge).last) attach = tree_.split(from.edge, from.index);
  const EdgeHandle added = tree_.add_child(attach, t, p.last);
  Edge& n = tree_.edge(added);
  n.rho_m = p.rho_m;
  ++stats_.edges_added;
  ++cycle_edges_;
  if (attach != from.edge) register_edge(attach);
  register_edge(added);
  if (p.best_cost_m < best_cost_m_) {
    best_cost_m_ = p.best_cost_m;
    best_rho_ = p.best_rho_m;
    best_ = TreeState{added, p.best_index};
  }
  // A later path to the goal replaces the solution when it gets there sooner (replanning
  // keeps growing the tree to improve the committed trajectory).
  if (p.goal_index != 0) offer_solution(TreeState{added, p.goal_index});
  return added;
}

template <VehicleModel V>
typename Planner<V>::Propagated Planner<V>::propagate(TrajectoryHandle t, const State& from,
                                                      std::uint32_t from_step, const Control& u,
                                                      std::uint32_t steps) noexcept {
  Propagated out;
  const double dt = config_.integration_step_s;
  const std::uint32_t per_record = config_.steps_per_record;
  tree_.state(t, 0) = from;
  State q = from;
  std::uint16_t recorded = 0;
  for (std::uint32_t j = 1; j <= steps; ++j) {
    q = vehicle_.step(q, u, dt);
    ++stats_.propagations;
    if (!is_free(q)) break;  // t_free: the trajectory ends at the last free recorded state
    // Safety at low cost: only the state reached at time T needs its contingency. If it
    // collides, everything from T on is cut (Algorithm 1, "adjust t_free").
    if (config_.safety == SafetyCheck::kAtHorizon && from_step + j == horizon_step_ &&
        !contingency_safe(q)) {
      break;
    }
    if (j % per_record != 0) continue;
    tree_.state(t, ++recorded) = q;
    const double rho = rho_at(q);
    out.rho_m = std::min(out.rho_m, rho);
    // Plans are chosen among states at least T from the root (they must cover the next cycle).
    const double cost = rho + cost_speed_ * step_time(from_step + j);
    if (from_step + j >= horizon_step_ && cost < out.best_cost_m) {
      out.best_cost_m = cost;
      out.best_rho_m = rho;
      out.best_index = recorded;
    }
    if (out.goal_index == 0 && in_goal_region(q)) {
      out.goal_index = recorded;
      // Standalone runs end at the goal; replanning goes on (the vehicle may be inside F).
      if (config_.stop_at_goal) break;
    }
  }
  if (config_.safety == SafetyCheck::kAllLeaves) {
    // The Fig. 7 variant: the new leaf must be safe; walk back until a safe state is found.
    while (recorded > 0 && !contingency_safe(tree_.state(t, recorded))) --recorded;
    if (out.goal_index > recorded) out.goal_index = 0;
    if (out.best_index > recorded) {
      out.rho_m = std::numeric_limits<double>::infinity();
      out.best_cost_m = std::numeric_limits<double>::infinity();
      out.best_index = 0;
      for (std::uint16_t k = 1; k <= recorded; ++k) {
        const double rho = rho_at(tree_.state(t, k));
        out.rho_m = std::min(out.rho_m, rho);
        const std::uint32_t step = from_step + k * per_record;
        const double cost = rho + cost_speed_ * step_time(step);
        if (step >= horizon_step_ && cost < out.best_cost_m) {
          out.best_cost_m = cost;
          out.best_rho_m = rho;
          out.best_index = k;
        }
      }
    }
  }
  out.last = recorded;
  return out;
}

template <VehicleModel V>
bool Planner<V>::is_free(const State& q) noexcept {
  ++stats_.collision_checks;
  return checker_.is_free(state_x(q), state_y(q), state_theta(q));
}

template <VehicleModel V>
bool Planner<V>::contingency_safe(const State& q) noexcept {
  ++stats_.contingency_checks;
  return contingency_is_collision_free(vehicle_, checker_, q, config_.integration_step_s,
                                       stats_.collision_checks);
}

template <VehicleModel V>
double Planner<V>::sampled_rho(EdgeHandle e, std::uint32_t stride, bool* in_goal) const noexcept {
  // Eq. 1 over the states of the edge taken every `stride` records, and always its last one
  // (its first state belongs to its parent); optionally whether one of them lies in F.
  const Edge& edge = tree_.edge(e);
  double rho = std::numeric_limits<double>::infinity();
  const int first = edge.parent == kNoHandle ? edge.first : edge.first + 1;
  for (int k = edge.last; k >= first; k -= static_cast<int>(stride)) {
    const State& q = tree_.state(edge.trajectory, static_cast<std::uint32_t>(k));
    rho = std::min(rho, rho_at(q));
    if (in_goal != nullptr && !*in_goal) *in_goal = in_goal_region(q);
  }
  return rho;
}

template <VehicleModel V>
double Planner<V>::score(const Edge& e) const noexcept {
  // ln s(e) = p(e) ln a + ln rho(e, F) (Eq. 3 in log space: a^p overflows for the priorities
  // that occur). Unreachable edges score +inf; rho below the floor compares as equal.
  return e.priority * log_a_ + std::log(std::max(e.rho_m, config_.rho_floor_m));
}

template <VehicleModel V>
void Planner<V>::push_scored(EdgeHandle e) noexcept {
  const bool pushed = heap_.push(e, score(tree_.edge(e)));
  GRIP_ASSERT(pushed);  // the heap holds as many entries as the edge pool
}

template <VehicleModel V>
void Planner<V>::register_edge(EdgeHandle e) noexcept {
  switch (config_.selection) {
    case Selection::kGrip:
      break;  // GRIP's heap is kept by iterate()
    case Selection::kRandom:
      GRIP_ASSERT(live_edges_.push_back(e));  // sized to the edge pool
      break;
    case Selection::kRrt:
    case Selection::kRrtBias: {
      const Edge& edge = tree_.edge(e);
      for (int k = edge.first; k <= edge.last; ++k) {
        const State& q = tree_.state(edge.trajectory, static_cast<std::uint32_t>(k));
        int cx = 0;
        int cy = 0;
        if (!grid_->to_cell(state_x(q), state_y(q), cx, cy)) continue;
        const std::uint32_t cell = grid_->index(cx, cy);
        if (cell_state_[cell].edge != kNoHandle) continue;
        cell_state_[cell] = TreeState{e, static_cast<std::uint16_t>(k)};
        tree_cells_->add_source(rho_field_, cell);
      }
      break;
    }
  }
}

template <VehicleModel V>
TreeState Planner<V>::best_state() const noexcept {
  return resolve(solved() ? solution_ : best_);
}

template <VehicleModel V>
bool Planner<V>::contains(TreeState s) const noexcept {
  if (s.edge == kNoHandle || !tree_.contains(s.edge) || s.index > tree_.edge(s.edge).last) {
    return false;
  }
  return resolve(s).edge != kNoHandle;
}

template <VehicleModel V>
TreeState Planner<V>::state_at_step(TreeState s, std::uint32_t step) const noexcept {
  s = resolve(s);
  if (s.edge == kNoHandle || step > tree_.step_of(s.edge, s.index)) return TreeState{};
  for (EdgeHandle e = s.edge; e != kNoHandle; e = tree_.edge(e).parent) {
    const Edge& edge = tree_.edge(e);
    if (step < edge.start_step) continue;
    const std::uint32_t offset = (step - edge.start_step) / config_.steps_per_record;
    if ((step - edge.start_step) % config_.steps_per_record != 0) return TreeState{};
    return resolve(TreeState{e, static_cast<std::uint16_t>(edge.first + offset)});
  }
  return TreeState{};
}

template <VehicleModel V>
TreeState Planner<V>::committable_state(TreeState target, std::uint32_t min_step) noexcept {
  TreeState s = resolve(target);
  while (s.edge != kNoHandle) {
    const Edge& edge = tree_.edge(s.edge);
    if (tree_.step_of(s.edge, s.index) < min_step) return TreeState{};
    if (config_.safety == SafetyCheck::kNone ||
        contingency_safe(tree_.edge_state(s.edge, s.index))) {
      return s;
    }
    if (s.index > edge.first + (edge.parent == kNoHandle ? 0 : 1)) {
      --s.index;
    } else if (edge.parent != kNoHandle) {
      s = TreeState{edge.parent, tree_.edge(edge.parent).last};
    } else {
      return TreeState{};
    }
  }
  return TreeState{};
}

template <VehicleModel V>
bool Planner<V>::extract_plan(TreeState s, VectorView<PlanStep>& out) const noexcept {
  out.clear();
  s = resolve(s);
  if (s.edge == kNoHandle) return true;
  const double record_step = config_.record_step_s();
  // Count the pieces first (consecutive edges of one trajectory merge into one), then fill
  // from the back, so that no buffer is needed for the walk up the tree.
  std::size_t pieces = 0;
  TrajectoryHandle previous = kNoHandle;
  for (EdgeHandle e = s.edge; e != kNoHandle; e = tree_.edge(e).parent) {
    const Edge& edge = tree_.edge(e);
    const std::uint16_t last = e == s.edge ? s.index : edge.last;
    if (last == edge.first) continue;
    if (edge.trajectory != previous) ++pieces;
    previous = edge.trajectory;
  }
  if (pieces > out.capacity()) return false;
  for (std::size_t i = 0; i < pieces; ++i) GRIP_ASSERT(out.push_back(PlanStep{}));
  std::size_t slot = pieces;
  previous = kNoHandle;
  for (EdgeHandle e = s.edge; e != kNoHandle; e = tree_.edge(e).parent) {
    const Edge& edge = tree_.edge(e);
    const std::uint16_t last = e == s.edge ? s.index : edge.last;
    if (last == edge.first) continue;
    const double duration = (last - edge.first) * record_step;
    if (edge.trajectory == previous) {
      out[slot].duration_s += duration;
    } else {
      --slot;
      out[slot].control = tree_.trajectory(edge.trajectory).control;
      out[slot].duration_s = duration;
    }
    previous = edge.trajectory;
  }
  return true;
}

template class Planner<DdVelocity>;
template class Planner<DdAcceleration>;
template class Planner<Car>;

}  // namespace grip
