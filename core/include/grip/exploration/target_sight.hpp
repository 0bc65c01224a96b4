#pragma once
// Which cells see the exploration target (the paper's Sec. IV): d(tr, c) counts a target cell c
// from the states of tr that see it (PathSelector). Up to kMaxTargetCells cells c of the target
// group, and for every cell of a sight grid the set of them it sees within the sensing radius
// d_max.
//
// The bounded approximation, and why:
//  - c ranges over at most kMaxTargetCells cells of the group, evenly spread along it: a
//    frontier group can hold hundreds of cells, and one bit per cell keeps "which of them does
//    this grid cell see" a 32-bit word.
//  - Seeing is decided per sight cell, once per set_target(): rays are cast from each target's
//    sight cell to the border of the square of half-side d_max around it and walk
//    (detail::trace_cells) until they leave the sensing disk or meet a cell that blocks the view;
//    every cell they cross is marked as seeing that target. Sight along a segment is symmetric,
//    so this is "the state's cell sees c" at the sight grid's resolution, with rays to the
//    border cells standing for the segments to each cell (rays one border cell apart are less
//    than a cell apart everywhere inside). Cost: O(kMaxTargetCells x 8 r^2) per call, r = d_max
//    in sight cells, independent of the map's size and of the tree.
//  - The sight grid is the map's grid while d_max spans at most kMaxSightRadius of its cells,
//    else blocks of k x k map cells with k the smallest that brings d_max within it: the cost
//    of a call is bounded however fine the map is. A block blocks the view when one of its
//    cells is an obstacle or none is free: a wall stops sight at the block it touches, up to a
//    block early, and a frontier's own block, part unknown, is seen through. The target's own
//    block is always in sight.
//
// A call costs milliseconds, so it belongs with the choice of the target, beside the planning
// thread (rt::ExplorationDriver keeps two: the one the planning thread reads and the one cast
// for the next target).
//
// Memory is reserved by create() (a 32-bit mask per sight cell, the list of marked ones bounded
// by the targets' sensing squares, and with blocks a 32-bit stamp per sight cell);
// set_target() never allocates and never throws.

#include <cstdint>
#include <span>

#include "grip/common/result.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

class TargetSight {
 public:
  static constexpr std::uint32_t kMaxTargetCells = 32;
  // [sight cells] d_max spans at most this many cells of the sight grid (see the file comment).
  static constexpr int kMaxSightRadius = 64;

  // For grids of this size and resolution, seeing d_max = sensing_radius_m. Errors as for
  // OccupancyGrid::create, and for a radius not finite or not > 0.
  static Result<TargetSight> create(int width_cells, int height_cells, double resolution_m,
                                    double sensing_radius_m);

  // The cells c (e.g. FrontierMap::target_cells()): up to kMaxTargetCells of them, evenly
  // spread over the list, and which sight cells see each, by what blocks the view in `grid`.
  // Asserts the grid's size matches and every cell is in it.
  void set_target(const OccupancyGrid& grid, std::span<const std::uint32_t> cells) noexcept;

  // The target cells used (after subsampling) and their centres.
  std::span<const std::uint32_t> target_cells() const noexcept { return targets_.span(); }
  double target_x_m(std::uint32_t i) const noexcept { return target_x_m_[i]; }
  double target_y_m(std::uint32_t i) const noexcept { return target_y_m_[i]; }
  // Which targets (bit i: target_cells()[i]) the grid cell `cell` sees.
  std::uint32_t seen_from(std::uint32_t cell) const noexcept;
  // The same for the cell holding the point (x, y); 0 off the grid.
  std::uint32_t seen_at(double x_m, double y_m) const noexcept {
    const double u = (x_m - origin_x_m_) * inv_resolution_;
    const double v = (y_m - origin_y_m_) * inv_resolution_;
    if (!(u >= 0.0 && v >= 0.0 && u < width_ && v < height_)) return 0;
    return seen_[sight_cell(static_cast<std::uint32_t>(u), static_cast<std::uint32_t>(v))];
  }

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  double sensing_radius_m() const noexcept { return sensing_radius_m_; }
  // Map cells per side of a sight cell (1: the map's own grid).
  int sight_block() const noexcept { return block_; }

 private:
  TargetSight(int width_cells, int height_cells, double resolution_m, double sensing_radius_m);
  void cast_rays_from(const OccupancyGrid& grid, std::uint32_t target_bit) noexcept;
  bool blocks_sight(const OccupancyGrid& grid, int sx, int sy) noexcept;
  // The sight cell holding map cell (x, y).
  std::uint32_t sight_cell(std::uint32_t x, std::uint32_t y) const noexcept {
    const auto block = static_cast<std::uint32_t>(block_);
    return sight_index(static_cast<int>(x / block), static_cast<int>(y / block));
  }
  // The index of sight cell (sx, sy), inside the sight grid.
  std::uint32_t sight_index(int sx, int sy) const noexcept {
    return static_cast<std::uint32_t>(sy) * static_cast<std::uint32_t>(sight_width_) +
           static_cast<std::uint32_t>(sx);
  }

  int width_;
  int height_;
  double resolution_;
  double inv_resolution_;
  double sensing_radius_m_;
  int block_;        // map cells per side of a sight cell
  int sight_width_;  // sight cells
  int sight_height_;
  int radius_;               // d_max in sight cells, rounded up
  std::uint32_t stamp_ = 0;  // of the current set_target(); blocked_ holds stamp_ << 1 | blocks
  double origin_x_m_ = 0.0;  // of the grid given to set_target()
  double origin_y_m_ = 0.0;
  FixedVector<std::uint32_t, kMaxTargetCells> targets_;
  double target_x_m_[kMaxTargetCells] = {};  // cell centres
  double target_y_m_[kMaxTargetCells] = {};
  BoundedVector<std::uint32_t> seen_;       // per sight cell: bit i set = sees target i
  BoundedVector<std::uint32_t> seen_list_;  // sight cells with a bit set, to clear them
  BoundedVector<std::uint32_t> blocked_;    // per sight cell, with blocks: stamp_ when known
};

}  // namespace grip
