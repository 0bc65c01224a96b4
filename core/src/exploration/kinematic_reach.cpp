#include "grip/exploration/kinematic_reach.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>

#include "../world/validation.hpp"
#include "grip/common/assert.hpp"

namespace grip {

namespace {

constexpr double kBinRad = 2.0 * std::numbers::pi / KinematicReach::kHeadingBins;
constexpr std::size_t kMaxRing = std::size_t{1} << 20;

// theta finite: wrapped first, so that any heading rounds within range.
int nearest_bin(double theta) noexcept {
  const double wrapped = std::remainder(theta, 2.0 * std::numbers::pi);  // [-pi, pi]
  const long bin = std::lround(wrapped / kBinRad) % KinematicReach::kHeadingBins;
  return static_cast<int>(bin < 0 ? bin + KinematicReach::kHeadingBins : bin);
}

}  // namespace

Status KinematicReachConfig::validate() const {
  if (!(std::isfinite(turning_radius_m) && turning_radius_m > 0.0)) {
    return invalid_argument("kinematic reach: turning_radius_m must be finite and > 0 (got " +
                            detail::format_number(turning_radius_m) + ")");
  }
  if (max_expansions == 0) return invalid_argument("kinematic reach: max_expansions must be > 0");
  return Ok{};
}

Result<KinematicReach> KinematicReach::create(const OccupancyGrid& grid,
                                              const KinematicReachConfig& config) {
  if (Status s = config.validate(); !s) return s.error();
  auto checker = CollisionChecker::create(grid, config.footprint, 0.0);
  if (!checker) return checker.error();
  return KinematicReach(grid, config, std::move(checker).value());
}

KinematicReach::KinematicReach(const OccupancyGrid& grid, const KinematicReachConfig& config,
                               CollisionChecker checker)
    : grid_(&grid),
      config_(config),
      checker_(std::move(checker)),
      visited_(grid.cell_count(), 0),
      blocked_(grid.cell_count(), 0),
      pending_(grid.cell_count(), 0),
      passed_((grid.cell_count() + 63) / 64, 0),
      ring_(std::min<std::size_t>(std::size_t{grid.cell_count()} * kHeadingBins, kMaxRing)) {
  build_moves();
}

// A bin's arc at the turning radius, or as long as one and a half cells where that is longer
// (a move must leave its cell: on a coarse grid the turn is then wider than full lock).
void KinematicReach::build_moves() noexcept {
  const double resolution = grid_->resolution();
  const double step_m = std::max(config_.turning_radius_m * kBinRad, 1.5 * resolution);
  const double curvature = kBinRad / step_m;
  const int samples =
      std::clamp(static_cast<int>(std::ceil(step_m / (0.5 * resolution))), 1, Move::kMaxSamples);
  reach_cells_ = static_cast<int>(
                     std::ceil((step_m + config_.footprint.circumscribed_radius()) / resolution)) +
                 1;
  moves_.resize(static_cast<std::size_t>(kHeadingBins) * kMovesPerBin);
  for (int bin = 0; bin < kHeadingBins; ++bin) {
    const double theta0 = bin * kBinRad;
    for (int m = 0; m < kMovesPerBin; ++m) {
      const double direction = m < 3 ? 1.0 : -1.0;
      const int steer = m % 3 - 1;  // -1 right, 0 straight, +1 left
      Move& move = moves_[static_cast<std::size_t>(bin * kMovesPerBin + m)];
      move.samples = samples;
      for (int i = 0; i < samples; ++i) {
        const double s = direction * step_m * (i + 1) / samples;
        const double theta = theta0 + steer * curvature * s;
        double x = s * std::cos(theta0);
        double y = s * std::sin(theta0);
        if (steer != 0) {
          x = (std::sin(theta) - std::sin(theta0)) / (steer * curvature);
          y = -(std::cos(theta) - std::cos(theta0)) / (steer * curvature);
        }
        move.dx_m[static_cast<std::size_t>(i)] = x;
        move.dy_m[static_cast<std::size_t>(i)] = y;
        move.theta[static_cast<std::size_t>(i)] = theta;
      }
      const auto last = static_cast<std::size_t>(samples - 1);
      move.end_dx = static_cast<int>(std::lround(move.dx_m[last] / resolution));
      move.end_dy = static_cast<int>(std::lround(move.dy_m[last] / resolution));
      move.end_bin = ((bin + steer * static_cast<int>(direction)) % kHeadingBins + kHeadingBins) %
                     kHeadingBins;
    }
  }
}

void KinematicReach::update(const CellBox& changed, double x_m, double y_m, double theta) noexcept {
  const OccupancyGrid& grid = *grid_;
  if (!changed.empty()) {
    checker_.refresh(changed);
    // States near the change whose moves were blocked may now go on.
    const int x0 = std::max(changed.x0 - reach_cells_, 0);
    const int y0 = std::max(changed.y0 - reach_cells_, 0);
    const int x1 = std::min(changed.x1 + reach_cells_, grid.width() - 1);
    const int y1 = std::min(changed.y1 + reach_cells_, grid.height() - 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::uint32_t c = grid.index(x, y);
        if (blocked_[c] != 0) schedule(c, blocked_[c]);
      }
    }
  }
  int cx = 0;
  int cy = 0;
  if (std::isfinite(theta) && grid.to_cell(x_m, y_m, cx, cy)) {
    seed(grid.index(cx, cy), nearest_bin(theta));
  }
  std::uint32_t state = 0;
  for (std::uint32_t n = 0; n < config_.max_expansions && pop(state); ++n) {
    expand(state / kHeadingBins, static_cast<int>(state % kHeadingBins));
  }
}

