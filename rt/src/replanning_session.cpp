#include "grip/rt/replanning_session.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace grip::rt {

namespace {

std::int64_t ns_of(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }

template <VehicleModel V>
typename V::State state_of(const VehicleSample& sample) noexcept {
  typename V::State q;
  for (int i = 0; i < V::kStateDim; ++i) q[i] = sample.state[static_cast<std::size_t>(i)];
  return q;
}

}  // namespace

template <VehicleModel V>
Result<ReplanningSession<V>> ReplanningSession<V>::create(const V& vehicle, OccupancyGrid grid,
                                                          const SessionConfig& config) {
  if (!(config.cycle_s > 0.0) || !(config.budget_s > 0.0) || config.max_plan_steps == 0) {
    return invalid_argument("a session needs cycle_s > 0, budget_s > 0 and max_plan_steps > 0");
  }
  return ReplanningSession(vehicle, std::move(grid), config);
}

template <VehicleModel V>
Status ReplanningSession<V>::create_cycle(double time_scale, bool lockstep, bool explore) {
  time_scale_ = time_scale;
  lockstep_ = lockstep;
  period_wall_ns_ = ns_of(config_.cycle_s / time_scale);
  CycleBudget budget;
  budget.cycle_s = config_.cycle_s;
  budget.budget_ms = config_.budget_s * 1e3 / time_scale;
  budget.margin_ms = config_.margin_s >= 0.0 ? config_.margin_s * 1e3 / time_scale : -1.0;
  budget.max_edges = config_.max_edges;
  budget.lockstep_edges = lockstep ? config_.lockstep_edges : 0;
  budget.seed = config_.seed;
  budget.safety = !config_.no_safety;
  budget.tuning = config_.tuning;
  auto sized = size_cycle(budget);
  if (!sized) return sized.error();
  sizing_ = std::move(sized).value();
  max_edges_ = sizing_.planner.max_edges;
  CycleConfig& cycle_config = sizing_.cycle;
  if (explore) {
    // Until it has timed a commit (the path selector's pass over the tree), the cycle takes
    // 1 us per pool edge for it.
    cycle_config.commit_reserve_prior_ns = static_cast<std::int64_t>(max_edges_) * 1'000;
  }
  // Exploring, rho comes with each target (ExplorationTarget::rho); the target thread takes a
  // cycle to choose, so the cycle's own refresh is only a fallback for a late one.
  cycle_config.rho_refresh_cycles =
      explore ? 2 * config_.target_refresh_cycles + 1 : config_.target_refresh_cycles;
  auto cycle = ReplanningCycle<V>::create(vehicle_, grid_, sizing_.planner, cycle_config);
  if (!cycle) return cycle.error();
  cycle_.emplace(std::move(cycle).value());
  ledger_.emplace(vehicle_, sizing_.planner.integration_step_s, config_.max_plan_steps);
  return Ok{};
}

template <VehicleModel V>
Status ReplanningSession<V>::start(const VehicleSample& state, const Goal& goal) {
  if (Status s = cycle_->start(state_of<V>(state), goal); !s) return s;
  note_state(state);
  return Ok{};
}

template <VehicleModel V>
void ReplanningSession<V>::note_state(const VehicleSample& state) noexcept {
  last_state_ = state;
  if (!lockstep_) lead_.observe(state.plan_arrival_cycle, state.plan_arrival_margin_ns);
}

template <VehicleModel V>
void ReplanningSession<V>::note_release(std::int64_t release_ns) noexcept {
  if (last_release_ns_ != 0 && release_ns - last_release_ns_ > period_wall_ns_) {
    misses_ += static_cast<std::uint64_t>((release_ns - last_release_ns_) / period_wall_ns_ - 1);
  }
  last_release_ns_ = release_ns;
}

