#pragma once
// One planning cycle of the paper's Fig. 2, clock-agnostic so that tests drive it with a fake
// clock. During cycle (t[i-1] : t[i]) the planner plans from q[i], the state the vehicle will
// be in at t[i] on the plan it is executing, for execution during (t[i] : t[i+1]):
//   1. predict q[i]: the state T along the committed plan (or at the end of its braking
//      contingency when there is no plan), and retain the tree below it (Algorithm 1);
//   2. grow the tree (anytime) until the deadline minus a safety margin;
//   3. commit the best path whose duration is at least T and whose end state can brake safely
//      (lazy evaluation); if there is none, the previous plan continues: it is safe for T and
//      ends in a collision-free contingency by construction.
// Allocation-free after create(); never throws.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "grip/common/function_ref.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/planner/planner.hpp"

namespace grip::rt {

struct CycleConfig {
  double cycle_s = 0.05;  // T: the duration of every cycle, a whole number of integration steps
  // The planner stops growing this long before the deadline, and besides early enough to
  // commit the plan (CommitReserve): room for the stalls of a shared machine and for the
  // caller's work after the cycle (default_safety_margin_ms, cycle_sizing.hpp).
  std::int64_t safety_margin_ns = 5'000'000;
  // What committing is taken to cost until the first commit is timed (CommitReserve); 0:
  // nothing.
  std::int64_t commit_reserve_prior_ns = 0;
  std::uint32_t max_plan_pieces = 1024;
  // rho toward a target that has not changed is recomputed every this many cycles (1: every
  // cycle). It is a wavefront over the whole map; where the map changes every cycle, as in
  // exploration, recomputing it each time can take most of a short cycle's budget, while rho
  // only orders the search (collisions are always checked on the current map).
  std::uint32_t rho_refresh_cycles = 1;
};

// The time the next commit will take, learned from the cycles before, so that growth stops
// early enough for it. Exploration's commit (the path selector's pass over the tree, then the
// lazy safety checks back along the chosen path) took 2.1 to 2.7 ms median whether the tree had
// 300 or 4,000 edges (a car at time scale 2), so it is not scaled with the tree: the reserve
// is the 90th percentile of the last kWindow commits. A percentile, not the maximum: a stall
// during one commit would otherwise starve growth for kWindow cycles (stalls are what the
// safety margin is for).
class CommitReserve {
 public:
  static constexpr std::size_t kWindow = 32;

  explicit CommitReserve(std::int64_t prior_ns) noexcept : reserve_ns_(prior_ns) {}
  void note(std::int64_t commit_ns) noexcept;
  std::int64_t ns() const noexcept { return reserve_ns_; }