void KinematicReach::seed(std::uint32_t cell, int bin) noexcept {
  const auto bit = static_cast<std::uint16_t>(1U << bin);
  mark_passed(grid_->cell_x(cell), grid_->cell_y(cell));
  if ((visited_[cell] & bit) != 0) return;
  visited_[cell] |= bit;
  ++states_reached_;
  schedule(cell, bit);
}

void KinematicReach::schedule(std::uint32_t cell, std::uint16_t bins) noexcept {
  auto fresh = static_cast<std::uint16_t>(bins & ~pending_[cell]);
  pending_[cell] |= fresh;
  for (; fresh != 0; fresh &= static_cast<std::uint16_t>(fresh - 1)) {
    if (ring_size_ == ring_.size()) {
      overflow_ = true;  // stays pending: refill_from_pending() finds it
      return;
    }
    ring_[(ring_head_ + ring_size_++) % ring_.size()] =
        cell * kHeadingBins + static_cast<std::uint32_t>(std::countr_zero(fresh));
  }
}

bool KinematicReach::pop(std::uint32_t& state) noexcept {
  if (ring_size_ == 0 && overflow_) refill_from_pending();
  if (ring_size_ == 0) return false;
  state = ring_[ring_head_];
  ring_head_ = (ring_head_ + 1) % ring_.size();
  --ring_size_;
  return true;
}

// Called with the ring empty: every pending state is outside it.
void KinematicReach::refill_from_pending() noexcept {
  overflow_ = false;
  ring_head_ = 0;
  for (std::uint32_t c = 0; c < pending_.size(); ++c) {
    for (std::uint16_t bins = pending_[c]; bins != 0;
         bins &= static_cast<std::uint16_t>(bins - 1)) {
      if (ring_size_ == ring_.size()) {
        overflow_ = true;
        return;
      }
      ring_[ring_size_++] = c * kHeadingBins + static_cast<std::uint32_t>(std::countr_zero(bins));
    }
  }
}

void KinematicReach::expand(std::uint32_t cell, int bin) noexcept {
  const OccupancyGrid& grid = *grid_;
  const auto bit = static_cast<std::uint16_t>(1U << bin);
  pending_[cell] &= static_cast<std::uint16_t>(~bit);
  blocked_[cell] &= static_cast<std::uint16_t>(~bit);
  const int cx = grid.cell_x(cell);
  const int cy = grid.cell_y(cell);
  const double x0 = grid.cell_center_x(cx);
  const double y0 = grid.cell_center_y(cy);
  for (int m = 0; m < kMovesPerBin; ++m) {
    const Move& move = moves_[static_cast<std::size_t>(bin * kMovesPerBin + m)];
    const int ex = cx + move.end_dx;
    const int ey = cy + move.end_dy;
    bool free = grid.in_bounds(ex, ey);
    int blocked_at = -1;
    for (int i = 0; i < move.samples && free; ++i) {
      const auto k = static_cast<std::size_t>(i);
      free = checker_.is_free(x0 + move.dx_m[k], y0 + move.dy_m[k], move.theta[k]);
      if (!free) blocked_at = i;
    }
    if (!free) {
      // Known obstacles stay: only a move that unknown cells may have blocked is tried again.
      if (blocked_at >= 0) {
        const auto k = static_cast<std::size_t>(blocked_at);
        if (unknown_near(x0 + move.dx_m[k], y0 + move.dy_m[k])) blocked_[cell] |= bit;
      }
      continue;
    }
    for (int i = 0; i < move.samples; ++i) {
      const auto k = static_cast<std::size_t>(i);
      int px = 0;
      int py = 0;
      if (grid.to_cell(x0 + move.dx_m[k], y0 + move.dy_m[k], px, py)) mark_passed(px, py);
    }
    const std::uint32_t end = grid.index(ex, ey);
    const auto end_bit = static_cast<std::uint16_t>(1U << move.end_bin);
    if ((visited_[end] & end_bit) != 0) continue;
    visited_[end] |= end_bit;
    ++states_reached_;
    schedule(end, end_bit);
  }
}

// Any unknown cell within the chassis' circumscribed disk round (x_m, y_m), or the pose off the
// grid (the grid's edge may be where the map is not known yet).
bool KinematicReach::unknown_near(double x_m, double y_m) const noexcept {
  const OccupancyGrid& grid = *grid_;
  const double r = config_.footprint.circumscribed_radius();
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
  if (!grid.to_cell(x_m - r, y_m - r, x0, y0) || !grid.to_cell(x_m + r, y_m + r, x1, y1)) {
    return true;
  }
  const std::span<const Cell> cells = grid.cells();
  for (int y = y0; y <= y1; ++y) {
    const std::uint32_t row = grid.index(0, y);
    for (int x = x0; x <= x1; ++x) {
      if (cells[row + static_cast<std::uint32_t>(x)] == Cell::kUnknown) return true;
    }
  }
  return false;
}

bool KinematicReach::passed(std::uint32_t cell) const noexcept {
  GRIP_ASSERT(cell < grid_->cell_count());
  return ((passed_[cell >> 6] >> (cell & 63U)) & 1U) != 0;
}

void KinematicReach::mark_passed(int cx, int cy) noexcept {
  const std::uint32_t c = grid_->index(cx, cy);
  passed_[c >> 6] |= std::uint64_t{1} << (c & 63U);
}

}  // namespace grip