template <VehicleModel V>
void ReplanningSession<V>::chain_plan_start(std::int64_t release_ns,
                                            const VehicleClock& clock) noexcept {
  // Committed before the deadline, the plan reaches the vehicle before it is due (a late plan is
  // refused). The chain is re-anchored only when a plan would start too early (more than T/8
  // before the next release: the clock estimate moved) or needlessly late (more than 1.5 T
  // after it); check_vehicle_follows then moves the tree to the new start.
  const auto cycle_ns = static_cast<std::uint64_t>(ns_of(config_.cycle_s));
  const auto wanted = static_cast<std::uint64_t>(
      clock.vehicle_ns(release_ns + period_wall_ns_, time_scale_) + lead_.lead_ns());
  plan_start_ns_ += cycle_ns;
  const bool too_early = plan_start_ns_ + cycle_ns / 8 < wanted;
  const bool too_late = plan_start_ns_ > wanted + cycle_ns + cycle_ns / 2;
  if ((too_early || too_late) && last_state_) {
    const std::uint64_t stamp_ns = last_state_->stamp_ns;
    const double cycles =
        std::ceil(static_cast<double>(static_cast<std::int64_t>(wanted - stamp_ns)) /
                  static_cast<double>(cycle_ns));
    plan_start_ns_ = stamp_ns + static_cast<std::uint64_t>(std::max(0.0, cycles)) * cycle_ns;
  }
}

template <VehicleModel V>
void ReplanningSession<V>::set_plan_start_after(const VehicleSample& state) noexcept {
  plan_start_ns_ = state.stamp_ns + static_cast<std::uint64_t>(ns_of(config_.cycle_s));
}

template <VehicleModel V>
CycleOutcome ReplanningSession<V>::run(FunctionRef<std::int64_t()> now_ns, std::int64_t deadline_ns,
                                       FunctionRef<TreeState(const Planner<V>&)> choose,
                                       FunctionRef<void()> plan_chosen) noexcept {
  CycleOutcome out =
      lockstep_ ? cycle_->run_for_edges(now_ns, config_.lockstep_edges, choose, plan_chosen)
                : cycle_->run(now_ns, deadline_ns, choose, plan_chosen);
  ++cycles_;
  if (!lockstep_ && now_ns() > deadline_ns) ++misses_;
  return out;
}

template <VehicleModel V>
SentPlan<V> ReplanningSession<V>::send_plan(const CycleOutcome& outcome) noexcept {
  // Planned during (t[i-1], t[i]) for execution from t[i]. Without a plan an empty one is sent:
  // the vehicle drives the plan it executes to its end, where its braking was checked
  // (idl/plan.idl), and the next cycle starts a fresh tree where the ledger forecasts it then.
  std::span<const PlanStep> steps;
  if (outcome.plan_available) {
    steps = std::span<const PlanStep>(cycle_->plan().data(), cycle_->plan().size());
  }
  steps = steps.first(std::min<std::size_t>(steps.size(), config_.max_plan_steps));
  SentPlan<V> sent{cycles_, plan_start_ns_, cycle_->plan_start(),
                   last_state_ ? last_state_->sequence_number : std::uint64_t{0}, steps};
  ledger_->record(cycles_, plan_start_ns_, sent.from, steps);
  if (!outcome.plan_available) {
    follow_forecast(plan_start_ns_ + static_cast<std::uint64_t>(ns_of(config_.cycle_s)));
  }
  plans_committed_ += outcome.plan_available ? 1 : 0;
  return sent;
}

// The next tree starts where the vehicle will be at until_ns, from the last measured state and
// the plans sent since, when that is not where the cycle puts it.
template <VehicleModel V>
void ReplanningSession<V>::follow_forecast(std::uint64_t until_ns) noexcept {
  if (!last_state_ || until_ns < last_state_->stamp_ns) return;
  const auto there = ledger_->forecast(state_of<V>(*last_state_), last_state_->stamp_ns,
                                       last_state_->plan_cycle, until_ns);
  if (!there) return;  // it executes a plan older than the ledger: nothing to go by
  if (states_match(there->state, cycle_->next_plan_start())) return;
  cycle_->resynchronise(there->state);
  ++resyncs_;
}

template class ReplanningSession<DdVelocity>;
template class ReplanningSession<DdAcceleration>;
template class ReplanningSession<Car>;

}  // namespace grip::rt
