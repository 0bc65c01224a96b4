#pragma once
// How far a vehicle that turns no tighter than radius R, forward or in reverse (a Reeds-Shepp
// car), drives its reference point to reach a point, with any heading on arrival: the
// obstacle-free, non-holonomic half of Hybrid A*'s heuristic (Dolgov, Thrun, Montemerlo, Diebel
// 2008), toward a point because the planner's target set is a set of cells, not a pose.
//
// The length is the shortest of the paths made of one arc of radius R and one straight segment,
// in either order, each driven forward or in reverse (a cusp between them is free). Wherever the
// point lies outside both turning circles one of them is the shortest path overall; close
// beside the vehicle, inside a turning circle, a path of two arcs can be a little shorter, so
// there the length is an upper bound. What matters to the planner is kept: a point beside or
// behind a vehicle that cannot turn in place is farther than a point the same distance ahead.
//
// Lengths are precomputed at start-up into a table of one quadrant of the vehicle's frame
// (x ahead, y to the left): the other three follow by symmetry (left and right mirror; forward
// and reverse cost the same length). Lookups are O(1); beyond the table the closed form is
// evaluated. create() allocates; lookups never allocate and never throw.

#include <vector>

#include "grip/common/result.hpp"

namespace grip {

class TurningDistance {
 public:
  // A table covering |x|, |y| <= range_m at cells of resolution_m. Errors name the value that
  // is not finite and > 0, or a table of more than 2^22 cells.
  static Result<TurningDistance> create(double turning_radius_m, double range_m,
                                        double resolution_m);

  // [m] The closed form at the point (x_m, y_m) of the vehicle's frame (what the table holds).
  static double exact_m(double turning_radius_m, double x_m, double y_m) noexcept;

  // [m] The table's length at (x_m, y_m) in the vehicle's frame: the length at the table cell
  // nearest to the point (within the table), else the closed form.
  double at(double x_m, double y_m) const noexcept;

  double turning_radius_m() const noexcept { return radius_m_; }
  double range_m() const noexcept { return range_m_; }

 private:
  TurningDistance(double radius_m, double range_m, double resolution_m, int side);

  double radius_m_;
  double range_m_;
  double inv_resolution_;
  int side_;  // cells per side of the quadrant
  std::vector<float> lengths_;
};

}  // namespace grip
