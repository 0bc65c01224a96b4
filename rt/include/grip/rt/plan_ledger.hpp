#pragma once
// The plans the planner sent, and what the vehicle's controller does with them (idl/plan.idl):
// each plan starts at its start time if the vehicle is then in the state the plan starts from,
// and is refused otherwise (the vehicle carries on with what it was doing); an empty plan
// changes nothing the vehicle executes; a plan that runs out ends in its braking contingency.
// From a measured state and the plan the vehicle reports executing, the ledger forecasts where
// the vehicle will be when the next plan starts, integrating exactly as the controller does (the
// model's step() and brake_step(), in ticks of the integration step, split where a piece or a
// plan starts).
//
// The planner compares that forecast with where its tree puts the next plan's start: when they
// differ (a plan arrived late or was refused, the planner had no plan, the chain of start
// times was re-anchored), the tree must start again from the forecast, or every plan it sends
// would be refused.
//
// Capacity is fixed at construction (kCapacity plans of max_steps pieces); record() and
// forecast() never allocate and never throw. Planning thread only.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "grip/planner/plan_following.hpp"
#include "grip/planner/plan_step.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip::rt {

template <VehicleModel V>
class PlanLedger {
 public:
  using State = typename V::State;
  // Plans kept: the one executed and those sent since (refused ones too; runs of empty plans
  // count once).
  static constexpr std::size_t kCapacity = 16;

  struct Forecast {
    State state = State::Zero();  // at until_ns
    std::uint64_t cycle = 0;      // the plan executed then (0: braking or at rest)
  };

  PlanLedger(const V& vehicle, double step_s, std::uint32_t max_steps);

  // A plan sent (steps empty: an empty plan). Plans are recorded in the order they are sent;
  // consecutive empty plans share one entry.
  void record(std::uint64_t cycle, std::uint64_t start_ns, const State& start,
              std::span<const PlanStep> steps) noexcept;

  // The vehicle was in `measured` at stamp_ns, having executed plan `executing_cycle` (0: none)
  // up to then; the recorded plans starting at or after stamp_ns are still to come. Where it
  // is at until_ns (>= stamp_ns), or nothing when the executed plan is not in the ledger.
  std::optional<Forecast> forecast(const State& measured, std::uint64_t stamp_ns,
                                   std::uint64_t executing_cycle,
                                   std::uint64_t until_ns) const noexcept;

 private:
  struct Entry {
    std::uint64_t cycle = 0;
    std::int64_t start_ns = 0;
    State start;
    std::vector<PlanStep> steps;       // capacity max_steps
    std::vector<std::int64_t> end_ns;  // absolute end of each piece
  };

  const Entry* find(std::uint64_t cycle) const noexcept;
  const Entry& nth_oldest(std::size_t i) const noexcept {
    return entries_[(next_ + kCapacity - count_ + i) % kCapacity];
  }

  V vehicle_;
  std::int64_t step_ns_;
  std::uint32_t max_steps_;
  std::array<Entry, kCapacity> entries_;
  std::size_t next_ = 0;   // slot the next record() writes
  std::size_t count_ = 0;  // recorded plans kept (at most kCapacity)
};

extern template class PlanLedger<DdVelocity>;
extern template class PlanLedger<DdAcceleration>;
extern template class PlanLedger<Car>;

}  // namespace grip::rt
