// libFuzzer target: a received Plan, validated as the vehicle's controller validates it (the
// contract's check_plan), and when valid executed as the simulator's controller executes it:
// the plan executor refuses what breaks the vehicle's limits (controls, durations, start) and
// drives the rest, braking when it runs out. The vehicle must stay a valid state throughout.

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_bytes.hpp"
#include "grip/link/messages.hpp"
#include "grip/sim/plan_executor.hpp"
#include "grip/sim/sim_participant.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "samples.hpp"

namespace {

// The ground truth: 6.4 m x 6.4 m at 0.1 m, free inside a wall (small: each run builds its
// executor, collision checker included).
const grip::OccupancyGrid& truth() {
  static const grip::OccupancyGrid grid = [] {
    auto g = grip::OccupancyGrid::create(64, 64, 0.1, 0.0, 0.0, grip::Cell::kFree).value();
    for (int i = 0; i < 64; ++i) {
      g.set(i, 0, grip::Cell::kObstacle);
      g.set(i, 63, grip::Cell::kObstacle);
      g.set(0, i, grip::Cell::kObstacle);
      g.set(63, i, grip::Cell::kObstacle);
    }
    return g;
  }();
  return grid;
}

constexpr std::int64_t kStartNs = 1'000'000'000;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  grip::fuzz::FuzzBytes in(data, size);
  const auto kind = static_cast<grip::VehicleKind>(in.take<std::uint8_t>() % 3);
  const auto ticks = in.take<std::uint8_t>();
  std::vector<grip_msg_PlanStep> wire_steps;
  grip_msg_Plan msg = grip::fuzz::plan_from(in, wire_steps);
  // Mostly plans that start near the vehicle's time, as a planner's would.
  if ((msg.cycle & 1U) == 0) msg.start_time_ns = kStartNs + msg.start_time_ns % 2'000'000'000;
  if (!grip::link::check_plan(msg, kind).ok()) return 0;
  grip::with_default_vehicle(kind, [&](const auto& vehicle) {
    using V = std::remove_cvref_t<decltype(vehicle)>;
    typename V::State start = V::State::Zero();
    start[0] = 3.2;
    start[1] = 3.2;
    grip::sim::ExecutorConfig config;
    config.max_speed_samples = 128;
    config.max_collision_events = 16;
    config.refuse_start_mismatch = (ticks & 1U) != 0;
    auto executor = grip::sim::PlanExecutor<V>::create(vehicle, truth(), start, kStartNs, config);
    if (!executor) std::abort();
    std::vector<grip::PlanStep> steps;
    steps.reserve(grip_msg_kMaxPlanSteps);
    static_cast<void>(grip::sim::submit_wire_plan(*executor, msg, steps));
    for (int t = 0; t < (ticks & 63); ++t) {
      executor->step();
      if (!vehicle.validate_state(executor->state()).ok()) std::abort();
    }
  });
  return 0;
}
