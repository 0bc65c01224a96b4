#pragma once
// Line of sight on an occupancy grid: exact traversal of the cells a segment crosses
// (Amanatides & Woo, "A Fast Voxel Traversal Algorithm", 1987), used by the simulator's range
// sensor against the ground truth and by the planner's visibility weight (the paper's Sec. IV)
// against the known map.
//
// Which cells a segment visits: every cell whose interior the segment passes through, in order
// from the start, beginning with the cell that contains the start point (the grid's floor
// convention, occupancy_grid.hpp). Where the segment passes exactly through a cell corner
// (within 1e-9 cells), both cells beside the corner are visited (the x neighbour first, then
// the y neighbour) before the diagonal one, so a ray never slips between two obstacles that
// touch at a corner. A segment running exactly along a grid line visits the cells on the side
// the floor convention picks. The traversal stops at the cell that holds the end point, when
// the next cell would lie outside the grid, or when the visitor returns false.
//
// What "seen" means (visible_cells, cell_visible): walking a ray from the viewpoint, every cell
// up to and including the first opaque cell is seen; cells behind it are not. Opaque means not
// kFree: obstacles, and on a planner's map also unknown cells (the planner does not count on
// seeing through space it has not sensed). The first opaque cell is seen because a range
// sensor's beam returns from it.
//
// Everything here is noexcept and allocation-free; the visitor is called once per cell.

#include <cstdint>

#include "grip/common/function_ref.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

// Called with each visited cell (in bounds); return false to stop the traversal there.
using CellVisitor = FunctionRef<bool(int cx, int cy)>;

enum class TraversalEnd : std::uint8_t {
  kReachedEnd,  // the cell holding the end point was visited
  kStoppedByVisitor,
  kLeftGrid,  // the next cell lies outside the grid (or the start does: nothing visited)
};

struct TraversalResult {
  TraversalEnd end = TraversalEnd::kLeftGrid;
  std::uint32_t cells_visited = 0;
};

// Visits the cells the segment from (x0_m, y0_m) to (x1_m, y1_m) crosses, in order (see the top
// of this file). Non-finite coordinates visit nothing (kLeftGrid).
TraversalResult traverse_segment(const OccupancyGrid& grid, double x0_m, double y0_m, double x1_m,
                                 double y1_m, CellVisitor visit) noexcept;

// The ray from (x_m, y_m) at heading angle_rad, up to range_m (>= 0) from the start.
TraversalResult traverse_ray(const OccupancyGrid& grid, double x_m, double y_m, double angle_rad,
                             double range_m, CellVisitor visit) noexcept;

// Walks the segment and reports each cell it sees: the transparent (kFree) cells in order and,
// if the segment meets one, the first opaque cell, where the walk stops. `seen` returning false
// stops the walk too. Returns true iff the segment reached its end cell without meeting an
// opaque cell before it (the end cell itself may be opaque: it is seen).
bool visible_cells(const OccupancyGrid& grid, double x0_m, double y0_m, double x1_m, double y1_m,
                   CellVisitor seen) noexcept;

// True iff cell (cx, cy) is seen from (x_m, y_m) along the segment to its centre: the centre lies
// within range_m, and every cell the segment crosses before (cx, cy) is kFree. The target cell's
// own value does not matter (an obstacle is seen when the sight line reaches it). False for a
// cell outside the grid and for a viewpoint outside the grid.
bool cell_visible(const OccupancyGrid& grid, double x_m, double y_m, int cx, int cy,
                  double range_m) noexcept;

}  // namespace grip
