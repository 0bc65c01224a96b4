#pragma once
// The planner's map: a 2-D occupancy grid with the paper's three values (Sec. IV).
// A state collides when its chassis touches an obstacle cell, an unknown cell, or the outside of
// the grid: only known-free space is free.
//
// Geometry: cell (cx, cy) covers [origin_x + cx * res, origin_x + (cx + 1) * res) in x, and the
// same in y. Row-major, y up: row 0 is the bottom row (y = origin_y). A point maps to a cell by
// floor((x - origin_x) * (1 / res)); every world/ class uses this same conversion.
//
// Capacity is fixed by create(); the query and update methods never allocate and never throw.

#include <cstdint>
#include <span>
#include <vector>

#include "grip/common/assert.hpp"
#include "grip/common/result.hpp"

namespace grip {

enum class Cell : std::uint8_t { kFree = 0, kObstacle = 1, kUnknown = 2 };

// An inclusive rectangle of cells, e.g. where a map update made cells non-free.
struct CellBox {
  int x0 = 0;
  int y0 = 0;
  int x1 = -1;
  int y1 = -1;
  bool empty() const noexcept { return x1 < x0 || y1 < y0; }
  void add(const CellBox& other) noexcept {
    if (other.empty()) return;
    if (empty()) {
      *this = other;
      return;
    }
    x0 = x0 < other.x0 ? x0 : other.x0;
    y0 = y0 < other.y0 ? y0 : other.y0;
    x1 = x1 > other.x1 ? x1 : other.x1;
    y1 = y1 > other.y1 ? y1 : other.y1;
  }
};

class OccupancyGrid {
 public:
  // Limits that keep every index and every distance (world/distance_field.hpp) in 32 bits.
  static constexpr int kMaxSideCells = 16384;
  static constexpr std::uint32_t kMaxCells = 1U << 24;
  // The geometry a map from outside (a map file, a received map update) may have: beyond
  // these, the planner's and simulator's grids, footprints and sensor windows are not sized
  // for it. create() itself accepts any finite positive resolution and finite origin.
  static constexpr double kMinResolutionM = 1e-3;  // [m] 1 mm per cell
  static constexpr double kMaxResolutionM = 10.0;  // [m] per cell
  static constexpr double kMaxOriginM = 1e6;       // [m] |origin_x|, |origin_y|

  // Errors (kInvalidArgument) name the bad parameter and its value: a size outside
  // [1, kMaxSideCells] or a product above kMaxCells, resolution not finite or <= 0, a non-finite
  // origin, a fill value that is not a Cell.
  static Result<OccupancyGrid> create(int width_cells, int height_cells, double resolution_m,
                                      double origin_x_m = 0.0, double origin_y_m = 0.0,
                                      Cell fill = Cell::kUnknown);

  int width() const noexcept { return width_; }               // [cells]
  int height() const noexcept { return height_; }             // [cells]
  double resolution() const noexcept { return resolution_; }  // [m] side of a cell
  double origin_x() const noexcept { return origin_x_; }      // [m] left edge of column 0
  double origin_y() const noexcept { return origin_y_; }      // [m] bottom edge of row 0
  double width_m() const noexcept { return width_ * resolution_; }
  double height_m() const noexcept { return height_ * resolution_; }
  std::uint32_t cell_count() const noexcept { return static_cast<std::uint32_t>(cells_.size()); }

  bool in_bounds(int cx, int cy) const noexcept {
    return cx >= 0 && cy >= 0 && cx < width_ && cy < height_;
  }
  // Row-major index cy * width + cx. Asserts in bounds.
  std::uint32_t index(int cx, int cy) const noexcept {
    GRIP_ASSERT(in_bounds(cx, cy));
    return static_cast<std::uint32_t>(cy) * static_cast<std::uint32_t>(width_) +
           static_cast<std::uint32_t>(cx);
  }
  int cell_x(std::uint32_t index) const noexcept {
    return static_cast<int>(index % static_cast<std::uint32_t>(width_));
  }
  int cell_y(std::uint32_t index) const noexcept {
    return static_cast<int>(index / static_cast<std::uint32_t>(width_));
  }

  // Out of bounds reads as kObstacle: outside the map is never free.
  Cell at(int cx, int cy) const noexcept {
    return in_bounds(cx, cy) ? cells_[index(cx, cy)] : Cell::kObstacle;
  }
  // Asserts index < cell_count().
  Cell at(std::uint32_t index) const noexcept {
    GRIP_ASSERT(index < cells_.size());
    return cells_[index];
  }
  // Asserts in bounds. Increments revision() only when the value changes.
  void set(int cx, int cy, Cell value) noexcept;

  // The cell containing (x_m, y_m); false (cx, cy untouched) when the point is outside the grid
  // or not finite.
  bool to_cell(double x_m, double y_m, int& cx, int& cy) const noexcept;
  double cell_center_x(int cx) const noexcept { return origin_x_ + (cx + 0.5) * resolution_; }
  double cell_center_y(int cy) const noexcept { return origin_y_ + (cy + 0.5) * resolution_; }

  // Sets every cell whose centre lies in the closed rectangle spanned by the two corners (given
  // in any order, clipped to the grid). Increments revision() once if any cell changed.
  void fill_rect(double x0_m, double y0_m, double x1_m, double y1_m, Cell value) noexcept;

  std::span<const Cell> cells() const noexcept { return cells_; }
  // Raw write access for the mapper. Calling it counts as a mutation: revision() increments.
  std::span<Cell> mutable_cells() noexcept {
    ++revision_;
    return cells_;
  }
  // Increments on every change, so dependants (clearance maps, distance fields) know to refresh.
  std::uint64_t revision() const noexcept { return revision_; }
  // For writers that changed cells through mutable_cells() after taking the span.
  void mark_changed() noexcept { ++revision_; }

 private:
  OccupancyGrid(int width_cells, int height_cells, double resolution_m, double origin_x_m,
                double origin_y_m, Cell fill);

  int width_;
  int height_;
  double resolution_;
  double inv_resolution_;
  double origin_x_;
  double origin_y_;
  std::uint64_t revision_ = 0;
  std::vector<Cell> cells_;
};

}  // namespace grip
