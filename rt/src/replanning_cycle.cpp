#include "grip/rt/replanning_cycle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "grip/common/enum_names.hpp"

namespace grip::rt {

namespace {
constexpr std::array<NamedValue<RestartCause>, 6> kRestartCauseNames{{
    {RestartCause::kNone, "none"},
    {RestartCause::kVehicleOffPlans, "vehicle-off-plans"},
    {RestartCause::kNoPlan, "no-plan"},
    {RestartCause::kRootInCollision, "root-in-collision"},
    {RestartCause::kRetainRefused, "retain-refused"},
    {RestartCause::kTreeFullWithoutPlan, "tree-full-without-plan"},
}};
}  // namespace

std::string_view restart_cause_name(RestartCause cause) noexcept {
  return name_in(kRestartCauseNames, cause);
}

void CommitReserve::note(std::int64_t commit_ns) noexcept {
  samples_[next_] = commit_ns;
  next_ = (next_ + 1) % kWindow;
  count_ = std::min(count_ + 1, kWindow);
  std::array<std::int64_t, kWindow> sorted = samples_;
  const auto end = sorted.begin() + static_cast<std::ptrdiff_t>(count_);
  const auto p90 = sorted.begin() + static_cast<std::ptrdiff_t>(count_ - 1 - count_ / 10);
  std::nth_element(sorted.begin(), p90, end);
  reserve_ns_ = *p90;
}

template <VehicleModel V>
Result<ReplanningCycle<V>> ReplanningCycle<V>::create(const V& vehicle, const OccupancyGrid& grid,
                                                      PlannerConfig planner_config,
                                                      const CycleConfig& config) {
  if (!std::isfinite(config.cycle_s) || config.cycle_s <= 0.0) {
    return invalid_argument("cycle: T (cycle_s) must be > 0 (got " +
                            std::to_string(config.cycle_s) + ")");
  }
  const double steps = config.cycle_s / planner_config.integration_step_s;
  if (std::abs(steps - std::round(steps)) > 1e-6 || std::round(steps) < 1.0) {
    return invalid_argument("cycle: T (" + std::to_string(config.cycle_s) +
                            " s) must be a whole number of integration steps (" +
                            std::to_string(planner_config.integration_step_s) + " s)");
  }
  if (config.safety_margin_ns < 0 || config.max_plan_pieces == 0) {
    return invalid_argument("cycle: safety margin must be >= 0 and max_plan_pieces > 0");
  }
  if (config.commit_reserve_prior_ns < 0) {
    return invalid_argument("cycle: commit_reserve_prior_ns must be >= 0 (got " +
                            std::to_string(config.commit_reserve_prior_ns) + ")");
  }
  planner_config.steps_per_record = 1;  // every checked state is a recorded one (retainment)
  planner_config.stop_at_goal = false;  // once solved, cycles improve the solution
  planner_config.safety_horizon_s = config.cycle_s;
  planner_config.selection = Selection::kGrip;
  // Near an inevitable collision only braking keeps the state at T safe.
  if (planner_config.braking_control_fraction == 0.0)
    planner_config.braking_control_fraction = 0.125;
  auto planner = Planner<V>::create(vehicle, grid, planner_config);
  if (!planner) return planner.error();
  return ReplanningCycle(std::move(planner).value(), config,
                         static_cast<std::uint32_t>(std::llround(steps)));
}

template <VehicleModel V>
ReplanningCycle<V>::ReplanningCycle(Planner<V> planner, const CycleConfig& config,
                                    std::uint32_t cycle_steps)
    : planner_(std::move(planner)),
      config_(config),
      cycle_steps_(cycle_steps),
      goal_cells_(planner_.checker().grid().cell_count()),
      plan_(config.max_plan_pieces),
      commit_reserve_(config.commit_reserve_prior_ns) {}

template <VehicleModel V>
void ReplanningCycle<V>::set_goal(const Goal& goal, DistanceField* rho) noexcept {
  if (goal.is_disk()) {
    goal_ = goal;
  } else {
    if (goal.cells().data() != goal_cells_.span().data()) {  // not goal() again
      goal_cells_.clear();
      for (const std::uint32_t c : goal.cells()) {
        if (!goal_cells_.push_back(c)) break;
      }
    }
    goal_ = Goal::cells(goal_cells_.span());
  }
  goal_changed_ = true;
  rho_adopted_ = false;
  if (rho != nullptr && planner_.adopt_goal(goal_, *rho) == RetainStatus::kOk) {
    goal_changed_ = false;
    rho_adopted_ = true;
  }
}

template <VehicleModel V>
Status ReplanningCycle<V>::start(const State& q0, const Goal& goal) {
  if (auto s = planner_.set_problem(q0, goal); !s) return s;
  set_goal(goal);
  committed_ = TreeState{};
  full_without_plan_ = false;
  plan_.clear();
  return Ok{};
}

template <VehicleModel V>
const typename ReplanningCycle<V>::State& ReplanningCycle<V>::plan_start() const noexcept {
  const TreeState root = planner_.root_state();
  return planner_.tree().edge_state(root.edge, root.index);
}

template <VehicleModel V>
typename ReplanningCycle<V>::State ReplanningCycle<V>::predicted_state_without_plan()
    const noexcept {
  // The committed plan (if any) is shorter than T: the vehicle drives it to its end and then
  // brakes for the rest of the cycle, as the controller does (its contingency).
  std::uint32_t steps_left = cycle_steps_;
  State q = plan_start();
  if (planner_.contains(committed_)) {
    const TreeState end = committed_;
    const auto& tree = planner_.tree();
    const std::uint32_t planned = tree.step_of(end.edge, end.index);
    q = tree.edge_state(end.edge, end.index);
    steps_left -= std::min(steps_left, planned);
  }
  return braked_state(planner_.vehicle(), q, steps_left, planner_.config().integration_step_s);
}

template <VehicleModel V>
TreeState ReplanningCycle<V>::next_root() const noexcept {
  if (committed_.edge != kNoHandle) return planner_.state_at_step(committed_, cycle_steps_);
  // No plan: the vehicle brakes from the root, and once it rests there the next plan starts
  // where the tree does. Growing that tree on beats restarting it every cycle: a vehicle that
  // needs more than one cycle's growth to find a safe plan would otherwise never move again.
  // Once that tree reaches its capacity without a plan (its pools, or the time a cycle has to
  // retain and grow it) it cannot grow on, or only by pruning what scores worst, which in a
  // dead end is the way out: a fresh one is sampled (a car at a time scale of 10 otherwise sat
  // for minutes with a full tree and no plan).
  const TreeState root = planner_.root_state();
  if (root.edge != kNoHandle && planner_.vehicle().is_stopped(plan_start()) &&
      !full_without_plan_) {
    return root;
  }
  return TreeState{};
}

template <VehicleModel V>
void ReplanningCycle<V>::resynchronise(const State& q) noexcept {
  resync_ = q;
}

template <VehicleModel V>
typename ReplanningCycle<V>::State ReplanningCycle<V>::next_plan_start() const noexcept {
  if (resync_) return *resync_;
  const TreeState root = next_root();
  if (root.edge == kNoHandle) return predicted_state_without_plan();
  return planner_.tree().edge_state(root.edge, root.index);
}

template <VehicleModel V>
CycleOutcome ReplanningCycle<V>::run(FunctionRef<std::int64_t()> now_ns,
                                     std::int64_t deadline_ns) noexcept {
  return run(now_ns, deadline_ns,
             [](const Planner<V>& planner) noexcept { return planner.best_state(); });
}

template <VehicleModel V>
CycleOutcome ReplanningCycle<V>::run(FunctionRef<std::int64_t()> now_ns, std::int64_t deadline_ns,
                                     FunctionRef<TreeState(const Planner<V>&)> choose_target,
                                     FunctionRef<void()> plan_chosen) noexcept {
  const std::int64_t reserve = commit_reserve_.ns();
  const std::int64_t stop_at = deadline_ns - config_.safety_margin_ns - reserve;
  CycleOutcome out = run_growing(
      now_ns, [&] { return now_ns() >= stop_at; }, choose_target, plan_chosen);
  out.commit_reserve_ns = reserve;
  return out;
}

template <VehicleModel V>
CycleOutcome ReplanningCycle<V>::run_for_edges(
    FunctionRef<std::int64_t()> now_ns, std::uint64_t edges,
    FunctionRef<TreeState(const Planner<V>&)> choose_target,
    FunctionRef<void()> plan_chosen) noexcept {
  // Iterations are bounded too: where no selection can add an edge (every random plan from the
  // tree collides at once), the edge count alone would never be reached.
  const PlannerStats& stats = planner_.stats();
  const std::uint64_t stop_at = stats.edges_added + edges;
  const std::uint64_t give_up_at = stats.iterations + 20 * edges;
  return run_growing(
      now_ns, [&] { return stats.edges_added >= stop_at || stats.iterations >= give_up_at; },
      choose_target, plan_chosen);
}

template <VehicleModel V>
CycleOutcome ReplanningCycle<V>::run_growing(
    FunctionRef<std::int64_t()> now_ns, FunctionRef<bool()> stop_growing,
    FunctionRef<TreeState(const Planner<V>&)> choose_target,
    FunctionRef<void()> plan_chosen) noexcept {
  CycleOutcome out;
  const std::int64_t cycle_start = now_ns();
  // 1. The new root: T along the committed plan, when the plan covers T (or the root itself,
  // for a vehicle resting there without a plan).
  const TreeState next_root = resync_ ? TreeState{} : this->next_root();
  const RhoUpdate rho =
      !rho_adopted_ && (goal_changed_ || cycles_since_rho_ + 1 >= config_.rho_refresh_cycles)
          ? RhoUpdate::kRecompute
          : RhoUpdate::kKeep;
  if (next_root.edge != kNoHandle) {
    const CellBox* blocked = blocked_noted_ ? &newly_blocked_ : nullptr;
    out.retain_status = planner_.retain(next_root, goal_, config_.cycle_s, blocked, rho);
    out.edges_retained = planner_.last_retain().edges_kept;
  } else {
    out.retain_status = RetainStatus::kRootNotInTree;
  }
  if (out.retain_status != RetainStatus::kOk) {
    const State q = resync_ ? *resync_
                    : next_root.edge != kNoHandle
                        ? planner_.tree().edge_state(next_root.edge, next_root.index)
                        : predicted_state_without_plan();
    out.restart_cause = resync_ ? RestartCause::kVehicleOffPlans
                        : next_root.edge == kNoHandle
                            ? (full_without_plan_ && planner_.vehicle().is_stopped(plan_start())
                                   ? RestartCause::kTreeFullWithoutPlan
                                   : RestartCause::kNoPlan)
                        : out.retain_status == RetainStatus::kRootInCollision
                            ? RestartCause::kRootInCollision
                            : RestartCause::kRetainRefused;
    resync_.reset();
    // rho as for a retainment: a restart is no reason to recompute it, and the whole-map
    // wavefront would take the cycle's growth (a vehicle restarted every cycle never moved).
    out.retain_status = planner_.restart(q, goal_, config_.cycle_s, rho);
    committed_ = TreeState{};
  } else if (!planner_.contains(committed_)) {
    committed_ = TreeState{};  // the new map or T cut the rest of the previous plan
  }

  cycles_since_rho_ = rho == RhoUpdate::kRecompute || rho_adopted_ ? 0 : cycles_since_rho_ + 1;
  goal_changed_ = false;
  rho_adopted_ = false;
  newly_blocked_ = CellBox{};
  blocked_noted_ = false;
  out.retain_ns = now_ns() - cycle_start;

  // 2. Anytime growth, stopping itself before the deadline (or after its edges).
  const std::uint64_t edges_before = planner_.stats().edges_added;
  if (out.retain_status == RetainStatus::kOk) {
    const SolveResult grown = planner_.solve(stop_growing);
    out.pool_exhausted = grown.reason == StopReason::kPoolExhausted;  // this cycle's growth
  }
  out.edges_added = planner_.stats().edges_added - edges_before;

  const std::int64_t commit_start = now_ns();
  out.grow_ns = commit_start - cycle_start - out.retain_ns;
  // 3. Commit: the solution if there is one, else the state closest to the target; its path
  // must cover the next cycle and end where the vehicle can brake safely.
  const TreeState candidate =
      out.retain_status == RetainStatus::kOk
          ? planner_.committable_state(choose_target(planner_), cycle_steps_)
          : TreeState{};
  plan_chosen();
  if (candidate.edge != kNoHandle) {
    commit(candidate);
    out.committed = true;
  } else if (committed_.edge != kNoHandle) {
    out.kept_previous = true;  // still in the tree, still safe for T
    commit(committed_);
  } else {
    committed_ = TreeState{};
    plan_.clear();
  }
  out.commit_ns = now_ns() - commit_start;
  commit_reserve_.note(out.commit_ns);
  out.plan_available = committed_.edge != kNoHandle;
  // The tree reached its capacity and still holds no plan: the pools, the share of them a
  // retained tree may keep, or what the cycle's time allows (retaining it and reserving the
  // commit left no time to grow it: a car at rest with 1,100 edges at a time scale of 10).
  full_without_plan_ =
      !out.plan_available && out.retain_status == RetainStatus::kOk &&
      (out.pool_exhausted || planner_.last_retain().pruned_for_room > 0 || out.edges_added == 0);
  // The committed plan reaches the target only if it was not shortened for safety.
  const TreeState solution = planner_.best_state();
  out.solved = planner_.solved() && out.committed && candidate.edge == solution.edge &&
               candidate.index == solution.index;
  const auto& tree = planner_.tree();
  out.tree_edges = tree.edge_count();
  out.trajectories_used = tree.trajectory_count();
  if (out.plan_available) {
    out.plan_duration_s =
        tree.step_of(committed_.edge, committed_.index) * planner_.config().integration_step_s;
  }
  return out;
}

template <VehicleModel V>
void ReplanningCycle<V>::commit(TreeState s) noexcept {
  committed_ = s;
  if (!planner_.extract_plan(s, plan_)) {
    // More pieces than max_plan_pieces: no plan is committed and the vehicle brakes. The
    // configuration decides this at start-up; a plan of 1 s pieces over minutes never gets here.
    committed_ = TreeState{};
    plan_.clear();
  }
}

template class ReplanningCycle<DdVelocity>;
template class ReplanningCycle<DdAcceleration>;
template class ReplanningCycle<Car>;

}  // namespace grip::rt
