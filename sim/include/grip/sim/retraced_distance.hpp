#pragma once
// How much of a run's driving went back over ground the vehicle had already driven over: the
// measure behind "the robot does not revisit covered space needlessly". Part of it is needed
// (leaving a dead end the way one came); a planner that wanders back and forth shows more.

#include <array>
#include <span>

namespace grip::sim {

struct RetracedDistance {
  double distance_m = 0.0;  // the whole trajectory's length
  double retraced_m = 0.0;  // of which on ground driven over before
  double fraction() const noexcept { return distance_m > 0.0 ? retraced_m / distance_m : 0.0; }
};

// `trajectory`: the reference point's (x, y) per tick. The ground is cut in squares of cell_m;
// a move counts as retraced when it ends in a square the vehicle occupied before and has, on
// entering it again, driven at least away_m since it last left it (so that wiggling across
// the border of two squares, or turning on the spot, retraces nothing).
RetracedDistance retraced_distance(std::span<const std::array<double, 2>> trajectory, double cell_m,
                                   double away_m);

}  // namespace grip::sim
