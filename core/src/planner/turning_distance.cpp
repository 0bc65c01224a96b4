#include "grip/planner/turning_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "../world/validation.hpp"

namespace grip {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxTableCells = 1 << 22;

// [m] An arc of radius r turning the position angle about its centre from `from` to `to`, on
// the circle of side `side` (1: left, forward is counter-clockwise; -1: right): forward the way
// the heading points, or in reverse the other way round, whichever costs less.
double arc_cost(double r, double side, double from, double to, double reverse_factor) noexcept {
  double forward = std::fmod(side * (to - from), kTwoPi);
  if (forward < 0.0) forward += kTwoPi;
  return r * std::min(forward, reverse_factor * (kTwoPi - forward));
}

// An arc on the circle of radius r centred at (0, side * r) from the origin to a tangent point,
// then straight to p along the tangent: the two tangent points. At position angle phi on that
// circle the heading is phi + side * pi / 2, however the arc was driven.
double arc_then_straight(double r, double side, double px, double py, double k) noexcept {
  const double cy = side * r;
  const double d = std::hypot(px, py - cy);
  if (d < r) return std::numeric_limits<double>::infinity();
  const double straight = std::sqrt(std::max(d * d - r * r, 0.0));
  const double to_p = std::atan2(py - cy, px);
  const double spread = std::acos(std::min(r / d, 1.0));
  const double from = -side * std::numbers::pi / 2;  // the origin, seen from the centre
  double best = std::numeric_limits<double>::infinity();
  for (const double phi : {to_p + spread, to_p - spread}) {
    const double tx = r * std::cos(phi);
    const double ty = cy + r * std::sin(phi);
    const double heading = phi + side * std::numbers::pi / 2;
    const bool ahead = (px - tx) * std::cos(heading) + (py - ty) * std::sin(heading) >= 0.0;
    best = std::min(best, arc_cost(r, side, from, phi, k) + straight * (ahead ? 1.0 : k));
  }
  return best;
}

// Straight along the heading to (s, 0), then an arc on the circle of radius r centred at
// (s, side * r) that passes through p: the two such s.
double straight_then_arc(double r, double side, double px, double py, double k) noexcept {
  const double dy = py - side * r;
  if (std::abs(dy) > r) return std::numeric_limits<double>::infinity();
  const double half_chord = std::sqrt(std::max(r * r - dy * dy, 0.0));
  const double from = -side * std::numbers::pi / 2;
  double best = std::numeric_limits<double>::infinity();
  for (const double s : {px - half_chord, px + half_chord}) {
    const double straight = s >= 0.0 ? s : -k * s;
    best = std::min(best, straight + arc_cost(r, side, from, std::atan2(dy, px - s), k));
  }
  return best;
}

}  // namespace

double TurningDistance::exact_m(double turning_radius_m, double x_m, double y_m,
                                double reverse_factor) noexcept {
  double best = std::numeric_limits<double>::infinity();
  for (const double side : {1.0, -1.0}) {
    best = std::min(best, arc_then_straight(turning_radius_m, side, x_m, y_m, reverse_factor));
    best = std::min(best, straight_then_arc(turning_radius_m, side, x_m, y_m, reverse_factor));
  }
  return best;
}

Result<TurningDistance> TurningDistance::create(double turning_radius_m, double range_m,
                                                double resolution_m, double reverse_factor) {
  const auto positive = [](const char* name, double value) -> Status {
    if (std::isfinite(value) && value > 0.0) return Ok{};
    return invalid_argument(std::string("turning distance: ") + name +
                            " must be finite and > 0 (got " + detail::format_number(value) + ")");
  };
  if (Status s = positive("turning_radius_m", turning_radius_m); !s) return s.error();
  if (Status s = positive("range_m", range_m); !s) return s.error();
  if (Status s = positive("resolution_m", resolution_m); !s) return s.error();
  if (!(std::isfinite(reverse_factor) && reverse_factor >= 1.0)) {
    return invalid_argument("turning distance: reverse_factor must be finite and >= 1 (got " +
                            detail::format_number(reverse_factor) + ")");
  }
  const double side = std::ceil(range_m / resolution_m) + 1.0;
  if (side * (2.0 * side - 1.0) > kMaxTableCells) {
    return invalid_argument("turning distance: a range of " + detail::format_number(range_m) +
                            " m at " + detail::format_number(resolution_m) + " m is more than " +
                            std::to_string(kMaxTableCells) + " table cells");
  }
  return TurningDistance(turning_radius_m, range_m, resolution_m, reverse_factor,
                         static_cast<int>(side));
}

TurningDistance::TurningDistance(double radius_m, double range_m, double resolution_m,
                                 double reverse_factor, int side)
    : radius_m_(radius_m),
      range_m_(range_m),
      reverse_factor_(reverse_factor),
      inv_resolution_(1.0 / resolution_m),
      side_(side),
      lengths_(static_cast<std::size_t>(side) * static_cast<std::size_t>(2 * side - 1)) {
  const int columns = 2 * side_ - 1;
  for (int j = 0; j < side_; ++j) {
    for (int i = 0; i < columns; ++i) {
      lengths_[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) +
               static_cast<std::size_t>(i)] =
          static_cast<float>(exact_m(radius_m_, (i - (side_ - 1)) * resolution_m,
                                     j * resolution_m, reverse_factor_));
    }
  }
}

double TurningDistance::at(double x_m, double y_m) const noexcept {
  const double u = x_m * inv_resolution_ + (side_ - 1) + 0.5;
  const double v = std::abs(y_m) * inv_resolution_ + 0.5;
  const int columns = 2 * side_ - 1;
  if (!(u >= 0.0 && u < columns && v < side_)) {
    return exact_m(radius_m_, x_m, std::abs(y_m), reverse_factor_);
  }
  return static_cast<double>(
      lengths_[static_cast<std::size_t>(v) * static_cast<std::size_t>(columns) +
               static_cast<std::size_t>(u)]);
}

}  // namespace grip
