#include "grip/sim/turning_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace grip::sim {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Below these a tick moved or turned not at all (the executor integrates a vehicle at rest
// exactly).
constexpr double kStillM = 1e-9;
constexpr double kStillRad = 1e-9;

double wrapped(double angle) { return std::remainder(angle, 2.0 * std::numbers::pi); }

bool usable(double limit) { return std::isfinite(limit) && limit >= 0.0; }

}  // namespace

Result<std::vector<double>> turning_caps_m_s(std::span<const std::array<double, 2>> route,
                                             std::span<const double> headings,
                                             const TurningLimits& limits) {
  const TurningLimits& l = limits;
  if (!usable(l.max_turn_rate_rad_s) || !usable(l.half_track_m) || !usable(l.max_wheel_speed_m_s) ||
      !usable(l.wheel_accel_m_s2) || !usable(l.wheelbase_m) || !usable(l.max_steer_rate_rad_s)) {
    return invalid_argument(
        "turning bound: turn rate, half track, wheel speed, wheel acceleration, wheelbase and "
        "steering rate must be finite and >= 0 (got " +
        std::to_string(l.max_turn_rate_rad_s) + ", " + std::to_string(l.half_track_m) + ", " +
        std::to_string(l.max_wheel_speed_m_s) + ", " + std::to_string(l.wheel_accel_m_s2) + ", " +
        std::to_string(l.wheelbase_m) + ", " + std::to_string(l.max_steer_rate_rad_s) + ")");
  }
  if (headings.size() != route.size()) {
    return invalid_argument("turning bound: " + std::to_string(headings.size()) +
                            " headings for a route of " + std::to_string(route.size()) + " points");
  }
  const double h = l.half_track_m;
  std::vector<double> caps(route.size(), kInfinity);
  bool moved_before = false;
  double last_kappa = 0.0;  // of the last tick that moved: signed, along the heading
  double last_ds = 0.0;
  for (std::size_t k = 1; k < route.size(); ++k) {
    const double dx = route[k][0] - route[k - 1][0];
    const double dy = route[k][1] - route[k - 1][1];
    const double ds = std::hypot(dx, dy);
    const double dtheta = wrapped(headings[k] - headings[k - 1]);
    if (ds < kStillM) {
      if (std::abs(dtheta) >= kStillRad) caps[k] = 0.0;  // turns on the spot
      continue;
    }
    // Signed along the heading, so that backing up along an arc keeps its curvature's sign (a
    // car's steering angle does not flip at a cusp).
    const double forward =
        dx * std::cos(headings[k]) + dy * std::sin(headings[k]) >= 0.0 ? 1.0 : -1.0;
    const double kappa = dtheta / (forward * ds);
    double cap = kInfinity;
    if (l.max_turn_rate_rad_s > 0.0 && kappa != 0.0) {
      cap = std::min(cap, l.max_turn_rate_rad_s / std::abs(kappa));
    }
    if (l.max_wheel_speed_m_s > 0.0) {
      cap = std::min(cap, l.max_wheel_speed_m_s / (1.0 + std::abs(kappa) * h));
    }
    if (moved_before) {
      // kappa and last_kappa are means over their ticks' moves, half of each apart.
      const double apart = 0.5 * (ds + last_ds);
      const double kappa_rate = std::abs(kappa - last_kappa) / apart;  // |kappa'|
      if (l.wheel_accel_m_s2 > 0.0 && h > 0.0 && kappa_rate > 0.0) {
        cap = std::min(
            cap, std::sqrt(l.wheel_accel_m_s2 * (1.0 + std::abs(kappa) * h) / (h * kappa_rate)));
      }
      if (l.max_steer_rate_rad_s > 0.0 && l.wheelbase_m > 0.0) {
        const double delta = std::atan(l.wheelbase_m * kappa);
        const double last_delta = std::atan(l.wheelbase_m * last_kappa);
        const double steer_rate = std::abs(delta - last_delta) / apart;  // |d delta / ds|
        if (steer_rate > 0.0) {
          // Of the front wheels' speed: the route's is that times cos(delta).
          cap = std::min(
              cap, l.max_steer_rate_rad_s / (steer_rate * std::cos(0.5 * (delta + last_delta))));
        }
      }
    }
    caps[k] = cap;
    moved_before = true;
    last_kappa = kappa;
    last_ds = ds;
  }
  return caps;
}

}  // namespace grip::sim
