#include "grip/world/nearest_source_field.hpp"

#include <string>

namespace grip {

Result<NearestSourceField> NearestSourceField::create(int width_cells, int height_cells) {
  if (width_cells <= 0 || height_cells <= 0 ||
      static_cast<std::uint64_t>(width_cells) * static_cast<std::uint64_t>(height_cells) >
          (1ULL << 24)) {
    return invalid_argument(
        "nearest source field: size must be positive and at most 2^24 cells "
        "(got " +
        std::to_string(width_cells) + " x " + std::to_string(height_cells) + ")");
  }
  return NearestSourceField(width_cells, height_cells);
}

NearestSourceField::NearestSourceField(int width_cells, int height_cells)
    : width_(width_cells),
      height_(height_cells),
      cost_(new std::uint32_t[static_cast<std::size_t>(width_cells) *
                              static_cast<std::size_t>(height_cells)]),
      source_(new std::uint32_t[static_cast<std::size_t>(width_cells) *
                                static_cast<std::size_t>(height_cells)]),
      open_(static_cast<std::uint32_t>(width_cells * height_cells)) {}

void NearestSourceField::reset() noexcept {
  const auto cells = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  for (std::size_t i = 0; i < cells; ++i) {
    cost_[i] = DistanceField::kUnreachable;
    source_[i] = kNoCell;
  }
  open_.clear();
}

void NearestSourceField::add_source(const DistanceField& metric, std::uint32_t cell) noexcept {
  GRIP_ASSERT(metric.width() == width_ && metric.height() == height_);
  if (!metric.traversable(cell) || cost_[cell] == 0) return;
  cost_[cell] = 0;
  source_[cell] = cell;
  GRIP_ASSERT(open_.push(cell, 0.0));
  const auto passable = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width_ && y < height_ &&
           metric.traversable(static_cast<std::uint32_t>(y * width_ + x));
  };
  while (!open_.empty()) {
    const std::uint32_t u = open_.pop();
    const int ux = static_cast<int>(u % static_cast<std::uint32_t>(width_));
    const int uy = static_cast<int>(u / static_cast<std::uint32_t>(width_));
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !passable(ux + dx, uy + dy)) continue;
        // Diagonal moves may not cut a corner (DistanceField's rule).
        const bool diagonal = dx != 0 && dy != 0;
        if (diagonal && (!passable(ux + dx, uy) || !passable(ux, uy + dy))) continue;
        const std::uint32_t step =
            diagonal ? DistanceField::kDiagonalCost : DistanceField::kOrthogonalCost;
        const auto v = static_cast<std::uint32_t>((uy + dy) * width_ + ux + dx);
        const std::uint32_t through_u = cost_[u] + step;
        if (through_u >= cost_[v]) continue;
        cost_[v] = through_u;
        source_[v] = source_[u];
        if (open_.contains(v)) {
          open_.update(v, through_u);
        } else {
          GRIP_ASSERT(open_.push(v, through_u));
        }
      }
    }
  }
}

}  // namespace grip
