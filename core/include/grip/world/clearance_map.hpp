#pragma once
// Per-cell clearance of an occupancy grid: how far each cell is from the nearest cell that is
// not known free (obstacle or unknown) or from the outside of the grid. Shared by the collision
// checker (its O(1) "certainly free" test) and the distance field (its inflation).
//
// What is stored: d2(c), the exact squared Euclidean distance, in cells, from the centre of c to
// the centre of the nearest non-free cell, where every cell outside the grid counts as non-free
// (0 for a non-free cell). Computed by an exact two-pass Euclidean distance transform
// (Felzenszwalb & Huttenlocher) in O(cells), without allocation after create().
//
// What it means, in metres (res = resolution, hd = res * sqrt(2) / 2, half a cell diagonal):
//   clearance_m(c) = sqrt(d2(c)) * res - hd   (0 for a non-free cell)
// is a lower bound of the distance from the centre of c to any point of any non-free cell,
// because every point of a cell lies within hd of its centre. It errs low by at most
// 0.21 * res against axis-aligned walls. Consequently every point of c is at least
// clearance_m(c) - hd from every non-free point.

#include <cstdint>
#include <span>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

// The cells where a point (a chassis' reference point) has at least a given clearance: kFree,
// and with a clearance > 0, d2 at least ClearanceMap::squared_cells_at_least of it. The one
// statement of that rule, read cell by cell in the wavefronts' loops (ClearanceMap::clear_cells).
struct ClearCells {
  const Cell* cells = nullptr;
  const std::uint32_t* squared_clearance = nullptr;  // nullptr: every free cell
  std::uint32_t min_squared_clearance = 0;

  // Every free cell of the grid (no clearance asked).
  static ClearCells free_cells(const OccupancyGrid& grid) noexcept {
    return ClearCells{grid.cells().data(), nullptr, 0};
  }
  bool contains(std::uint32_t c) const noexcept {
    return cells[c] == Cell::kFree &&
           (squared_clearance == nullptr || squared_clearance[c] >= min_squared_clearance);
  }
};

class ClearanceMap {
 public:
  // Allocates every buffer; errors as for OccupancyGrid::create. compute() must run before use.
  static Result<ClearanceMap> create(int width_cells, int height_cells, double resolution_m);
  // Allocates for the grid's size and computes.
  static Result<ClearanceMap> create_for(const OccupancyGrid& grid);

  // Recomputes from the grid. Asserts the grid has this map's width, height and resolution.
  void compute(const OccupancyGrid& grid) noexcept;
  // The same after a change confined to `changed` (no cell outside it changed between free and
  // non-free since the last compute() or update()), in O(window) rather than O(cells): the
  // window is `changed` grown by about sqrt(exact_up_to_d2) cells. Afterwards every d2 up to
  // exact_up_to_d2 is exact, and a cell whose exact d2 is larger holds some d2 that is larger
  // too, so any comparison of d2 with a threshold up to exact_up_to_d2 answers as after
  // compute(); that is all the collision checker and the distance field ask (exact_up_to()
  // tells the bound). Returns the cells rewritten (the window). Why: in exploration the map
  // changes every cycle, near the vehicle, and a whole-map pass would be paid on the planning
  // thread each time. A window larger than the scratch (the larger of 2^20 cells and an
  // eighth of the map) is recomputed whole instead, and the whole map returned. Asserts compute()
  // ran first.
  CellBox update(const OccupancyGrid& grid, const CellBox& changed,
                 std::uint32_t exact_up_to_d2) noexcept;
  // The largest d2 known exact (UINT32_MAX after compute(); the smallest bound of the updates
  // since).
  std::uint32_t exact_up_to() const noexcept { return exact_up_to_d2_; }

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  double resolution() const noexcept { return resolution_; }
  std::uint32_t cell_count() const noexcept { return static_cast<std::uint32_t>(d2_.size()); }
  // The grid revision seen by the last compute(); false from computed() before the first.
  std::uint64_t source_revision() const noexcept { return source_revision_; }
  bool computed() const noexcept { return computed_; }

  // d2 as described above. Asserts index < cell_count().
  std::uint32_t squared_cells(std::uint32_t index) const noexcept {
    GRIP_ASSERT(index < d2_.size());
    return d2_[index];
  }
  // The lower bound described above [m]. Asserts index < cell_count().
  double clearance_m(std::uint32_t index) const noexcept;
  std::span<const std::uint32_t> squared_cells() const noexcept { return d2_; }

  // The smallest d2 such that d2(c) >= it  <=>  clearance_m(c) >= min_clearance_m (up to a
  // relative 1e-12 rounded towards requiring more). 0 for min_clearance_m <= 0 (every cell,
  // including non-free ones: callers test freedom separately).
  std::uint32_t squared_cells_at_least(double min_clearance_m) const noexcept;
  // The cells of `grid` (the one this map was computed from) with at least this clearance.
  ClearCells clear_cells(const OccupancyGrid& grid, double min_clearance_m) const noexcept {
    const std::uint32_t min_d2 = squared_cells_at_least(min_clearance_m);
    return min_d2 == 0 ? ClearCells::free_cells(grid)
                       : ClearCells{grid.cells().data(), d2_.data(), min_d2};
  }

 private:
  ClearanceMap(int width_cells, int height_cells, double resolution_m);

  int width_;
  int height_;
  double resolution_;
  double half_diagonal_m_;
  std::uint64_t source_revision_ = 0;
  bool computed_ = false;
  std::uint32_t exact_up_to_d2_ = 0;
  std::vector<std::uint32_t> d2_;
  // Scratch for the transform, sized at creation (column distances of update()'s window: the
  // larger of 2^20 cells and an eighth of the map, at most the map).
  std::vector<std::uint32_t> columns_;
  std::vector<std::int64_t> f_;
  std::vector<std::int64_t> d_;
  std::vector<int> v_;
  std::vector<double> z_;
};

}  // namespace grip
