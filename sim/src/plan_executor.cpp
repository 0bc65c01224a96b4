#include "grip/sim/plan_executor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "grip/common/enum_names.hpp"

namespace grip::sim {

namespace {

constexpr double kNsPerS = 1e9;
// Longest plan piece accepted, so that sums of 1024 pieces stay far inside int64 nanoseconds.
constexpr double kMaxPieceDurationS = 1e6;

constexpr std::array<NamedValue<PlanVerdict>, 7> kVerdictNames{{
    {PlanVerdict::kAccepted, "accepted"},
    {PlanVerdict::kEmpty, "empty"},
    {PlanVerdict::kTooManySteps, "too-many-steps"},
    {PlanVerdict::kBadDuration, "bad-duration"},
    {PlanVerdict::kBadControl, "bad-control"},
    {PlanVerdict::kStartsInThePast, "starts-in-the-past"},
    {PlanVerdict::kQueueFull, "queue-full"},
}};

constexpr std::array<NamedValue<ExecutorMode>, 3> kModeNames{{
    {ExecutorMode::kAtRest, "at-rest"},
    {ExecutorMode::kExecuting, "executing"},
    {ExecutorMode::kBraking, "braking"},
}};

std::string pose_text(double x, double y, double theta) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  std::string text = "(";
  text += std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(theta) + ")";
  return text;
}

}  // namespace

std::string_view plan_verdict_name(PlanVerdict v) noexcept { return name_in(kVerdictNames, v); }
std::string_view executor_mode_name(ExecutorMode m) noexcept { return name_in(kModeNames, m); }

Status ExecutorConfig::validate() const {
  if (!std::isfinite(step_s) || step_s < 1e-6 || step_s > 1.0) {
    return invalid_argument("executor step_s must be in [1e-6, 1] s (got " +
                            std::to_string(step_s) + ")");
  }
  if (max_plan_steps == 0) return invalid_argument("executor max_plan_steps must be >= 1 (got 0)");
  if (max_queued_plans == 0) {
    return invalid_argument("executor max_queued_plans must be >= 1 (got 0)");
  }
  return Ok{};
}

template <VehicleModel V>
Result<PlanExecutor<V>> PlanExecutor<V>::create(const V& vehicle, const OccupancyGrid& truth,
                                                const State& start, std::int64_t start_time_ns,
                                                const ExecutorConfig& config) {
  static_assert(V::Control::RowsAtCompileTime == 2, "plans carry two control components");
  if (auto s = config.validate(); !s) return s.error();
  if (auto s = vehicle.validate_state(start); !s) return s.error();
  if (!vehicle.is_stopped(start)) {
    return invalid_argument("executor: the start state must be at rest");
  }
  auto checker = CollisionChecker::create(truth, vehicle.footprint(), 0.0);
  if (!checker) return checker.error();
  const double x = state_x(start);
  const double y = state_y(start);
  const double theta = state_theta(start);
  if (!checker->is_free(x, y, theta)) {
    return invalid_argument("executor: the chassis at the start pose " + pose_text(x, y, theta) +
                            " touches an obstacle of the ground truth or leaves the map");
  }
  return PlanExecutor(vehicle, std::move(checker).value(), start, start_time_ns, config);
}

template <VehicleModel V>
PlanExecutor<V>::PlanExecutor(const V& vehicle, CollisionChecker checker, const State& start,
                              std::int64_t start_time_ns, const ExecutorConfig& config)
    : vehicle_(vehicle),
      checker_(std::move(checker)),
      config_(config),
      step_ns_(std::llround(config.step_s * kNsPerS)),
      state_(start),
      control_(Control::Zero()),
      now_ns_(start_time_ns),
      slots_(config.max_queued_plans + 1U),
      queue_(config.max_queued_plans) {
  for (PlanSlot& slot : slots_) {
    slot.steps.reserve(config.max_plan_steps);
    slot.end_ns.reserve(config.max_plan_steps);
  }
  events_.reserve(config.max_collision_events);
  speeds_.reserve(config.max_speed_samples);
}

