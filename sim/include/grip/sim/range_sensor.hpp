#pragma once
// The simulated range sensor (the paper's Sec. IV): from the vehicle's reference point it casts
// rays against the ground truth and writes what they see into the planner-visible three-valued
// map, which starts all kUnknown.
//
// What is seen: rays of length radius_m leave the sensor point at N equally spaced headings;
// each walks the cells it crosses (world/line_of_sight.hpp, including the corner rule) and sees
// every free cell up to and including the first obstacle cell, which stops it. A ray also stops
// at the edge of the grid. N = max(16, ceil(2 pi radius / (0.5 res))): neighbouring rays are at
// most half a cell apart at full range, so no cell lying wholly within the radius fits between
// two rays without being crossed by one (a cell is at least one cell wide in every direction,
// the gap between neighbours at most half a cell); a cell
// that one ray reaches unobstructed is seen even if another ray is blocked before it. Every
// seen cell has a point within radius_m of the sensor: nothing beyond the radius is marked.
//
// Cells are written with their ground-truth value, so a cell marked free is truly free, and a
// cell once known never changes again (the world is static). The sweep reports the cells whose
// value changed, as their grid indices and their bounding box: the patch of the next map update.
//
// Capacity is fixed at creation; sense() never allocates and never throws.

#include <cstdint>
#include <span>
#include <vector>

#include "grip/common/function_ref.hpp"
#include "grip/common/result.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::sim {

struct SenseResult {
  CellBox changed;                               // bounding box of changed cells; empty if none
  std::span<const std::uint32_t> changed_cells;  // grid indices, valid until the next sense()
  std::uint32_t cells_visited = 0;               // ray-cell visits (a cell may count repeatedly)
};

class RangeSensor {
 public:
  // One tenth of the scene width (the paper's Sec. IV); the scene width is taken as the larger
  // side of the grid, so a long narrow map still gets a useful radius.
  static double default_radius_m(const OccupancyGrid& truth) noexcept;

  // rays: the N above when 0; a real sensor's beam count otherwise (16 to 1 << 20), with which
  // cells far out may fit between two rays, as they do for that sensor.
  // Errors (kInvalidArgument): radius_m not finite or <= 0, or so large that the ray count
  // exceeds 1 << 20; rays outside its range. The truth grid must outlive the sensor and must
  // not move.
  static Result<RangeSensor> create(const OccupancyGrid& truth, double radius_m,
                                    std::uint32_t rays = 0);

  // Senses from (x_m, y_m) and writes the seen cells into `known`. A sensor point outside the
  // grid sees nothing. Asserts that `known` has the truth's width, height, resolution and origin.
  SenseResult sense(double x_m, double y_m, OccupancyGrid& known) noexcept;

  double radius_m() const noexcept { return radius_m_; }
  std::uint32_t ray_count() const noexcept { return static_cast<std::uint32_t>(cos_.size()); }
  const OccupancyGrid& truth() const noexcept { return *truth_; }

 private:
  RangeSensor(const OccupancyGrid& truth, double radius_m, std::uint32_t rays,
              std::size_t capacity);

  const OccupancyGrid* truth_;
  double radius_m_;
  std::vector<double> cos_;  // per ray heading
  std::vector<double> sin_;
  std::vector<std::uint32_t> changed_;  // reserved at creation, never grows past it
  std::size_t capacity_;
};

// Calls emit(tile) for rectangles of at most max_cells cells (>= 1) that tile `box` (empty: no
// call), row by row from the bottom-left: map updates carry at most msg::kMaxPatchCells cells.
void for_each_patch(const CellBox& box, std::uint32_t max_cells,
                    FunctionRef<void(const CellBox&)> emit) noexcept;

}  // namespace grip::sim
