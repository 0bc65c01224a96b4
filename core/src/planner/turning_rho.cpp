#include "grip/planner/turning_rho.hpp"

#include <algorithm>
#include <limits>

namespace grip {

namespace {

constexpr double kLookaheadTurningRadii = 3.0;
// A power of two; 64 K cells hold a tree spread over 25 m x 25 m at 0.1 m.
constexpr std::size_t kCacheEntries = std::size_t{1} << 16;

}  // namespace

Result<TurningRho> TurningRho::create(double turning_radius_m, double resolution_m) {
  const double lookahead_m = kLookaheadTurningRadii * turning_radius_m;
  // The table reaches every lookahead point: it lies within lookahead_m (straight) of the state
  // plus the half diagonal of its cell; its cells are a fraction of the grid's and of R.
  auto table = TurningDistance::create(turning_radius_m, lookahead_m + resolution_m,
                                       std::min(0.5 * resolution_m, 0.1 * turning_radius_m));
  if (!table) return table.error();
  return TurningRho(std::move(table).value(), lookahead_m, resolution_m);
}

TurningRho::TurningRho(TurningDistance table, double lookahead_m, double resolution_m)
    : table_(std::move(table)),
      cache_(kCacheEntries),
      lookahead_m_(lookahead_m),
      lookahead_units_(static_cast<std::uint32_t>(
          std::ceil(lookahead_m / resolution_m * DistanceField::kCostUnitsPerCell))),
      half_cell_m_(0.5 * resolution_m) {}

double TurningRho::at(const DistanceField& field, double x_m, double y_m,
                      double theta) const noexcept {
  const std::uint32_t cell = field.cell_at(x_m, y_m);
  if (cell == DistanceField::kNoCell || !field.reachable(cell)) {
    return std::numeric_limits<double>::infinity();
  }
  const std::uint32_t ahead = lookahead_cell(field, cell);
  const auto w = static_cast<std::uint32_t>(field.width());
  const double ax =
      field.origin_x_m() + (static_cast<double>(ahead % w) + 0.5) * field.resolution();
  const double ay =
      field.origin_y_m() + (static_cast<double>(ahead / w) + 0.5) * field.resolution();
  // The lookahead cell in the vehicle's frame, its nearest point rather than its centre.
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const double dx = ax - x_m;
  const double dy = ay - y_m;
  const double along = c * dx + s * dy;
  const double across = c * dy - s * dx;
  const double turn = table_.at(std::max(std::abs(along) - half_cell_m_, 0.0),
                                std::max(std::abs(across) - half_cell_m_, 0.0));
  return std::max(field.at(cell), field.at(ahead) + turn);
}

void TurningRho::forget() noexcept {
  // Generation 0 marks the entries never filled; a wrap clears them all once in 2^32 fields.
  if (++generation_ == 0) {
    std::fill(cache_.begin(), cache_.end(), CachedLookahead{});
    generation_ = 1;
  }
}

std::uint32_t TurningRho::lookahead_cell(const DistanceField& field,
                                         std::uint32_t cell) const noexcept {
  CachedLookahead& entry = cache_[cell & (kCacheEntries - 1)];
  if (entry.cell != cell || entry.generation != generation_) {
    entry = CachedLookahead{cell, generation_, field.descend(cell, lookahead_units_)};
  }
  return entry.ahead;
}

}  // namespace grip