template <VehicleModel V>
PlanVerdict PlanExecutor<V>::submit(std::span<const PlanStep> steps, std::int64_t start_time_ns,
                                    const std::optional<State>& predicted_start,
                                    std::uint64_t tag) noexcept {
  const PlanVerdict verdict = [&] {
    if (steps.empty()) return PlanVerdict::kEmpty;
    if (steps.size() > config_.max_plan_steps) return PlanVerdict::kTooManySteps;
    if (start_time_ns < now_ns_) return PlanVerdict::kStartsInThePast;
    for (const PlanStep& s : steps) {
      if (!std::isfinite(s.duration_s) || s.duration_s <= 0.0 ||
          s.duration_s > kMaxPieceDurationS || std::llround(s.duration_s * kNsPerS) == 0) {
        return PlanVerdict::kBadDuration;
      }
      const Control u(s.control[0], s.control[1]);
      if (!std::isfinite(u[0]) || !std::isfinite(u[1])) return PlanVerdict::kBadControl;
      // The model's check builds a message when it fails: only this rejection path allocates.
      if constexpr (requires { vehicle_.validate_control(u); }) {
        if (!vehicle_.validate_control(u).ok()) return PlanVerdict::kBadControl;
      }
    }
    if (start_time_ns > std::numeric_limits<std::int64_t>::max() -
                            static_cast<std::int64_t>(static_cast<double>(steps.size()) *
                                                      kMaxPieceDurationS * kNsPerS)) {
      return PlanVerdict::kBadDuration;
    }
    return PlanVerdict::kAccepted;
  }();
  if (verdict != PlanVerdict::kAccepted) {
    ++stats_.plans_rejected;
    return verdict;
  }
  return enqueue(steps, start_time_ns, predicted_start, tag);
}

template <VehicleModel V>
PlanVerdict PlanExecutor<V>::submit_empty(std::int64_t start_time_ns) noexcept {
  if (start_time_ns < now_ns_) {
    ++stats_.plans_rejected;
    return PlanVerdict::kStartsInThePast;
  }
  return enqueue({}, start_time_ns, std::nullopt, 0);
}

template <VehicleModel V>
PlanVerdict PlanExecutor<V>::enqueue(std::span<const PlanStep> steps, std::int64_t start_time_ns,
                                     const std::optional<State>& predicted_start,
                                     std::uint64_t tag) noexcept {
  // Queued plans starting at or after this one are superseded (they sit at the queue's tail).
  std::size_t keep = queue_size_;
  while (keep > 0 && slots_[queue_[keep - 1]].start_ns >= start_time_ns) --keep;
  if (keep == queue_.size()) {
    ++stats_.plans_rejected;
    return PlanVerdict::kQueueFull;
  }
  stats_.plans_superseded += queue_size_ - keep;
  queue_size_ = keep;
  // A free slot exists: slots_ has one more slot than the queue, for the executed plan.
  std::size_t free_slot = 0;
  for (;; ++free_slot) {
    GRIP_ASSERT(free_slot < slots_.size());
    const bool executed = mode_ == ExecutorMode::kExecuting && free_slot == current_;
    const bool queued =
        std::find(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(queue_size_),
                  free_slot) != queue_.begin() + static_cast<std::ptrdiff_t>(queue_size_);
    if (!executed && !queued) break;
  }
  PlanSlot& slot = slots_[free_slot];
  slot.steps.assign(steps.begin(), steps.end());
  slot.end_ns.clear();
  std::int64_t t = start_time_ns;
  for (const PlanStep& s : steps) {
    t += std::llround(s.duration_s * kNsPerS);
    slot.end_ns.push_back(t);
  }
  slot.start_ns = start_time_ns;
  slot.predicted_start = predicted_start;
  slot.tag = tag;
  queue_[queue_size_++] = free_slot;
  ++stats_.plans_accepted;
  return PlanVerdict::kAccepted;
}

template <VehicleModel V>
void PlanExecutor<V>::abandon_plans() noexcept {
  stats_.plans_superseded += queue_size_;
  queue_size_ = 0;
  if (mode_ == ExecutorMode::kExecuting) begin_contingency(ContingencyCause::kAbandoned);
}

template <VehicleModel V>
void PlanExecutor<V>::begin_contingency(ContingencyCause cause) noexcept {
  ++stats_.contingencies;
  switch (cause) {
    case ContingencyCause::kRanOut:
      ++stats_.plans_ran_out;
      break;
    case ContingencyCause::kAbandoned:
      ++stats_.plans_abandoned;
      break;
  }
  mode_ = contingency_mode(vehicle_, state_);
  if (mode_ == ExecutorMode::kAtRest) control_ = Control::Zero();
}

