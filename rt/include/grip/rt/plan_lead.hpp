#pragma once
// How far ahead of the planner's estimate of the vehicle's time at the next release a plan's
// start time t[i] is set. The vehicle clock estimate (vehicle_clock.hpp) is behind the vehicle
// by the states' delivery latency, and a plan takes its own delivery time: over a slow link a
// plan chained one cycle ahead arrives after its start time and is refused. Neither delay can
// be seen from the planner's side alone; the vehicle reports the margin each plan arrived with
// (VehicleState.plan_arrival_margin_ns: start time minus arrival, vehicle time), and the lead
// closes the gap a late plan reports, plus a quarter cycle for jitter. Plans arriving with more
// than half a cycle to spare let it decay slowly. Zero on a link that delivers within the
// cycle; bounded by kMaxLeadCycles (a link slower than that is not one to drive over: the
// vehicle would act on states that old).
//
// Pure and allocation-free: the planning thread feeds it each state it plans from.

#include <cstdint>

namespace grip::rt {

class PlanLead {
 public:
  static constexpr std::int64_t kMaxLeadCycles = 8;

  explicit PlanLead(std::int64_t cycle_ns) noexcept : cycle_ns_(cycle_ns) {}

  // A state reporting that plan `plan_cycle` (0: none yet) arrived margin_ns before its start
  // time (negative: after it). Each plan counts once, however many states repeat it.
  void observe(std::uint64_t plan_cycle, std::int64_t margin_ns) noexcept;
  std::int64_t lead_ns() const noexcept { return lead_ns_; }

 private:
  std::int64_t cycle_ns_;
  std::int64_t lead_ns_ = 0;
  std::uint64_t last_cycle_ = 0;
};

}  // namespace grip::rt
