#pragma once
// The chassis: a rectangle in the body frame, relative to the state's reference point (x, y)
// with the body x axis along the heading theta. It spans x in [-rear_m, front_m] and
// y in [-half_width_m, half_width_m]. rear_m may be negative (a chassis wholly ahead of the
// reference point) as long as front_m + rear_m > 0; see CollisionChecker::create.

#include <algorithm>
#include <cmath>

namespace grip {

struct Footprint {
  double front_m;       // [m] reference point to the front edge
  double rear_m;        // [m] reference point to the rear edge
  double half_width_m;  // [m] centre line to either side

  // [m] radius of the smallest disk centred on the reference point that holds the rectangle.
  double circumscribed_radius() const noexcept {
    return std::hypot(std::max(std::abs(front_m), std::abs(rear_m)), half_width_m);
  }
  // The rectangle grown by margin_m on every side.
  Footprint inflated(double margin_m) const noexcept {
    return Footprint{front_m + margin_m, rear_m + margin_m, half_width_m + margin_m};
  }
  bool operator==(const Footprint&) const = default;
};

}  // namespace grip
