#include "grip/rt/plan_ledger.hpp"

#include <algorithm>
#include <cmath>

#include "grip/common/assert.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip::rt {

namespace {
constexpr double kNsPerS = 1e9;
}  // namespace

template <VehicleModel V>
PlanLedger<V>::PlanLedger(const V& vehicle, double step_s, std::uint32_t max_steps)
    : vehicle_(vehicle), step_ns_(std::llround(step_s * kNsPerS)), max_steps_(max_steps) {
  GRIP_ASSERT(step_ns_ > 0);
  for (Entry& e : entries_) {
    e.steps.reserve(max_steps);
    e.end_ns.reserve(max_steps);
  }
}

template <VehicleModel V>
void PlanLedger<V>::record(std::uint64_t cycle, std::uint64_t start_ns, const State& start,
                           std::span<const PlanStep> steps) noexcept {
  if (steps.empty() && count_ > 0) {
    // A run of empty plans is one entry: each changes nothing the one before did not (it drops
    // the queued plans starting at or after the earlier start of the two), and a planner
    // without a plan for many cycles must not push out the plan the vehicle goes on with (with
    // 8 entries it did: the forecast was lost and the tree restarted where the vehicle was not).
    Entry& last = entries_[(next_ + kCapacity - 1) % kCapacity];
    if (last.steps.empty()) {
      last.cycle = cycle;
      last.start_ns = std::min(last.start_ns, static_cast<std::int64_t>(start_ns));
      last.start = start;
      return;
    }
  }
  Entry& e = entries_[next_];
  next_ = (next_ + 1) % kCapacity;
  count_ = std::min(count_ + 1, kCapacity);
  e.cycle = cycle;
  e.start_ns = static_cast<std::int64_t>(start_ns);
  e.start = start;
  const std::size_t n = std::min<std::size_t>(steps.size(), max_steps_);
  e.steps.assign(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(n));
  e.end_ns.clear();
  std::int64_t t = e.start_ns;
  for (const PlanStep& s : e.steps) {
    t += std::llround(s.duration_s * kNsPerS);  // as the controller rounds it
    e.end_ns.push_back(t);
  }
}

template <VehicleModel V>
const typename PlanLedger<V>::Entry* PlanLedger<V>::find(std::uint64_t cycle) const noexcept {
  for (std::size_t i = 0; i < count_; ++i) {
    const Entry& e = nth_oldest(i);
    if (e.cycle == cycle && !e.steps.empty()) return &e;
  }
  return nullptr;
}

template <VehicleModel V>
std::optional<typename PlanLedger<V>::Forecast> PlanLedger<V>::forecast(
    const State& measured, std::uint64_t stamp_ns, std::uint64_t executing_cycle,
    std::uint64_t until_ns) const noexcept {
  const auto stamp = static_cast<std::int64_t>(stamp_ns);
  const auto until = static_cast<std::int64_t>(std::max(until_ns, stamp_ns));
  using Mode = ControllerMode;
  State q = measured;
  const Entry* current = nullptr;
  std::size_t piece = 0;
  Mode mode = contingency_mode(vehicle_, q);
  if (executing_cycle != 0) {
    current = find(executing_cycle);
    if (current == nullptr) return std::nullopt;
    piece = static_cast<std::size_t>(
        std::upper_bound(current->end_ns.begin(), current->end_ns.end(), stamp) -
        current->end_ns.begin());
    mode = Mode::kExecuting;
  }
  // The plans still to come, as the controller queues them: each supersedes those queued to
  // start at or after it.
  std::array<const Entry*, kCapacity> queue{};
  std::size_t queued = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Entry& e = nth_oldest(i);
    if (e.start_ns < stamp || e.cycle <= executing_cycle) continue;
    while (queued > 0 && queue[queued - 1]->start_ns >= e.start_ns) --queued;
    queue[queued++] = &e;
  }
  std::size_t next = 0;
  // Tick by tick from the stamp (the controller's ticks fall on its stamps), each split where a
  // plan or a piece starts, as the controller integrates.
  for (std::int64_t tick = stamp; tick < until; tick += step_ns_) {
    const std::int64_t tick_end = std::min(until, tick + step_ns_);
    std::int64_t t = tick;
    while (t < tick_end) {
      if (next < queued && queue[next]->start_ns <= t) {
        const Entry& e = *queue[next++];
        if (!e.steps.empty() && states_match(q, e.start)) {
          current = &e;
          piece = 0;
          mode = Mode::kExecuting;
        }  // else an empty plan, or one refused: the vehicle goes on as it was
      }
      if (mode == Mode::kExecuting && piece == current->steps.size()) {
        mode = contingency_mode(vehicle_, q);
      }
      std::int64_t end = tick_end;
      if (next < queued) end = std::min(end, queue[next]->start_ns);
      if (mode == Mode::kExecuting) end = std::min(end, current->end_ns[piece]);
      const double h = static_cast<double>(end - t) / kNsPerS;
      typename V::Control held = V::Control::Zero();
      if (mode == Mode::kExecuting) {
        held << current->steps[piece].control[0], current->steps[piece].control[1];
      }
      q = follow(vehicle_, q, mode, held, h);
      t = end;
      if (mode == Mode::kExecuting && t >= current->end_ns[piece]) ++piece;
    }
  }
  Forecast f;
  f.state = q;
  // A plan whose last piece ended exactly now has run out: the vehicle brakes from here on.
  if (mode == Mode::kExecuting && piece < current->steps.size()) {
    f.cycle = current->cycle;
  }
  return f;
}

template class PlanLedger<DdVelocity>;
template class PlanLedger<DdAcceleration>;
template class PlanLedger<Car>;

}  // namespace grip::rt