template <VehicleModel V>
void PlanExecutor<V>::start_queued_plan() noexcept {
  const std::size_t slot_index = queue_[0];
  std::copy(queue_.begin() + 1, queue_.begin() + static_cast<std::ptrdiff_t>(queue_size_),
            queue_.begin());
  --queue_size_;
  const PlanSlot& slot = slots_[slot_index];
  if (slot.steps.empty()) return;  // an empty plan: the vehicle goes on as it was
  bool mismatch = false;
  if (slot.predicted_start) {
    const State& p = *slot.predicted_start;
    const double position_error =
        std::hypot(state_x(state_) - state_x(p), state_y(state_) - state_y(p));
    const double heading_error = std::abs(wrap_angle(state_theta(state_) - state_theta(p)));
    stats_.max_start_position_error_m = std::max(stats_.max_start_position_error_m, position_error);
    stats_.max_start_heading_error_rad =
        std::max(stats_.max_start_heading_error_rad, heading_error);
    if (!states_match(state_, p)) {
      ++stats_.start_mismatches;
      mismatch = true;
    }
  }
  if (mismatch && config_.refuse_start_mismatch) {
    // Its controls would drive the vehicle where nobody checked. Braking here would be no
    // better (nobody checked it here either): the vehicle goes on as it was.
    ++stats_.plans_refused;
    return;
  }
  current_ = slot_index;
  piece_ = 0;
  mode_ = ExecutorMode::kExecuting;
  speed_started_ = true;
  ++stats_.plans_started;
}

template <VehicleModel V>
void PlanExecutor<V>::integrate(std::int64_t until_ns) noexcept {
  while (now_ns_ < until_ns) {
    if (queue_size_ > 0 && slots_[queue_[0]].start_ns <= now_ns_) start_queued_plan();
    // The plan ended when the last sub-step did, and nothing was due then. Its successor may
    // still have come at that very instant (submitted between ticks, starting exactly on
    // time), so the contingency begins only now that the vehicle moves on without one.
    if (mode_ == ExecutorMode::kExecuting && piece_ == slots_[current_].steps.size()) {
      begin_contingency(ContingencyCause::kRanOut);
    }
    std::int64_t end = until_ns;
    if (queue_size_ > 0) end = std::min(end, slots_[queue_[0]].start_ns);
    if (mode_ == ExecutorMode::kExecuting) end = std::min(end, slots_[current_].end_ns[piece_]);
    const double h = static_cast<double>(end - now_ns_) / kNsPerS;
    const double x0 = state_x(state_);
    const double y0 = state_y(state_);
    if (mode_ == ExecutorMode::kExecuting) {
      const PlanStep& piece = slots_[current_].steps[piece_];
      control_ = Control(piece.control[0], piece.control[1]);
    } else {
      control_ =
          mode_ == ExecutorMode::kBraking ? vehicle_.braking_control(state_) : Control::Zero();
    }
    state_ = follow(vehicle_, state_, mode_, control_, h);
    stats_.distance_m += std::hypot(state_x(state_) - x0, state_y(state_) - y0);
    now_ns_ = end;
    if (mode_ == ExecutorMode::kExecuting && now_ns_ >= slots_[current_].end_ns[piece_]) {
      ++piece_;
    }
  }
}

template <VehicleModel V>
void PlanExecutor<V>::after_tick() noexcept {
  ++stats_.ticks;
  const bool colliding = !checker_.is_free(state_x(state_), state_y(state_), state_theta(state_));
  if (colliding) {
    ++stats_.ticks_in_collision;
    if (!in_collision_) {
      ++stats_.collisions;
      if (events_.size() < config_.max_collision_events) {
        events_.push_back(
            CollisionEvent{now_ns_, state_x(state_), state_y(state_), state_theta(state_)});
      } else {
        ++stats_.collision_events_dropped;
      }
    }
  }
  in_collision_ = colliding;
  if (speed_started_) {
    const double v = speed_m_s();
    stats_.speed_sum_m_s += v;
    ++stats_.speed_ticks;
    if (speeds_.size() < config_.max_speed_samples) {
      speeds_.push_back(SpeedSample{now_ns_, v});
    } else {
      ++stats_.speed_samples_dropped;
    }
  }
}

template <VehicleModel V>
void PlanExecutor<V>::step() noexcept {
  integrate(now_ns_ + step_ns_);
  after_tick();
}

template <VehicleModel V>
void PlanExecutor<V>::run_until(std::int64_t t_ns) noexcept {
  while (now_ns_ <= t_ns - step_ns_) step();
}

template <VehicleModel V>
double PlanExecutor<V>::speed_m_s() const noexcept {
  if constexpr (requires { vehicle_.speed_m_s(state_, control_); }) {
    return vehicle_.speed_m_s(state_, control_);
  } else {
    return vehicle_.speed_m_s(state_);
  }
}

template <VehicleModel V>
double PlanExecutor<V>::mean_speed_fraction() const noexcept {
  if (stats_.speed_ticks == 0) return 0.0;
  return stats_.speed_sum_m_s / static_cast<double>(stats_.speed_ticks) / vehicle_.max_speed_m_s();
}

template class PlanExecutor<DdVelocity>;
template class PlanExecutor<DdAcceleration>;
template class PlanExecutor<Car>;

}  // namespace grip::sim
