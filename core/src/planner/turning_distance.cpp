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

// |a| wrapped to [0, pi]: the shorter way round, forward or in reverse.
double arc_angle(double a) noexcept { return std::abs(std::remainder(a, kTwoPi)); }

// An arc on the circle of radius r centred at (0, side * r) from the origin to a tangent point,
// then straight to p along the tangent: the two tangent points, the shorter arc to each.
double arc_then_straight(double r, double side, double px, double py) noexcept {
  const double cy = side * r;
  const double d = std::hypot(px, py - cy);
  if (d < r) return std::numeric_limits<double>::infinity();
  const double straight = std::sqrt(std::max(d * d - r * r, 0.0));
  const double to_p = std::atan2(py - cy, px);
  const double spread = std::acos(std::min(r / d, 1.0));
  const double from = -side * std::numbers::pi / 2;  // the origin, seen from the centre
  return r * std::min(arc_angle(to_p + spread - from), arc_angle(to_p - spread - from)) + straight;
}

// Straight along the heading to (s, 0), then an arc on the circle of radius r centred at
// (s, side * r) that passes through p: the two such s.
double straight_then_arc(double r, double side, double px, double py) noexcept {
  const double dy = py - side * r;
  if (std::abs(dy) > r) return std::numeric_limits<double>::infinity();
  const double half_chord = std::sqrt(std::max(r * r - dy * dy, 0.0));
  const double from = -side * std::numbers::pi / 2;
  double best = std::numeric_limits<double>::infinity();
  for (const double s : {px - half_chord, px + half_chord}) {
    best = std::min(best, std::abs(s) + r * arc_angle(std::atan2(dy, px - s) - from));
  }
  return best;
}

}  // namespace

double TurningDistance::exact_m(double turning_radius_m, double x_m, double y_m) noexcept {
  double best = std::numeric_limits<double>::infinity();
  for (const double side : {1.0, -1.0}) {
    best = std::min(best, arc_then_straight(turning_radius_m, side, x_m, y_m));
    best = std::min(best, straight_then_arc(turning_radius_m, side, x_m, y_m));
  }
  return best;
}

Result<TurningDistance> TurningDistance::create(double turning_radius_m, double range_m,
                                                double resolution_m) {
  const auto positive = [](const char* name, double value) -> Status {
    if (std::isfinite(value) && value > 0.0) return Ok{};
    return invalid_argument(std::string("turning distance: ") + name +
                            " must be finite and > 0 (got " + detail::format_number(value) + ")");
  };
  if (Status s = positive("turning_radius_m", turning_radius_m); !s) return s.error();
  if (Status s = positive("range_m", range_m); !s) return s.error();
  if (Status s = positive("resolution_m", resolution_m); !s) return s.error();
  const double side = std::ceil(range_m / resolution_m) + 1.0;
  if (side * side > kMaxTableCells) {
    return invalid_argument("turning distance: a range of " + detail::format_number(range_m) +
                            " m at " + detail::format_number(resolution_m) + " m is more than " +
                            std::to_string(kMaxTableCells) + " table cells");
  }
  return TurningDistance(turning_radius_m, range_m, resolution_m, static_cast<int>(side));
}

TurningDistance::TurningDistance(double radius_m, double range_m, double resolution_m, int side)
    : radius_m_(radius_m),
      range_m_(range_m),
      inv_resolution_(1.0 / resolution_m),
      side_(side),
      lengths_(static_cast<std::size_t>(side) * static_cast<std::size_t>(side)) {
  for (int j = 0; j < side_; ++j) {
    for (int i = 0; i < side_; ++i) {
      lengths_[static_cast<std::size_t>(j) * static_cast<std::size_t>(side_) +
               static_cast<std::size_t>(i)] =
          static_cast<float>(exact_m(radius_m_, i * resolution_m, j * resolution_m));
    }
  }
}

double TurningDistance::at(double x_m, double y_m) const noexcept {
  const double u = std::abs(x_m) * inv_resolution_ + 0.5;
  const double v = std::abs(y_m) * inv_resolution_ + 0.5;
  if (!(u < side_ && v < side_)) return exact_m(radius_m_, std::abs(x_m), std::abs(y_m));
  return static_cast<double>(
      lengths_[static_cast<std::size_t>(v) * static_cast<std::size_t>(side_) +
               static_cast<std::size_t>(u)]);
}

}  // namespace grip
