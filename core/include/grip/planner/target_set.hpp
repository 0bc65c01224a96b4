#pragma once
// The planner's target set F (the paper's Sec. II) on its grid: the free cells it covers, for
// rho's wavefront and RRT's goal bias, and whether a workspace point is in it. Owns bounded
// buffers sized to the grid at construction; assign() never allocates.

#include <cstdint>
#include <span>

#include "grip/memory/fixed_vector.hpp"
#include "grip/planner/goal.hpp"
#include "grip/planner/planner_status.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

class TargetSet {
 public:
  // Sized for every cell of `grid`, which must outlive the set. F holds no cell until assign().
  explicit TargetSet(const OccupancyGrid& grid);

  // F becomes `goal` on the grid as it is now: the free cells whose centres lie in a disk, or
  // the free cells of a cells goal, each once. kGoalOutsideGrid for a disk that is not finite
  // with a radius > 0 or centred outside the grid, or a cell index >= cell_count();
  // kGoalWithoutFreeCell when no cell is free. A refused goal leaves F as it was.
  RetainStatus assign(const Goal& goal) noexcept;

  // Whether the reference point (x, y) [m] is in F: within the disk, or in one of the cells.
  bool contains(double x, double y) const noexcept;
  // F's free cells (indices cell_y * width + cell_x), valid until the next assign().
  std::span<const std::uint32_t> cells() const noexcept { return cells_.span(); }

 private:
  const OccupancyGrid* grid_;
  Goal disk_;            // the disk, when F is one
  bool is_disk_ = true;  // else contains() asks mask_
  BoundedVector<std::uint32_t> cells_;
  BoundedVector<std::uint8_t> mask_;  // per grid cell: 1 in F (cells goals only)
};

}  // namespace grip
