#pragma once
// Chassis collision checking against the three-valued grid (the paper's Sec. II and IV).
//
// A state (x, y, theta) is free iff every grid cell that the chassis rectangle, grown by
// margin_m on all sides, intersects is kFree and inside the grid. Cells and rectangle are
// closed sets: touching a cell's edge or corner counts as intersecting it, and so does touching
// the grid's outer border (outside is never free). The test is exact up to a tolerance of 1e-9
// cells, applied on the conservative side (within it, "touching" is assumed).
//
// Two paths, same answer:
//  - fast: if the clearance of the reference point's cell exceeds the grown rectangle's
//    circumscribed radius plus half a cell diagonal, the whole disk around the reference point
//    that holds the rectangle is free: answer "free" in O(1), without trigonometry;
//  - exact: a scanline over the cell rows the rotated rectangle covers; in each row strip the
//    rectangle's exact x-extent (its left boundary is the max of two edge lines, its right
//    the min, evaluated at the left/right vertex's height clamped into the strip) gives the run
//    of cells to test against a bit grid of non-free cells (one or two 64-bit words a row).
//
// The checker keeps a pointer to the grid: the grid must outlive the checker and must not move.
// It answers for a snapshot of the grid taken at creation and by refresh(): after the grid
// changes, call refresh() (stale() tells) or the answers stay those of the old grid.
// is_free(), refresh() and the rest never allocate and never throw.

#include <cmath>
#include <cstdint>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/clearance_map.hpp"
#include "grip/world/footprint.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

class CollisionChecker {
 public:
  // Errors (kInvalidArgument): a non-finite footprint size, half_width_m <= 0,
  // front_m + rear_m <= 0, margin_m negative or not finite, shared_clearance_m negative or not
  // finite. Computes the clearance map. shared_clearance_m: the largest clearance others ask of
  // clearance() (e.g. the inflation of a DistanceField sharing it); refresh(changed) keeps
  // clearance exact up to it as well as up to what the checker itself needs.
  static Result<CollisionChecker> create(const OccupancyGrid& grid, const Footprint& footprint,
                                         double margin_m, double shared_clearance_m = 0.0);

  // True iff the grown chassis at (x_m, y_m, theta_rad) touches only known-free cells inside
  // the grid. Non-finite input is never free.
  bool is_free(double x_m, double y_m, double theta_rad) const noexcept {
    if (fast_path_free(x_m, y_m)) return std::isfinite(theta_rad);
    return covering_disks_or_exact(x_m, y_m, theta_rad, margin_m_);
  }

  // The same for the chassis grown by margin_m instead of margin(), up to margin() (a larger
  // margin_m, or one not finite, checks with margin()): a vehicle moving slowly needs less
  // margin between two checks than one at top speed (planner/step_margin.hpp). The fast tiers,
  // built for margin(), answer "free" only where the larger chassis is free; the exact test
  // decides the rest with the smaller one.
  bool is_free(double x_m, double y_m, double theta_rad, double margin_m) const noexcept {
    return is_free_with(x_m, y_m, theta_rad, [margin_m] { return margin_m; });
  }
  // The same with the margin computed by margin_of() (a double), called only when the fast
  // path cannot decide: in open space the margin costs nothing.
  template <typename MarginOf>
  bool is_free_with(double x_m, double y_m, double theta_rad, MarginOf&& margin_of) const noexcept {
    if (fast_path_free(x_m, y_m)) return std::isfinite(theta_rad);
    const double margin_m = margin_of();
    return covering_disks_or_exact(x_m, y_m, theta_rad,
                                   margin_m >= 0.0 && margin_m < margin_m_ ? margin_m : margin_m_);
  }

  // The exact path alone (what is_free answers when the fast path cannot decide).
  bool rectangle_is_free_exact(double x_m, double y_m, double theta_rad) const noexcept;

  // True iff the fast path alone decides (x_m, y_m) is free for every heading (and margin).
  bool fast_path_free(double x_m, double y_m) const noexcept {
    const double u = (x_m - origin_x_m_) * inv_resolution_;
    const double v = (y_m - origin_y_m_) * inv_resolution_;
    if (!(u >= 0.0 && v >= 0.0 && u < width_d_ && v < height_d_)) return false;
    const auto cx = static_cast<std::uint32_t>(u);
    const auto cy = static_cast<std::uint32_t>(v);
    return ((fast_free_bits_[cy * words_per_row_ + (cx >> 6)] >> (cx & 63)) & 1) != 0;
  }

  // Takes a new snapshot of the grid: recomputes the clearance map and the checker's bit grids
  // (O(cells), no allocation). Both paths answer for the grid as of the last refresh().
  void refresh() noexcept;
  // The same when the grid changed only inside `changed` (between free and non-free) since the
  // last refresh: O(cells near it) (ClearanceMap::update), the same answers.
  void refresh(const CellBox& changed) noexcept;
  // True when the grid changed since the last refresh (or creation).
  bool stale() const noexcept { return grid_->revision() != clearance_.source_revision(); }

  const Footprint& footprint() const noexcept { return footprint_; }
  double margin() const noexcept { return margin_m_; }
  // The footprint grown by margin() on every side: what is actually checked.
  Footprint checked_footprint() const noexcept { return footprint_.inflated(margin_m_); }
  const OccupancyGrid& grid() const noexcept { return *grid_; }
  // The clearance of the grid as of the last refresh; DistanceField::compute can share it.
  const ClearanceMap& clearance() const noexcept { return clearance_; }

 private:
  CollisionChecker(const OccupancyGrid& grid, const Footprint& footprint, double margin_m,
                   ClearanceMap clearance);

  const OccupancyGrid* grid_;
  Footprint footprint_;
  double margin_m_;
  void rebuild_bits(const CellBox& box) noexcept;  // the cells of box, inside the grid
  CellBox whole() const noexcept {
    return CellBox{0, 0, static_cast<int>(width_) - 1, static_cast<int>(height_) - 1};
  }
  // Second tier: the grown rectangle is covered by disks along its axis; if the clearance map
  // clears every disk the answer is "free", else the exact test decides.
  bool covering_disks_or_exact(double x_m, double y_m, double theta_rad,
                               double margin_m) const noexcept;
  bool exact(double x_m, double y_m, double c, double s, double margin_m) const noexcept;

  static constexpr int kMaxDisks = 4;
  int disk_count_ = 1;
  double disk_offset_cells_[kMaxDisks] = {};  // along the body axis from the reference point
  std::uint32_t disk_free_d2_ = 0;            // a disk is clear when d2 of its cell exceeds this

  ClearanceMap clearance_;
  std::uint32_t fast_free_d2_;  // fast path: free when d2 of the reference cell exceeds this
  std::uint32_t exact_d2_;      // the largest d2 any user compares with (refresh(changed))
  // Bit grids, one bit per cell, rows of words_per_row_ 64-bit words (the last word of a row
  // is never read past; bits beyond the width are set in blocked_bits_):
  std::uint32_t words_per_row_;
  std::vector<std::uint64_t> blocked_bits_;    // 1 = not kFree
  std::vector<std::uint64_t> fast_free_bits_;  // 1 = d2 > fast_free_d2_
  std::uint32_t width_;
  std::uint32_t height_;
  double width_d_;
  double height_d_;
  double origin_x_m_;
  double origin_y_m_;
  double inv_resolution_;
};

}  // namespace grip
