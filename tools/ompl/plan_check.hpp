#pragma once
// The re-check every returned plan passes before it counts as a solution, whichever planner
// returned it. Only the controls and their durations are trusted; the plan is re-propagated
// with the core model from the start at the planning step dt, exactly as the planners and the
// simulator propagate it (that trajectory is what executing the plan does):
//  - every control within the vehicle's limits (validate_control);
//  - where the planner also returned states (`claimed`, one per piece end), they must be the
//    re-propagated ones (|dx|, |dy| <= 1e-6 m): no plan passes with states its controls do
//    not produce;
//  - the motion between consecutive states: from each state, the step is integrated again in
//    `substeps` sub-steps of dt / substeps, and every sub-step state is checked by the core
//    CollisionChecker grown only by the margin of a sub-step (half the largest chassis motion
//    in dt / substeps at the state's speed, state_collision_margin_m, as the planners check
//    each dt), which covers the continuous
//    motion between sub-steps, and by validate_state (finite, within the limits). Sub-steps
//    restart from every dt state, so the check follows the executed trajectory instead of
//    drifting from it over a long plan (open-loop integration error would grow with time);
//  - the end within the goal region (Goal::contains, no tolerance).
// The planners check every dt with a dt margin; this sees 10x finer with a 10x smaller margin,
// so it catches a plan that is free only at its samples, or only thanks to a coarse margin.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "grip/planner/planner.hpp"
#include "grip/planner/step_margin.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip::ompl_bridge {

// One control held for `steps` planning steps.
struct PlanPiece {
  std::array<double, 2> control{};
  std::uint32_t steps = 0;
};

struct PlanCheck {
  bool ok = false;
  std::string failure;                // why not, when !ok
  double duration_s = 0.0;            // sum of the pieces' durations
  double length_m = 0.0;              // path length of the reference point on the fine trajectory
  double end_goal_distance_m = 0.0;   // coarse end to the goal point
  double max_fine_deviation_m = 0.0;  // one step vs its sub-steps, end position, worst step
};

inline constexpr std::uint32_t kRecheckSubsteps = 10;

// The checker of the fine re-check: the vehicle's chassis on `grid` with the margin of one
// fine step (dt / substeps).
template <VehicleModel V>
Result<CollisionChecker> make_fine_checker(const V& vehicle, const OccupancyGrid& grid,
                                           double step_s,
                                           std::uint32_t substeps = kRecheckSubsteps) {
  return CollisionChecker::create(
      grid, vehicle.footprint(),
      step_collision_margin_m(vehicle, step_s / static_cast<double>(substeps)));
}

// `claimed`, if not empty, holds the planner's state at the end of each piece (x, y).
template <VehicleModel V>
PlanCheck check_plan(const V& vehicle, const CollisionChecker& fine_checker, const Goal& goal,
                     const typename V::State& start, const std::vector<PlanPiece>& plan,
                     double step_s, const std::vector<std::array<double, 2>>& claimed = {},
                     std::uint32_t substeps = kRecheckSubsteps) {
  using State = typename V::State;
  using Control = typename V::Control;
  PlanCheck out;
  const auto fail = [&](std::string why) {
    out.ok = false;
    out.failure = std::move(why);
    return out;
  };
  if (!claimed.empty() && claimed.size() != plan.size()) {
    return fail("the planner returned " + std::to_string(claimed.size()) + " states for " +
                std::to_string(plan.size()) + " controls");
  }
  const double fine_dt = step_s / static_cast<double>(substeps);
  State q = start;
  // The margin of each state's own speed for a fine step, as the planners check theirs.
  const auto chassis_free = [&](const State& at) {
    return chassis_free_at(vehicle, fine_checker, at, fine_dt);
  };
  if (!chassis_free(q)) {
    return fail("the start collides");
  }
  double t = 0.0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Control u{plan[i].control[0], plan[i].control[1]};
    if (auto s = vehicle.validate_control(u); !s) {
      return fail("piece " + std::to_string(i) + ": " + s.error().message);
    }
    for (std::uint32_t k = 0; k < plan[i].steps; ++k) {
      State fine = q;
      for (std::uint32_t j = 0; j < substeps; ++j) {
        const State next = vehicle.step(fine, u, fine_dt);
        out.length_m += std::hypot(state_x(next) - state_x(fine), state_y(next) - state_y(fine));
        fine = next;
        if (!chassis_free(fine)) {
          return fail("piece " + std::to_string(i) +
                      " collides at t = " + std::to_string(t + (j + 1.0) * fine_dt) + " s, (" +
                      std::to_string(state_x(fine)) + ", " + std::to_string(state_y(fine)) + ")");
        }
        if (auto s = vehicle.validate_state(fine); !s) {
          return fail("piece " + std::to_string(i) + ": " + s.error().message);
        }
      }
      q = vehicle.step(q, u, step_s);
      t += step_s;
      out.max_fine_deviation_m =
          std::max(out.max_fine_deviation_m,
                   std::hypot(state_x(q) - state_x(fine), state_y(q) - state_y(fine)));
    }
    out.duration_s = t;
    if (!claimed.empty() && (std::abs(claimed[i][0] - state_x(q)) > 1e-6 ||
                             std::abs(claimed[i][1] - state_y(q)) > 1e-6)) {
      return fail("piece " + std::to_string(i) + " ends at (" + std::to_string(claimed[i][0]) +
                  ", " + std::to_string(claimed[i][1]) + ") but its control leads to (" +
                  std::to_string(state_x(q)) + ", " + std::to_string(state_y(q)) + ")");
    }
  }
  out.end_goal_distance_m = std::hypot(state_x(q) - goal.x_m(), state_y(q) - goal.y_m());
  if (!goal.contains(state_x(q), state_y(q))) {
    return fail("the plan ends " + std::to_string(out.end_goal_distance_m) +
                " m from the goal point, outside the goal radius");
  }
  out.ok = true;
  return out;
}

}  // namespace grip::ompl_bridge