 private:
  std::array<std::int64_t, kWindow> samples_{};
  std::size_t count_ = 0;  // samples noted, up to kWindow
  std::size_t next_ = 0;   // where the next one goes
  std::int64_t reserve_ns_;
};

// Why a cycle started a fresh tree instead of keeping the last one.
enum class RestartCause : std::uint8_t {
  kNone,             // the tree was kept (or this cycle did not get that far)
  kVehicleOffPlans,  // resynchronise(): the vehicle will start the next plan elsewhere
  kNoPlan,           // no committed plan covers T and the vehicle is not resting at the root
  kRootInCollision,  // the new map puts the chassis at the new root in collision
  kRetainRefused,    // retain() refused for another reason (retain_status says which)
  // The vehicle rests at the root without a plan and the tree kept there reached its capacity
  // (the pools, the share a retained tree may keep, or the cycle's time: it grew no edge)
  // without holding one: a fresh tree is sampled.
  kTreeFullWithoutPlan,
};
std::string_view restart_cause_name(RestartCause cause) noexcept;

// Where an exploring cycle headed and how the path selector chose its plan's end
// (ExplorationDriver, PathSelector), for a cycle trace: a target that flips between groups, or
// plans that creep toward it, show here.
struct ExplorationRecord {
  bool exploring = false;   // the rest holds only when the cycle explored
  bool has_target = false;  // a frontier target had been taken over
  double target_x_m = 0.0;  // its centre: the group's cell nearest the robot by rho_A*
  double target_y_m = 0.0;
  double root_rho_m = std::numeric_limits<double>::infinity();  // from the root to the target
  bool chosen = false;       // the selector found an end (else the plan leads to the root)
  bool sees_target = false;  // by the visibility sum d (else by rho at the end)
  double d_m = std::numeric_limits<double>::infinity();  // d(tr), or rho at its end
  double length_m = 0.0;                                 // l(tr)
};

// What a cycle did.
struct CycleOutcome {
  RetainStatus retain_status = RetainStatus::kOk;  // of the retainment, or of the restart
  RestartCause restart_cause = RestartCause::kNone;
  bool committed = false;       // a new plan was committed
  bool kept_previous = false;   // nothing better: the previous plan continues
  bool plan_available = false;  // a plan covers the next cycle (else the contingency runs)
  bool solved = false;          // the plan committed this cycle ends in the goal region
  bool pool_exhausted = false;  // growth stopped this cycle because the pools were full
  std::uint64_t edges_added = 0;
  std::uint32_t tree_edges = 0;      // after the cycle
  std::uint32_t edges_retained = 0;  // carried over from the previous cycle
  std::uint32_t trajectories_used = 0;
  double plan_duration_s = 0.0;  // of the committed plan, from the new root
  std::int64_t retain_ns = 0;    // re-rooting, pruning and rescoring (or the restart)
  std::int64_t grow_ns = 0;      // anytime growth
  std::int64_t commit_ns = 0;    // choosing and extracting the plan after growth
  // Real time: the room growth left for committing (CommitReserve) when it stopped.
  std::int64_t commit_reserve_ns = 0;
  // The caller's work before the cycle (map updates, the vehicle's state, the choice of a
  // target), set by the caller: a cycle trace then accounts for the whole cycle.
  std::int64_t prepare_ns = 0;
  // Where the cycle planned from (q[i]: the root, where its plan starts), set by the caller.
  double start_x_m = 0.0;
  double start_y_m = 0.0;
  double start_theta = 0.0;
  ExplorationRecord exploration;  // set by the caller

  // The tree was rebuilt from the predicted state.
  bool restarted() const noexcept { return restart_cause != RestartCause::kNone; }
};

template <VehicleModel V>
class ReplanningCycle {
 public:
  using State = typename V::State;

  // The planner needs steps_per_record == 1 and T a whole number of integration steps.
  static Result<ReplanningCycle> create(const V& vehicle, const OccupancyGrid& grid,
                                        PlannerConfig planner_config, const CycleConfig& config);

  // Start-up: the vehicle at rest at q0 (or moving: any valid state) and the first target.
  Status start(const State& q0, const Goal& goal);
  // The target of the next cycles (a frontier, a goal). A cells goal (exploration: a frontier
  // group's approach cells) is copied; cells beyond the grid's cell count are dropped. With
  // `rho`, rho toward the cells computed elsewhere (Planner::adopt_goal; `rho` receives the
  // previous field): the cycles that follow keep it rather than run the wavefront themselves,
  // and rho_refresh_cycles counts from here. Should the planner refuse it (a disk, or cells it
  // refuses), the next cycle computes rho toward `goal` itself.
  void set_goal(const Goal& goal, DistanceField* rho = nullptr) noexcept;
  // The current target; a cells goal views this cycle's copy, valid until the next set_goal().
  const Goal& goal() const noexcept { return goal_; }

  // Where cells became non-free since the last cycle (map updates): the next retainment checks
  // only states within the chassis' reach of it. Without any note, a changed grid is checked
  // everywhere.
  void note_newly_blocked(const CellBox& box) noexcept {
    newly_blocked_.add(box);
    blocked_noted_ = true;
  }

  // Where cells became free or stopped being free since the last cycle: the planner refreshes
  // its clearance only near it (Planner::note_changed). Every change must be noted, or none.
  void note_changed(const CellBox& box) noexcept { planner_.note_changed(box); }

