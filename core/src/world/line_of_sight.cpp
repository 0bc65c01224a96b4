#include "grip/world/line_of_sight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "grip/common/saturating_cast.hpp"

namespace grip {

namespace {

// Two boundary crossings closer than this along the segment [cells] are one corner crossing.
constexpr double kCornerTolerance = 1e-9;

// floor() of a cell coordinate, clamped to [-1, limit]: a traversal never goes further than one
// cell outside the grid, and the clamp keeps huge but finite coordinates out of int overflow.
int clamped_floor(double u, int limit) noexcept { return floor_to_cell(u, -1, limit); }

struct Axis {
  int step = 0;          // +1, -1, or 0 when the segment does not move along this axis
  double t_max = 0.0;    // segment parameter at the next cell boundary on this axis
  double t_delta = 0.0;  // segment parameter between two boundaries on this axis
  int remaining = 0;     // boundaries left to cross before the end cell

  Axis(double u0, double u1, int cell, int end_cell) noexcept {
    const double du = u1 - u0;
    constexpr double kNever = std::numeric_limits<double>::infinity();
    if (du > 0.0) {
      step = 1;
      t_delta = 1.0 / du;
      t_max = (cell + 1 - u0) / du;
    } else if (du < 0.0) {
      step = -1;
      t_delta = -1.0 / du;
      t_max = (u0 - cell) / -du;
    } else {
      t_delta = kNever;
      t_max = kNever;
    }
    remaining = step == 0 ? 0 : std::abs(end_cell - cell);
  }
  void advance(int& cell) noexcept {
    cell += step;
    t_max += t_delta;
    --remaining;
  }
};

}  // namespace

TraversalResult traverse_segment(const OccupancyGrid& grid, double x0_m, double y0_m, double x1_m,
                                 double y1_m, CellVisitor visit) noexcept {
  TraversalResult result;
  const double inv_res = 1.0 / grid.resolution();
  const double u0 = (x0_m - grid.origin_x()) * inv_res;
  const double v0 = (y0_m - grid.origin_y()) * inv_res;
  const double u1 = (x1_m - grid.origin_x()) * inv_res;
  const double v1 = (y1_m - grid.origin_y()) * inv_res;
  if (!std::isfinite(u0) || !std::isfinite(v0) || !std::isfinite(u1) || !std::isfinite(v1)) {
    return result;
  }
  int cx = clamped_floor(u0, grid.width());
  int cy = clamped_floor(v0, grid.height());
  if (!grid.in_bounds(cx, cy)) return result;
  Axis ax(u0, u1, cx, clamped_floor(u1, grid.width()));
  Axis ay(v0, v1, cy, clamped_floor(v1, grid.height()));
  const double corner_t = kCornerTolerance / std::max(std::hypot(u1 - u0, v1 - v0), 1e-300);

  // Visits (x, y); false when the traversal must stop there.
  auto enter = [&](int x, int y) noexcept {
    ++result.cells_visited;
    if (!visit(x, y)) {
      result.end = TraversalEnd::kStoppedByVisitor;
      return false;
    }
    return true;
  };

  if (!enter(cx, cy)) return result;
  // The remaining counts, not the t_max comparisons, decide when the end cell is reached, so
  // round-off in t_max can reorder two nearly simultaneous crossings but never overshoot.
  while (ax.remaining > 0 || ay.remaining > 0) {
    if (ax.remaining > 0 && ay.remaining > 0 && std::abs(ax.t_max - ay.t_max) <= corner_t) {
      // Through a corner: both cells beside it, then the diagonal one.
      if (grid.in_bounds(cx + ax.step, cy) && !enter(cx + ax.step, cy)) return result;
      if (grid.in_bounds(cx, cy + ay.step) && !enter(cx, cy + ay.step)) return result;
      ax.advance(cx);
      ay.advance(cy);
    } else if (ay.remaining == 0 || (ax.remaining > 0 && ax.t_max < ay.t_max)) {
      ax.advance(cx);
    } else {
      ay.advance(cy);
    }
    if (!grid.in_bounds(cx, cy)) {
      result.end = TraversalEnd::kLeftGrid;
      return result;
    }
    if (!enter(cx, cy)) return result;
  }
  result.end = TraversalEnd::kReachedEnd;
  return result;
}

TraversalResult traverse_ray(const OccupancyGrid& grid, double x_m, double y_m, double angle_rad,
                             double range_m, CellVisitor visit) noexcept {
  const double r = std::max(range_m, 0.0);
  return traverse_segment(grid, x_m, y_m, x_m + r * std::cos(angle_rad),
                          y_m + r * std::sin(angle_rad), visit);
}

bool visible_cells(const OccupancyGrid& grid, double x0_m, double y0_m, double x1_m, double y1_m,
                   CellVisitor seen) noexcept {
  int end_x = -1;
  int end_y = -1;
  const bool end_in_grid = grid.to_cell(x1_m, y1_m, end_x, end_y);
  bool opaque_end = false;
  bool stopped_by_caller = false;
  const TraversalResult r =
      traverse_segment(grid, x0_m, y0_m, x1_m, y1_m, [&](int cx, int cy) noexcept {
        if (!seen(cx, cy)) {
          stopped_by_caller = true;
          return false;
        }
        if (grid.at(cx, cy) != Cell::kFree) {
          opaque_end = end_in_grid && cx == end_x && cy == end_y;
          return false;
        }
        return true;
      });
  if (r.end == TraversalEnd::kReachedEnd) return true;
  return r.end == TraversalEnd::kStoppedByVisitor && !stopped_by_caller && opaque_end;
}

bool cell_visible(const OccupancyGrid& grid, double x_m, double y_m, int cx, int cy,
                  double range_m) noexcept {
  if (!grid.in_bounds(cx, cy)) return false;
  const double tx = grid.cell_center_x(cx);
  const double ty = grid.cell_center_y(cy);
  if (!(std::hypot(tx - x_m, ty - y_m) <= range_m)) return false;
  return visible_cells(grid, x_m, y_m, tx, ty, [](int, int) noexcept { return true; });
}

}  // namespace grip
