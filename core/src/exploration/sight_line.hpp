#pragma once
// Line of sight on the three-valued grid, private to core/src/exploration: the one place that
// decides which cells a segment crosses, so that a shared grid traversal (Amanatides-Woo, being
// written for world/) can replace it when the branches merge.

#include <cstdlib>

#include "grip/world/occupancy_grid.hpp"

namespace grip::detail {

// Calls visit(cx, cy) for every cell that the segment from the centre of (x0, y0) to the centre
// of (x1, y1) crosses, in order from (x0, y0) (included) to (x1, y1) (included), until visit
// returns false. Where the segment passes exactly through a cell corner, both cells beside the
// corner are visited (a sight line through a corner between two diagonal obstacles is blocked,
// the conservative reading). Integer Amanatides-Woo: centre-to-centre segments need no floating
// point. Cells outside the grid are visited too (callers read them through OccupancyGrid::at,
// which reports them as obstacles).
template <typename Visit>
void trace_cells(int x0, int y0, int x1, int y1, Visit&& visit) noexcept {
  const int dx = std::abs(x1 - x0);
  const int dy = std::abs(y1 - y0);
  const int sx = x1 > x0 ? 1 : -1;
  const int sy = y1 > y0 ? 1 : -1;
  // error > 0: the segment leaves the current cell through its vertical side next.
  long error = static_cast<long>(dx) - dy;
  int x = x0;
  int y = y0;
  for (int left = dx + dy;;) {
    if (!visit(x, y) || left == 0) return;
    if (error > 0) {
      x += sx;
      error -= 2L * dy;
      --left;
    } else if (error < 0) {
      y += sy;
      error += 2L * dx;
      --left;
    } else {
      // Exactly through a corner: both side cells, then the diagonal one.
      if (!visit(x + sx, y) || !visit(x, y + sy)) return;
      x += sx;
      y += sy;
      error += 2L * dx - 2L * dy;
      left -= 2;
    }
  }
}

// Whether cell (x1, y1) is in sight from cell (x0, y0): every cell the segment between their
// centres crosses before (x1, y1) is kFree (an obstacle or an unknown cell blocks the view; the
// end cell itself may be anything).
inline bool in_sight(const OccupancyGrid& grid, int x0, int y0, int x1, int y1) noexcept {
  bool clear = true;
  trace_cells(x0, y0, x1, y1, [&](int x, int y) {
    if (x == x1 && y == y1) return false;
    clear = grid.at(x, y) == Cell::kFree;
    return clear;
  });
  return clear;
}

}  // namespace grip::detail
