#include "grip/planner/target_set.hpp"

#include <cmath>

#include "grip/common/saturating_cast.hpp"

namespace grip {

namespace {

// Calls visit(index) for every free cell whose centre lies in the disk, row by row.
template <typename Visit>
void visit_disk_cells(const OccupancyGrid& grid, const Goal& disk, int gx, int gy, Visit&& visit) {
  const int reach =
      ceil_to_count(disk.radius_m() / grid.resolution(), 0, OccupancyGrid::kMaxSideCells) + 1;
  for (int cy = gy - reach; cy <= gy + reach; ++cy) {
    for (int cx = gx - reach; cx <= gx + reach; ++cx) {
      if (!grid.in_bounds(cx, cy) || grid.at(cx, cy) != Cell::kFree) continue;
      if (disk.contains(grid.cell_center_x(cx), grid.cell_center_y(cy))) {
        visit(grid.index(cx, cy));
      }
    }
  }
}

}  // namespace

TargetSet::TargetSet(const OccupancyGrid& grid)
    : grid_(&grid), cells_(grid.cell_count()), mask_(grid.cell_count()) {
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) GRIP_ASSERT(mask_.push_back(0));
}

RetainStatus TargetSet::assign(const Goal& goal) noexcept {
  // Checked before anything changes, so that a refused goal leaves the current one intact.
  int gx = 0;
  int gy = 0;
  if (goal.is_disk()) {
    if (!std::isfinite(goal.radius_m()) || goal.radius_m() <= 0.0 ||
        !grid_->to_cell(goal.x_m(), goal.y_m(), gx, gy)) {
      return RetainStatus::kGoalOutsideGrid;
    }
    bool any_free = false;
    visit_disk_cells(*grid_, goal, gx, gy, [&](std::uint32_t) { any_free = true; });
    if (!any_free) return RetainStatus::kGoalWithoutFreeCell;
  } else {
    bool any_free = false;
    for (const std::uint32_t c : goal.cells()) {
      if (c >= grid_->cell_count()) return RetainStatus::kGoalOutsideGrid;
      any_free = any_free || grid_->at(c) == Cell::kFree;
    }
    if (!any_free) return RetainStatus::kGoalWithoutFreeCell;
  }
  for (const std::uint32_t c : cells_) mask_[c] = 0;
  cells_.clear();
  is_disk_ = goal.is_disk();
  if (is_disk_) {
    disk_ = goal;
    visit_disk_cells(*grid_, goal, gx, gy, [this](std::uint32_t c) {
      GRIP_ASSERT(cells_.push_back(c));  // sized to the grid
    });
    return RetainStatus::kOk;
  }
  // The given free cells, each once (the mask drops repeats).
  for (const std::uint32_t c : goal.cells()) {
    if (grid_->at(c) != Cell::kFree || mask_[c] != 0) continue;
    mask_[c] = 1;
    GRIP_ASSERT(cells_.push_back(c));  // sized to the grid
  }
  return RetainStatus::kOk;
}

bool TargetSet::contains(double x, double y) const noexcept {
  if (is_disk_) return disk_.contains(x, y);
  int cx = 0;
  int cy = 0;
  return grid_->to_cell(x, y, cx, cy) && mask_[grid_->index(cx, cy)] != 0;
}

}  // namespace grip
