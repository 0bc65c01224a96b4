#include "grip/world/collision_checker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "grip/common/saturating_cast.hpp"

#include "validation.hpp"

namespace grip {

namespace {

// Tolerance of the exact test, in cells: extents are widened by this much, so configurations
// within it of touching a cell count as touching (conservative, and independent of rounding).
constexpr double kTouchTolerance = 1e-9;

}  // namespace

Result<CollisionChecker> CollisionChecker::create(const OccupancyGrid& grid,
                                                  const Footprint& footprint, double margin_m,
                                                  double shared_clearance_m) {
  const auto bad = [](const char* name, double value, const char* rule) {
    return invalid_argument(std::string("CollisionChecker: ") + name + " " + rule + " (got " +
                            detail::format_number(value) + ")");
  };
  if (!std::isfinite(footprint.front_m)) {
    return bad("footprint.front_m", footprint.front_m, "must be finite");
  }
  if (!std::isfinite(footprint.rear_m)) {
    return bad("footprint.rear_m", footprint.rear_m, "must be finite");
  }
  if (!(std::isfinite(footprint.half_width_m) && footprint.half_width_m > 0.0)) {
    return bad("footprint.half_width_m", footprint.half_width_m, "must be finite and > 0");
  }
  if (!(footprint.front_m + footprint.rear_m > 0.0)) {
    return bad("footprint.front_m + footprint.rear_m", footprint.front_m + footprint.rear_m,
               "must be > 0");
  }
  if (!(std::isfinite(margin_m) && margin_m >= 0.0)) {
    return bad("margin_m", margin_m, "must be finite and >= 0");
  }
  if (!(std::isfinite(shared_clearance_m) && shared_clearance_m >= 0.0)) {
    return bad("shared_clearance_m", shared_clearance_m, "must be finite and >= 0");
  }
  auto clearance = ClearanceMap::create_for(grid);
  if (!clearance.ok()) {
    return clearance.error();
  }
  CollisionChecker checker(grid, footprint, margin_m, std::move(clearance).value());
  checker.exact_d2_ = std::max({checker.fast_free_d2_, checker.disk_free_d2_,
                                checker.clearance_.squared_cells_at_least(shared_clearance_m)});
  return checker;
}

CollisionChecker::CollisionChecker(const OccupancyGrid& grid, const Footprint& footprint,
                                   double margin_m, ClearanceMap clearance)
    : grid_(&grid),
      footprint_(footprint),
      margin_m_(margin_m),
      clearance_(std::move(clearance)),
      width_(static_cast<std::uint32_t>(grid.width())),
      height_(static_cast<std::uint32_t>(grid.height())),
      width_d_(grid.width()),
      height_d_(grid.height()),
      origin_x_m_(grid.origin_x()),
      origin_y_m_(grid.origin_y()),
      inv_resolution_(1.0 / grid.resolution()) {
  const Footprint grown = footprint.inflated(margin_m);

  // Fast path soundness. Every point of the reference cell is within hd (half a cell diagonal)
  // of its centre, and clearance_m(cell) = sqrt(d2) * res - hd is a lower bound of the distance
  // from that centre to any non-free point. So if sqrt(d2) * res - hd > R + hd (+ a tolerance
  // well above the exact test's), the disk of radius R around the reference point, which holds
  // the grown rectangle, is strictly clear of every non-free cell:
  //   d2 > ((R + 2 hd + tol) / res)^2.
  const double res = grid.resolution();
  const double hd = res * std::sqrt(0.5);
  constexpr double kMax = static_cast<double>(std::numeric_limits<std::uint32_t>::max());
  const auto to_d2 = [&](double radius_m) {
    const double q_cells = (radius_m + 2.0 * hd + 1e-6 * res) / res;
    const double q_squared = q_cells * q_cells * (1.0 + 1e-12);  // round up, never down
    return q_squared < kMax ? static_cast<std::uint32_t>(std::floor(q_squared))
                            : std::numeric_limits<std::uint32_t>::max();
  };
  fast_free_d2_ = to_d2(grown.circumscribed_radius());

  // Covering disks: n equal segments of the rectangle's length, each inside a disk through its
  // corners, radius sqrt((length / 2n)^2 + half_width^2). The same bound as above applies to
  // each disk's centre cell.
  const double length = grown.front_m + grown.rear_m;
  disk_count_ = ceil_to_count(length / (2.0 * grown.half_width_m), 1, kMaxDisks);
  const double segment = length / disk_count_;
  for (int i = 0; i < disk_count_; ++i) {
    disk_offset_cells_[i] = (-grown.rear_m + segment * (i + 0.5)) * inv_resolution_;
  }
  disk_free_d2_ = to_d2(std::hypot(0.5 * segment, grown.half_width_m));

  words_per_row_ = (width_ + 63) / 64;
  blocked_bits_.assign(static_cast<std::size_t>(words_per_row_) * height_, 0);
  fast_free_bits_.assign(static_cast<std::size_t>(words_per_row_) * height_, 0);
  rebuild_bits(whole());
}

void CollisionChecker::refresh() noexcept {
  clearance_.compute(*grid_);
  rebuild_bits(whole());
}

void CollisionChecker::refresh(const CellBox& changed) noexcept {
  const CellBox rewritten = clearance_.update(*grid_, changed, exact_d2_);
  if (!rewritten.empty()) rebuild_bits(rewritten);
}

// The words covering the box's columns, whole: a word's bits outside the box are rebuilt from
// cells that did not change, to what they were.
void CollisionChecker::rebuild_bits(const CellBox& box) noexcept {
  const std::span<const Cell> cells = grid_->cells();
  const std::span<const std::uint32_t> d2 = clearance_.squared_cells();
  const auto k0 = static_cast<std::uint32_t>(box.x0) / 64;
  const auto k1 = static_cast<std::uint32_t>(box.x1) / 64;
  for (auto y = static_cast<std::uint32_t>(box.y0); y <= static_cast<std::uint32_t>(box.y1); ++y) {
    std::uint64_t* blocked = blocked_bits_.data() + static_cast<std::size_t>(y) * words_per_row_;
    std::uint64_t* fast = fast_free_bits_.data() + static_cast<std::size_t>(y) * words_per_row_;
    for (std::uint32_t k = k0; k <= k1; ++k) {
      std::uint64_t blocked_word = 0;
      std::uint64_t fast_word = 0;
      for (std::uint32_t bit = 0; bit < 64; ++bit) {
        const std::uint32_t x = k * 64 + bit;
        if (x >= width_) {
          blocked_word |= std::uint64_t{1} << bit;  // beyond the width: never free
          continue;
        }
        const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
        if (cells[i] != Cell::kFree) {
          blocked_word |= std::uint64_t{1} << bit;
        }
        if (d2[i] > fast_free_d2_) {
          fast_word |= std::uint64_t{1} << bit;
        }
      }
      blocked[k] = blocked_word;
      fast[k] = fast_word;
    }
  }
}

bool CollisionChecker::rectangle_is_free_exact(double x_m, double y_m,
                                               double theta_rad) const noexcept {
  if (!(std::isfinite(x_m) && std::isfinite(y_m) && std::isfinite(theta_rad))) {
    return false;
  }
  return exact(x_m, y_m, std::cos(theta_rad), std::sin(theta_rad), margin_m_);
}

bool CollisionChecker::covering_disks_or_exact(double x_m, double y_m, double theta_rad,
                                               double margin_m) const noexcept {
  if (!(std::isfinite(x_m) && std::isfinite(y_m) && std::isfinite(theta_rad))) {
    return false;
  }
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  const double px = (x_m - origin_x_m_) * inv_resolution_;
  const double py = (y_m - origin_y_m_) * inv_resolution_;
  bool all_clear = true;
  for (int i = 0; i < disk_count_ && all_clear; ++i) {
    const double u = px + c * disk_offset_cells_[i];
    const double v = py + s * disk_offset_cells_[i];
    all_clear = u >= 0.0 && v >= 0.0 && u < width_d_ && v < height_d_ &&
                clearance_.squared_cells(static_cast<std::uint32_t>(v) * width_ +
                                         static_cast<std::uint32_t>(u)) > disk_free_d2_;
  }
  return all_clear || exact(x_m, y_m, c, s, margin_m);
}

bool CollisionChecker::exact(double x_m, double y_m, double c, double s,
                             double margin_m) const noexcept {
  // Everything below is in cell units relative to the grid origin.
  const double px = (x_m - origin_x_m_) * inv_resolution_;
  const double py = (y_m - origin_y_m_) * inv_resolution_;
  const double front_cells = (footprint_.front_m + margin_m) * inv_resolution_;
  const double rear_cells = (footprint_.rear_m + margin_m) * inv_resolution_;
  const double half_width_cells = (footprint_.half_width_m + margin_m) * inv_resolution_;
  const double fx = c * front_cells;
  const double fy = s * front_cells;
  const double rx = -c * rear_cells;
  const double ry = -s * rear_cells;
  const double lx = -s * half_width_cells;
  const double ly = c * half_width_cells;
  // Counter-clockwise: front-right, front-left, rear-left, rear-right.
  const double vx[4] = {px + fx - lx, px + fx + lx, px + rx + lx, px + rx - lx};
  const double vy[4] = {py + fy - ly, py + fy + ly, py + ry + ly, py + ry - ly};

  // Bottom vertex; counter-clockwise from it come the right, top and left vertices (for a
  // rectangle the top is always opposite the bottom; with ties, any lowest vertex will do).
  int b = 0;
  for (int k = 1; k < 4; ++k) {
    if (vy[k] < vy[b]) {
      b = k;
    }
  }
  const double bx = vx[b], by = vy[b];
  const double rvx = vx[(b + 1) & 3], rvy = vy[(b + 1) & 3];
  const double tx = vx[(b + 2) & 3], ty = vy[(b + 2) & 3];
  const double lvx = vx[(b + 3) & 3], lvy = vy[(b + 3) & 3];

  // Touching the outside (the cells beyond the border) is a collision. Also rejects NaN.
  const double xmin = std::min(std::min(lvx, bx), tx) - kTouchTolerance;
  const double xmax = std::max(std::max(rvx, bx), tx) + kTouchTolerance;
  const double ymin = by - kTouchTolerance;
  const double ymax = ty + kTouchTolerance;
  if (!(xmin > 0.0 && ymin > 0.0 && xmax < width_d_ && ymax < height_d_)) {
    return false;
  }

  // For y in [by, ty], the right boundary x_r(y) is concave: the minimum of the lines through
  // its two edges (bottom -> right, right -> top); the left boundary x_l(y) is convex: the
  // maximum of the lines through bottom -> left and left -> top. A horizontal edge drops out
  // (its line is +-infinity). Over a strip [ya, yb] the extent is then
  //   [x_l(clamp(lvy, ya, yb)), x_r(clamp(rvy, ya, yb))]
  // because a convex function's minimum over an interval lies at the clamp of its minimiser.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double r1_slope = rvy > by ? (rvx - bx) / (rvy - by) : 0.0;
  const double r2_slope = ty > rvy ? (tx - rvx) / (ty - rvy) : 0.0;
  const double l1_slope = lvy > by ? (lvx - bx) / (lvy - by) : 0.0;
  const double l2_slope = ty > lvy ? (tx - lvx) / (ty - lvy) : 0.0;
  const double r1_cut = rvy > by ? 0.0 : kInf;  // added to a dropped line's value
  const double r2_cut = ty > rvy ? 0.0 : kInf;
  const double l1_cut = lvy > by ? 0.0 : -kInf;
  const double l2_cut = ty > lvy ? 0.0 : -kInf;

  const int row_first = std::max(saturating_cast<int>(std::ceil(ymin)) - 1, 0);
  const int row_last = std::min(saturating_cast<int>(ymax), static_cast<int>(height_) - 1);
  const std::uint64_t* words =
      blocked_bits_.data() + static_cast<std::size_t>(row_first) * words_per_row_;
  for (int row = row_first; row <= row_last; ++row, words += words_per_row_) {
    // The strip of this row, clamped to the rectangle's y-range (degenerate when only touched).
    const double ya = std::clamp(static_cast<double>(row), by, ty);
    const double yb = std::clamp(static_cast<double>(row + 1), by, ty);
    const double yl = std::clamp(lvy, ya, yb);
    const double yr = std::clamp(rvy, ya, yb);
    const double lo =
        std::max(bx + (yl - by) * l1_slope + l1_cut, lvx + (yl - lvy) * l2_slope + l2_cut) -
        kTouchTolerance;
    const double hi =
        std::min(bx + (yr - by) * r1_slope + r1_cut, rvx + (yr - rvy) * r2_slope + r2_cut) +
        kTouchTolerance;
    // Cells first..last (closed: a cell whose edge is exactly at lo or hi is touched). lo and
    // hi are positive up to rounding (bounds test above); the clamps keep reads in the row.
    const auto lo_cell = saturating_cast<int>(lo);  // floor for lo >= 0
    const int first = std::max(lo_cell - (static_cast<double>(lo_cell) == lo ? 1 : 0), 0);
    const int last = std::min(saturating_cast<int>(hi), static_cast<int>(width_) - 1);
    const auto first_word = static_cast<std::uint32_t>(first) >> 6;
    const auto last_word = static_cast<std::uint32_t>(last) >> 6;
    const std::uint64_t first_mask = ~std::uint64_t{0} << (first & 63);
    const std::uint64_t last_mask = ~std::uint64_t{0} >> (63 - (last & 63));
    std::uint64_t blocked = 0;
    if (first_word == last_word) {
      blocked = words[first_word] & first_mask & last_mask;
    } else {
      blocked = (words[first_word] & first_mask) | (words[last_word] & last_mask);
      for (std::uint32_t k = first_word + 1; k < last_word; ++k) {
        blocked |= words[k];
      }
    }
    if (blocked != 0) {
      return false;
    }
  }
  return true;
}

}  // namespace grip
