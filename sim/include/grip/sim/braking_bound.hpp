#pragma once
// How fast a vehicle could have driven its own route while always able to stop inside what it
// had sensed: the physics behind an acceleration-limited vehicle's mean speed in unknown space
// (the paper's Sec. III-C: every plan ends in a braking maneuver checked against the known map).
//
// At each tick t the vehicle is at arc length s on the route it went on to drive. Ahead of it,
// the route is usable up to the first point where the chassis there touches a cell not sensed
// by tick t, or where the route reverses (a cusp, where any vehicle is at rest), or where the
// run ended (treated as open). The bound is the speed it can brake to rest from within that
// distance d, sqrt(2 b d) with the braking deceleration b, capped at the top speed (backing up,
// at the top reverse speed), and reached from the previous tick's bound at most at the
// acceleration bound (a vehicle at rest cannot jump to it). With caps (turning_bound.hpp: what
// the route's turns allow), it is also at most each tick's cap and the speed that brakes to
// every cap ahead in time. It ignores everything else: the planner's choice of route, obstacles
// a later plan would meet. A mean speed close to it means the vehicle drove as fast as its
// sensing (and its turns) allowed.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/footprint.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::sim {

struct SpeedLimits {
  double max_speed_m_s;
  double max_reverse_speed_m_s;  // where the route goes against the chassis's heading
  double accel_m_s2;             // the acceleration bound
  double braking_decel_m_s2;     // the braking maneuver's deceleration
};

inline constexpr std::uint32_t kNeverSensed = 0xFFFF'FFFFU;

// The tick each cell was first sensed at (kNeverSensed: not yet), on the grid of `map`.
class SensedTicks {
 public:
  explicit SensedTicks(const OccupancyGrid& map) : ticks_(map.cell_count(), kNeverSensed) {}
  // Cells sensed at `tick` (those already sensed keep their first tick).
  void mark(std::span<const std::uint32_t> cells, std::uint32_t tick) noexcept {
    for (const std::uint32_t c : cells) {
      if (ticks_[c] == kNeverSensed) ticks_[c] = tick;
    }
  }
  std::span<const std::uint32_t> ticks() const noexcept { return ticks_; }

 private:
  std::vector<std::uint32_t> ticks_;
};

// The bound per tick [m/s]: `route[k]` and `headings[k]` are the reference point's (x, y) and
// the chassis's heading at the end of tick k + 1, sensed from there in that tick (SensedTicks
// marked with k + 1; cells sensed before the first tick with 0); `grid` gives the geometry of
// `sensed`; `caps`, per tick, or empty. Errors: limits or step not finite and > 0, `headings`,
// `sensed` or `caps` of the wrong size.
Result<std::vector<double>> braking_bound_m_s(std::span<const std::array<double, 2>> route,
                                              std::span<const double> headings,
                                              const OccupancyGrid& grid,
                                              std::span<const std::uint32_t> sensed,
                                              const Footprint& footprint, const SpeedLimits& limits,
                                              double step_s, std::span<const double> caps = {});

}  // namespace grip::sim
