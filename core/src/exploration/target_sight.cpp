#include "grip/exploration/target_sight.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "../world/validation.hpp"
#include "grip/common/saturating_cast.hpp"
#include "sight_line.hpp"

namespace grip {

namespace {

// Map cells per side of a sight cell: the fewest that bring d_max within kMaxSightRadius.
int sight_block_for(double sensing_radius_m, double resolution_m) {
  return ceil_to_count(sensing_radius_m / resolution_m / TargetSight::kMaxSightRadius, 1,
                       OccupancyGrid::kMaxSideCells);
}

}  // namespace

Result<TargetSight> TargetSight::create(int width_cells, int height_cells, double resolution_m,
                                        double sensing_radius_m) {
  if (auto error =
          detail::check_grid_size("TargetSight", width_cells, height_cells, resolution_m)) {
    return *std::move(error);
  }
  if (!(std::isfinite(sensing_radius_m) && sensing_radius_m > 0.0)) {
    return invalid_argument("TargetSight: sensing_radius_m must be finite and > 0 (got " +
                            detail::format_number(sensing_radius_m) + ")");
  }
  return TargetSight(width_cells, height_cells, resolution_m, sensing_radius_m);
}

TargetSight::TargetSight(int width_cells, int height_cells, double resolution_m,
                         double sensing_radius_m)
    : width_(width_cells),
      height_(height_cells),
      resolution_(resolution_m),
      inv_resolution_(1.0 / resolution_m),
      sensing_radius_m_(sensing_radius_m),
      block_(sight_block_for(sensing_radius_m, resolution_m)),
      sight_width_((width_cells + block_ - 1) / block_),
      sight_height_((height_cells + block_ - 1) / block_),
      radius_(ceil_to_count(sensing_radius_m / (resolution_m * block_), 0,
                            OccupancyGrid::kMaxSideCells)),
      seen_(static_cast<std::size_t>(sight_width_) * static_cast<std::size_t>(sight_height_)),
      // A target marks cells of the square of half-side radius_ around it only.
      seen_list_(std::min(seen_.capacity(), std::size_t{kMaxTargetCells} *
                                                static_cast<std::size_t>(2 * radius_ + 1) *
                                                static_cast<std::size_t>(2 * radius_ + 1))),
      blocked_(block_ > 1 ? seen_.capacity() : 0) {
  for (std::size_t c = 0; c < seen_.capacity(); ++c) GRIP_ASSERT(seen_.push_back(0));
  for (std::size_t c = 0; c < blocked_.capacity(); ++c) GRIP_ASSERT(blocked_.push_back(0));
}

void TargetSight::set_target(const OccupancyGrid& grid,
                             std::span<const std::uint32_t> cells) noexcept {
  GRIP_ASSERT(grid.width() == width_ && grid.height() == height_ &&
              grid.resolution() == resolution_);
  for (const std::uint32_t c : seen_list_) seen_[c] = 0;
  seen_list_.clear();
  targets_.clear();
  origin_x_m_ = grid.origin_x();
  origin_y_m_ = grid.origin_y();
  // What blocks the view is read afresh from this grid; a stamp that would wrap clears all.
  if (++stamp_ > 0x7FFFFFFFU) {
    std::fill(blocked_.begin(), blocked_.end(), 0U);
    stamp_ = 1;
  }
  // Evenly spread: the i-th of n picks sits at (2i + 1) / 2n along the list, so that both ends
  // of a short frontier are represented as well as its middle.
  const std::size_t n = std::min<std::size_t>(cells.size(), kMaxTargetCells);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t c = cells[(2 * i + 1) * cells.size() / (2 * n)];
    GRIP_ASSERT(c < grid.cell_count());
    GRIP_ASSERT(targets_.push_back(c));
    target_x_m_[i] = grid.cell_center_x(grid.cell_x(c));
    target_y_m_[i] = grid.cell_center_y(grid.cell_y(c));
    cast_rays_from(grid, static_cast<std::uint32_t>(i));
  }
}

std::uint32_t TargetSight::seen_from(std::uint32_t cell) const noexcept {
  const auto width = static_cast<std::uint32_t>(width_);
  return seen_[sight_cell(cell % width, cell / width)];
}

bool TargetSight::blocks_sight(const OccupancyGrid& grid, int sx, int sy) noexcept {
  if (block_ == 1) return grid.at(sx, sy) != Cell::kFree;
  if (sx < 0 || sy < 0 || sx >= sight_width_ || sy >= sight_height_) return true;
  std::uint32_t& known = blocked_[sight_index(sx, sy)];
  if (known >> 1 == stamp_) return (known & 1U) != 0;
  bool obstacle = false;
  bool free = false;
  const int x1 = std::min(width_, (sx + 1) * block_);
  const int y1 = std::min(height_, (sy + 1) * block_);
  for (int y = sy * block_; y < y1 && !obstacle; ++y) {
    for (int x = sx * block_; x < x1; ++x) {
      const Cell cell = grid.at(x, y);
      obstacle = obstacle || cell == Cell::kObstacle;
      free = free || cell == Cell::kFree;
    }
  }
  const bool blocks = obstacle || !free;
  known = (stamp_ << 1) | (blocks ? 1U : 0U);
  return blocks;
}

void TargetSight::cast_rays_from(const OccupancyGrid& grid, std::uint32_t target_bit) noexcept {
  const std::uint32_t target = targets_[target_bit];
  const int tx = grid.cell_x(target) / block_;
  const int ty = grid.cell_y(target) / block_;
  const double range_cells = sensing_radius_m_ / (resolution_ * block_);
  const double range2 = range_cells * range_cells;
  const int r = radius_;
  const std::uint32_t bit = 1U << target_bit;
  const auto walk = [&](int px, int py) {
    detail::trace_cells(tx, ty, px, py, [&](int x, int y) {
      const double dx = x - tx;
      const double dy = y - ty;
      const bool start = x == tx && y == ty;
      if (dx * dx + dy * dy > range2 || (!start && blocks_sight(grid, x, y))) return false;
      const std::uint32_t c = sight_index(x, y);
      if (seen_[c] == 0) GRIP_ASSERT(seen_list_.push_back(c));  // each cell once
      seen_[c] |= bit;
      return true;
    });
  };
  // Every cell of the border of the square of half-side r, once.
  for (int i = -r; i < r; ++i) {
    walk(tx + i, ty - r);
    walk(tx + r, ty + i);
    walk(tx - i, ty + r);
    walk(tx - r, ty - i);
  }
}

}  // namespace grip
