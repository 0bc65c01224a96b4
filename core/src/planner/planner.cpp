#include "grip/planner/planner.hpp"

#include <algorithm>
#include <string>

#include "grip/common/saturating_cast.hpp"

namespace grip {

namespace {

std::uint32_t to_steps(double seconds, double step) noexcept {
  return saturating_cast<std::uint32_t>(std::round(seconds / step));
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
  auto field = DistanceField::create(
      grid.width(), grid.height(), grid.resolution(),
      DistanceField::block_for(grid.resolution(), config.rho_cell_m, config.rho_clearance_m));
  if (!field) return field.error();
  auto baseline = BaselineSelection<V>::create(config, grid);
  if (!baseline) return baseline.error();
  std::optional<TurningRho> turning_rho;
  if (config.rho_turning && vehicle.min_turning_radius_m() > 0.0) {
    auto made = TurningRho::create(vehicle.min_turning_radius_m(), grid.resolution());
    if (!made) return made.error();
    turning_rho = std::move(made).value();
  }
  return Planner(vehicle, grid, config, std::move(checker).value(), std::move(field).value(),
                 std::move(baseline).value(), std::move(turning_rho));
}

template <VehicleModel V>
Planner<V>::Planner(const V& vehicle, const OccupancyGrid& grid, const PlannerConfig& config,
                    CollisionChecker checker, DistanceField field, BaselineSelection<V> baseline,
                    std::optional<TurningRho> turning_rho)
    : vehicle_(vehicle),
      config_(config),
      grid_(&grid),
      checker_(std::move(checker)),
      rho_field_(std::move(field)),
      turning_rho_(std::move(turning_rho)),
      tree_(config.max_edges, config.max_trajectories, config.states_per_trajectory(),
            config.steps_per_record),
      heap_(config.max_edges),
      baseline_(std::move(baseline)),
      target_(grid),
      retainment_(config),
      rng_(config.seed),
      log_a_(std::log(config.score_base_a)),
      horizon_step_(1),
      // Time weighs a quarter of top speed: a vehicle accelerating from rest at 0.6 m/s^2
      // would otherwise never look better than its start, and a long meander still loses.
      cost_speed_(0.25 * vehicle.max_speed_m_s()),
      min_edge_records_(std::max<std::uint32_t>(
          1U, static_cast<std::uint32_t>(
                  std::ceil(config.min_edge_duration_s / config.record_step_s() - 1e-9)))),
      min_plan_steps_(
          std::max<std::uint32_t>(config.steps_per_record,
                                  to_steps(config.min_plan_duration_s, config.integration_step_s))),
      max_plan_steps_(std::min<std::uint32_t>(
          to_steps(config.max_plan_duration_s, config.integration_step_s),
          (config.states_per_trajectory() - 1U) * config.steps_per_record)) {}

template <VehicleModel V>
Status Planner<V>::set_problem(const State& start, const Goal& goal) {
  // The messages are built here, at start-up; restart() below is the allocation-free core.
  // Appended piecewise: GCC 12 at -O3 warns falsely (-Wrestrict) on "(" + std::string.
  std::string where;
  if (goal.is_disk()) {
    where = "at (";
    where += std::to_string(goal.x_m());
    where += ", ";
    where += std::to_string(goal.y_m());
    where += ") radius ";
    where += std::to_string(goal.radius_m());
  } else {
    where = "of ";
    where += std::to_string(goal.cells().size());
    where += " cells";
  }
  // A new problem replays the seed's samples and counts work from zero; restart() does not,
  // or a vehicle restarted in the same state would replay the samples that failed there.
  rng_.reseed(config_.seed);
  stats_ = PlannerStats{};
  return problem_status(restart(start, goal, config_.safety_horizon_s), start, where);
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
    case RetainStatus::kGoalNotCells:
    case RetainStatus::kRootNotInTree:
      break;
  }
  return invalid_argument("start: unexpected state");
}

template <VehicleModel V>
RetainStatus Planner<V>::restart(const State& q, const Goal& goal, double horizon_s,
                                 RhoUpdate rho) noexcept {
  if (!vehicle_.validate_state(q)) return RetainStatus::kInvalidState;
  if (!problem_set_) {
    checker_.refresh();
    changed_ = CellBox{};
    changed_noted_ = false;
  } else {
    refresh_checker();
  }
  if (!chassis_free(q)) return RetainStatus::kRootInCollision;
  if (rho == RhoUpdate::kRecompute || !problem_set_) {
    if (const RetainStatus s = set_target(goal); s != RetainStatus::kOk) return s;
  }
  set_horizon(horizon_s);

  baseline_.restart(rho_field_);
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
RetainStatus Planner<V>::set_target(const Goal& goal) noexcept {
  if (const RetainStatus s = target_.assign(goal); s != RetainStatus::kOk) return s;
  rho_field_.compute(*grid_, checker_.clearance(), target_.cells(), config_.rho_clearance_m);
  if (turning_rho_) turning_rho_->forget();
  return RetainStatus::kOk;
}

template <VehicleModel V>
RetainStatus Planner<V>::adopt_goal(const Goal& goal, DistanceField& rho) noexcept {
  GRIP_ASSERT(rho.width() == grid_->width() && rho.height() == grid_->height() &&
              rho.resolution() == grid_->resolution() && rho.block() == rho_field_.block());
  if (goal.is_disk()) return RetainStatus::kGoalNotCells;
  if (const RetainStatus s = target_.assign(goal); s != RetainStatus::kOk) return s;
  std::swap(rho_field_, rho);
  if (turning_rho_) turning_rho_->forget();
  return RetainStatus::kOk;
}

template <VehicleModel V>
void Planner<V>::set_horizon(double horizon_s) noexcept {
  horizon_step_ = std::max<std::uint32_t>(1U, to_steps(horizon_s, config_.integration_step_s));
}

template <VehicleModel V>
void Planner<V>::reset_tree(const State& q) noexcept {
  solution_ = TreeState{};
  heap_.clear();
  cycle_edges_ = 0;
  const EdgeHandle root = tree_.reset(q);
  Edge& r = tree_.edge(root);
  r.priority = 1.0;
  r.rho_m = rho_m(q);
  best_ = TreeState{root, 0};  // until a state at least T away exists
  best_rho_ = r.rho_m;
  best_cost_m_ = std::numeric_limits<double>::infinity();
  baseline_.register_edge(tree_, root, rho_field_);
  if (config_.selection == Selection::kGrip) push_scored(root);
  if (in_goal_region(q)) solution_ = best_;
}

template <VehicleModel V>
RetainStatus Planner<V>::retain(TreeState new_root, const Goal& goal, double horizon_s,
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
  if (!chassis_free(q)) return RetainStatus::kRootInCollision;
  if (rho == RhoUpdate::kRecompute) {
    if (const RetainStatus s = set_target(goal); s != RetainStatus::kOk) return s;
  }
  set_horizon(horizon_s);
  retainment_.run(*this, new_root, grid_->revision() != validated_revision_, newly_blocked);
  validated_revision_ = grid_->revision();
  cycle_edges_ = 0;
  return RetainStatus::kOk;
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
      if (config_.recycle_full_pool && recycle_pool()) continue;
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
bool Planner<V>::recycle_pool() noexcept {
  // The baselines (Fig. 5/6) are compared as the paper ran them: until the pools run out.
  if (config_.selection != Selection::kGrip) return false;
  const std::uint32_t before = tree_.trajectory_count();
  retainment_.recycle(*this);
  cycle_edges_ = 0;
  ++stats_.pool_recycles;
  if (before - tree_.trajectory_count() >= tree_.trajectory_capacity() / 10) return true;
  // What is left is mostly the path to the best state, split at nearly every record: a dead
  // end as far as the search can tell, and too little room to be worth a pass per handful of
  // propagations. Unless it holds a solution, the search starts over from the root with the
  // whole pool; the random stream goes on, so the next attempt differs.
  if (solved()) return false;
  const State root = tree_.edge_state(tree_.root(), tree_.edge(tree_.root()).last);
  reset_tree(root);
  return true;
}

template <VehicleModel V>
bool Planner<V>::iterate() noexcept {
  ++stats_.iterations;
  if (config_.selection != Selection::kGrip) {
    return expand_from(baseline_.select(tree_, target_.cells(), rng_)) != kNoHandle;
  }

  // GRIP (the paper's Sec. III-B): pop the minimum score, propagate from a random state along it,
  // and apply Eq. 2 to the parts of the selected edge whether or not the propagation succeeded.
  const EdgeHandle selected = heap_.pop();
  const double new_priority = std::fma(2.0, tree_.edge(selected).priority, 1.0);
  const double selected_rho_m = tree_.edge(selected).rho_m;
  const EdgeHandle added = expand_from(random_state_along(tree_, selected, rng_));
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
EdgeHandle Planner<V>::expand_from(TreeState from) noexcept {
  const TrajectoryHandle t = tree_.acquire_trajectory();
  GRIP_ASSERT(t != kNoHandle);  // solve() checked the room
  // Random controls (Sec. III-B), and, if configured, now and then the braking maneuver (the
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
  if (attach != from.edge) baseline_.register_edge(tree_, attach, rho_field_);
  baseline_.register_edge(tree_, added, rho_field_);
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
    // Plans are chosen among states at least T from the root (they must cover the next cycle).
    // rho_A* bounds rho from below: a state it shows cannot lower the edge's rho or its best
    // arrival needs no more than that lookup.
    const bool may_arrive_best = from_step + j >= horizon_step_;
    const double time_cost = cost_speed_ * step_time(from_step + j);
    const double rho_bound = rho_a_star_m(q);
    if (rho_bound < out.rho_m || (may_arrive_best && rho_bound + time_cost < out.best_cost_m)) {
      const double rho = turning_rho_ ? rho_m(q) : rho_bound;
      out.rho_m = std::min(out.rho_m, rho);
      if (may_arrive_best && rho + time_cost < out.best_cost_m) {
        out.best_cost_m = rho + time_cost;
        out.best_rho_m = rho;
        out.best_index = recorded;
      }
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
        const double rho = rho_m(tree_.state(t, k));
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
  return chassis_free(q);
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
    if (rho_a_star_m(q) < rho) rho = std::min(rho, rho_m(q));  // rho_A* <= rho
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
