#include "grip/sim/braking_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace grip::sim {

namespace {

// A point of the route, one per half cell of travel (standing still and creeping add none).
struct Waypoint {
  double x_m;
  double y_m;
  double arc_m;               // along the route from its start
  std::uint32_t sensed_tick;  // when the last cell under the chassis there was sensed
};

// The last tick at which a cell the chassis at (x, y, theta) touches was first sensed;
// kNeverSensed when the chassis leaves the grid. A cell counts when its centre lies within half
// a cell of the rectangle along the chassis's axes (exact for a chassis along the grid).
std::uint32_t sensed_tick_under(const OccupancyGrid& grid, std::span<const std::uint32_t> sensed,
                                double x_m, double y_m, double theta_rad,
                                const Footprint& footprint) {
  int cx = 0;
  int cy = 0;
  if (!grid.to_cell(x_m, y_m, cx, cy)) return kNeverSensed;
  const double half_cell = 0.5 * grid.resolution();
  const int reach =
      static_cast<int>(std::ceil(footprint.circumscribed_radius() / grid.resolution())) + 1;
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  std::uint32_t last = 0;
  for (int y = cy - reach; y <= cy + reach; ++y) {
    for (int x = cx - reach; x <= cx + reach; ++x) {
      const double dx = grid.cell_center_x(x) - x_m;
      const double dy = grid.cell_center_y(y) - y_m;
      const double along = c * dx + s * dy;
      const double across = -s * dx + c * dy;
      if (along > footprint.front_m + half_cell || along < -footprint.rear_m - half_cell ||
          std::abs(across) > footprint.half_width_m + half_cell) {
        continue;
      }
      if (!grid.in_bounds(x, y)) return kNeverSensed;
      last = std::max(last, sensed[grid.index(x, y)]);
    }
  }
  return last;
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

Result<std::vector<double>> braking_bound_m_s(std::span<const std::array<double, 2>> route,
                                              std::span<const double> headings,
                                              const OccupancyGrid& grid,
                                              std::span<const std::uint32_t> sensed,
                                              const Footprint& footprint, const SpeedLimits& limits,
                                              double step_s, std::span<const double> caps) {
  if (!positive(limits.max_speed_m_s) || !positive(limits.max_reverse_speed_m_s) ||
      !positive(limits.accel_m_s2) || !positive(limits.braking_decel_m_s2) || !positive(step_s)) {
    return invalid_argument(
        "braking bound: top speeds, acceleration, braking deceleration and step must be finite "
        "and > 0 (got " +
        std::to_string(limits.max_speed_m_s) + ", " + std::to_string(limits.max_reverse_speed_m_s) +
        ", " + std::to_string(limits.accel_m_s2) + ", " +
        std::to_string(limits.braking_decel_m_s2) + ", " + std::to_string(step_s) + ")");
  }
  if (headings.size() != route.size()) {
    return invalid_argument("braking bound: " + std::to_string(headings.size()) +
                            " headings for a route of " + std::to_string(route.size()) + " points");
  }
  if (sensed.size() != grid.cell_count()) {
    return invalid_argument("braking bound: " + std::to_string(sensed.size()) +
                            " sensed ticks for a grid of " + std::to_string(grid.cell_count()) +
                            " cells");
  }
  if (!caps.empty() && caps.size() != route.size()) {
    return invalid_argument("braking bound: " + std::to_string(caps.size()) +
                            " speed caps for a route of " + std::to_string(route.size()) +
                            " points");
  }
  // The route thinned to a waypoint per half cell; each tick's arc length and last waypoint.
  const double spacing = 0.5 * grid.resolution();
  std::vector<Waypoint> waypoints;
  std::vector<double> arc(route.size());
  std::vector<std::uint32_t> at_waypoint(route.size());
  double s = 0.0;
  for (std::size_t k = 0; k < route.size(); ++k) {
    if (k > 0) s += std::hypot(route[k][0] - route[k - 1][0], route[k][1] - route[k - 1][1]);
    arc[k] = s;
    if (waypoints.empty() || std::hypot(route[k][0] - waypoints.back().x_m,
                                        route[k][1] - waypoints.back().y_m) >= spacing) {
      waypoints.push_back(Waypoint{
          route[k][0], route[k][1], s,
          sensed_tick_under(grid, sensed, route[k][0], route[k][1], headings[k], footprint)});
    }
    at_waypoint[k] = static_cast<std::uint32_t>(waypoints.size() - 1);
  }
  // Where the route reverses: the direction of travel turns by more than a right angle from
  // one move to the next (moves of zero length do not count). Which ticks back up: their move
  // goes against the heading (a tick that does not move keeps its predecessor's).
  std::vector<double> cusp_arcs;
  std::vector<bool> backing(route.size(), false);
  std::array<double, 2> last_move{0.0, 0.0};
  for (std::size_t k = 1; k < route.size(); ++k) {
    const std::array<double, 2> move{route[k][0] - route[k - 1][0], route[k][1] - route[k - 1][1]};
    backing[k] = backing[k - 1];
    if (move[0] == 0.0 && move[1] == 0.0) continue;
    if (move[0] * last_move[0] + move[1] * last_move[1] < 0.0) cusp_arcs.push_back(arc[k - 1]);
    backing[k] = move[0] * std::cos(headings[k]) + move[1] * std::sin(headings[k]) < 0.0;
    last_move = move;
  }
  const double fastest = std::max(limits.max_speed_m_s, limits.max_reverse_speed_m_s);
  const double stopping_m = fastest * fastest / (2.0 * limits.braking_decel_m_s2);
  // Each tick's cap, and the speed that still brakes to every cap ahead.
  std::vector<double> capped(route.size(), std::numeric_limits<double>::infinity());
  if (!caps.empty()) {
    double ahead = std::numeric_limits<double>::infinity();
    for (std::size_t k = route.size(); k-- > 0;) {
      if (k + 1 < route.size()) {
        ahead = std::sqrt(ahead * ahead + 2.0 * limits.braking_decel_m_s2 * (arc[k + 1] - arc[k]));
      }
      ahead = std::min(ahead, caps[k]);
      capped[k] = ahead;
    }
  }
  std::vector<double> bound(route.size());
  double previous = 0.0;
  std::size_t next_cusp = 0;
  for (std::size_t k = 0; k < route.size(); ++k) {
    const auto tick = static_cast<std::uint32_t>(k + 1);
    while (next_cusp < cusp_arcs.size() && cusp_arcs[next_cusp] < arc[k]) ++next_cusp;
    double free_m = next_cusp < cusp_arcs.size()
                        ? std::min(stopping_m, cusp_arcs[next_cusp] - arc[k])
                        : stopping_m;
    for (std::size_t j = at_waypoint[k] + 1; j < waypoints.size(); ++j) {
      const double ahead = waypoints[j].arc_m - arc[k];
      if (ahead >= free_m) break;
      if (waypoints[j].sensed_tick > tick) {
        free_m = ahead;
        break;
      }
    }
    const double top = backing[k] ? limits.max_reverse_speed_m_s : limits.max_speed_m_s;
    const double v = std::min({top, std::sqrt(2.0 * limits.braking_decel_m_s2 * free_m),
                               previous + limits.accel_m_s2 * step_s, capped[k]});
    bound[k] = v;
    previous = v;
  }
  return bound;
}

}  // namespace grip::sim
