#pragma once
// How fast a vehicle could have driven its own route for the way the route turns: the other
// half of the physics behind an acceleration-limited vehicle's mean speed (braking_bound.hpp is
// the first). A route's shape fixes its curvature kappa(s) along its arc length s; driving it at
// speed v then asks of the vehicle
//  - a turn rate v |kappa| (the differential drive's limit),
//  - wheel speeds v (1 + |kappa| h) for wheels h either side of the reference point,
//  - for a change of curvature, wheel accelerations of at least v^2 h |kappa'| less what the
//    acceleration along the route can take from it (|a| |kappa| h, with |a| at most the wheel
//    acceleration bound A): v^2 h |kappa'| <= A (1 + |kappa| h),
//  - for a car of wheelbase L, a steering rate v cos(delta) |d delta / ds|, delta = atan(L kappa)
//    (a car's speed is its front wheels' (car.hpp), the route's is v cos(delta)).
// Each limit it has caps v at each tick; a route that turns on the spot (the heading changes, the
// position does not) caps it at 0 there, and so does a curvature that jumps (a car that steered
// at rest). kappa and kappa' are read from the route's ticks (the heading's change over the
// distance moved), exact for the arcs a tick of constant controls drives. Standing still asks
// nothing (no cap). Every limit is necessary: no speed the vehicle could drive the route at
// exceeds a cap, so the bound built with them (braking_bound_m_s) stays an upper bound.

#include <array>
#include <span>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::sim {

// A limit of 0 is one the vehicle does not have: the wheel acceleration's counts with a half
// track, the steering rate's with a wheelbase.
struct TurningLimits {
  double max_turn_rate_rad_s = 0.0;
  double half_track_m = 0.0;  // h: the wheels' distance from the reference point
  double max_wheel_speed_m_s = 0.0;
  double wheel_accel_m_s2 = 0.0;  // A
  double wheelbase_m = 0.0;       // L
  double max_steer_rate_rad_s = 0.0;
};

// The cap per tick [m/s] (infinity where nothing caps it): `route[k]` and `headings[k]` as for
// braking_bound_m_s. Errors: a limit negative or not finite, `headings` of the wrong size.
Result<std::vector<double>> turning_caps_m_s(std::span<const std::array<double, 2>> route,
                                             std::span<const double> headings,
                                             const TurningLimits& limits);

}  // namespace grip::sim