  // The vehicle is not where the plans put it (a plan came late or was refused, it brakes on
  // its contingency, it goes on with a plan this tree did not commit): the next run starts a
  // fresh tree at q, the state the vehicle will hold at that plan's start.
  void resynchronise(const State& q) noexcept;
  // Where the next cycle's plan starts: where resynchronise() put it, else, if the vehicle
  // follows the committed plan, T along it, or, when it is shorter than T or there is none,
  // where braking at its end leads.
  State next_plan_start() const noexcept;

  // Runs one cycle, growing the tree until now_ns() >= deadline_ns - safety margin - the
  // commit's reserve.
  CycleOutcome run(FunctionRef<std::int64_t()> now_ns, std::int64_t deadline_ns) noexcept;
  // The same, with the state the plan should lead to chosen by `choose_target` instead of the
  // planner's best_state() (exploration: PathSelector::select); it is then cut back to the
  // latest state that can brake safely, at least T from the root, as usual. `plan_chosen` is
  // called once the plan's end is settled (after that cut), before the plan is extracted: a
  // thread that publishes the plan can wake meanwhile.
  CycleOutcome run(
      FunctionRef<std::int64_t()> now_ns, std::int64_t deadline_ns,
      FunctionRef<TreeState(const Planner<V>&)> choose_target,
      FunctionRef<void()> plan_chosen = [] {}) noexcept;
  // Lockstep (a simulation that waits for each plan): growth adds `edges` edges, fewer only
  // when the goal is reached, the pools run out or 20 x `edges` selections added none,
  // however long it takes, so that a seed reproduces a run exactly. now_ns only times the
  // phases.
  CycleOutcome run_for_edges(
      FunctionRef<std::int64_t()> now_ns, std::uint64_t edges,
      FunctionRef<TreeState(const Planner<V>&)> choose_target,
      FunctionRef<void()> plan_chosen = [] {}) noexcept;

  // The committed plan, from the root of the current cycle (the state at the start of the
  // next cycle's execution); empty when this cycle has none.
  const VectorView<PlanStep>& plan() const noexcept { return plan_; }
  // The state the plan starts from, and the one it reaches after T (the next root).
  const State& plan_start() const noexcept;
  const Planner<V>& planner() const noexcept { return planner_; }
  // The end of the committed plan in the tree (empty: braking).
  TreeState committed() const noexcept { return committed_; }
  std::uint32_t cycle_steps() const noexcept { return cycle_steps_; }

 private:
  ReplanningCycle(Planner<V> planner, const CycleConfig& config, std::uint32_t cycle_steps);
  CycleOutcome run_growing(FunctionRef<std::int64_t()> now_ns, FunctionRef<bool()> stop_growing,
                           FunctionRef<TreeState(const Planner<V>&)> choose_target,
                           FunctionRef<void()> plan_chosen) noexcept;
  State predicted_state_without_plan() const noexcept;
  // The tree state the next cycle's plan starts from, if the tree has it.
  TreeState next_root() const noexcept;
  void commit(TreeState s) noexcept;

  Planner<V> planner_;
  CycleConfig config_;
  std::uint32_t cycle_steps_;
  Goal goal_;  // a cells goal views goal_cells_
  BoundedVector<std::uint32_t> goal_cells_;
  bool goal_changed_ = true;  // since the last retainment or restart
  bool rho_adopted_ = false;  // rho toward the goal came with it (set_goal with a field)
  std::uint32_t cycles_since_rho_ = 0;
  TreeState committed_;             // end of the committed plan in the tree; empty: braking
  bool full_without_plan_ = false;  // the last cycle reached the tree's capacity, no plan
  CellBox newly_blocked_;
  bool blocked_noted_ = false;
  BoundedVector<PlanStep> plan_;
  std::optional<State> resync_;
  CommitReserve commit_reserve_;
};

extern template class ReplanningCycle<DdVelocity>;
extern template class ReplanningCycle<DdAcceleration>;
extern template class ReplanningCycle<Car>;

}  // namespace grip::rt
