#include "grip/sim/range_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "grip/world/line_of_sight.hpp"

namespace grip::sim {

namespace {
constexpr double kRaySpacingCells = 0.5;  // at full range, between neighbouring rays
constexpr std::uint32_t kMinRays = 16;
constexpr double kMaxRays = 1 << 20;
}  // namespace

double RangeSensor::default_radius_m(const OccupancyGrid& truth) noexcept {
  return 0.1 * std::max(truth.width_m(), truth.height_m());
}

Result<RangeSensor> RangeSensor::create(const OccupancyGrid& truth, double radius_m,
                                        std::uint32_t rays) {
  if (!std::isfinite(radius_m) || radius_m <= 0.0) {
    return invalid_argument("range sensor radius_m must be a finite number > 0 (got " +
                            std::to_string(radius_m) + ")");
  }
  const double radius_cells = radius_m / truth.resolution();
  if (rays != 0 && (rays < kMinRays || rays > kMaxRays)) {
    return invalid_argument("range sensor rays must be 0 (enough for every cell in range) or in [" +
                            std::to_string(kMinRays) + ", " +
                            std::to_string(static_cast<std::uint32_t>(kMaxRays)) + "] (got " +
                            std::to_string(rays) + ")");
  }
  const double ray_count =
      rays != 0
          ? rays
          : std::max<double>(kMinRays,
                             std::ceil(2.0 * std::numbers::pi * radius_cells / kRaySpacingCells));
  if (ray_count > kMaxRays) {
    return invalid_argument("range sensor radius_m " + std::to_string(radius_m) +
                            " needs more than 2^20 rays at resolution " +
                            std::to_string(truth.resolution()) + " m");
  }
  // Every seen cell lies in the disk's bounding box, grown by one cell for the corner rule and
  // the cell the ray ends in; each cell changes at most once per sweep.
  const double side = 2.0 * std::ceil(radius_cells) + 3.0;
  const auto capacity =
      static_cast<std::size_t>(std::min(side * side, static_cast<double>(truth.cell_count())));
  return RangeSensor(truth, radius_m, static_cast<std::uint32_t>(ray_count), capacity);
}

RangeSensor::RangeSensor(const OccupancyGrid& truth, double radius_m, std::uint32_t rays,
                         std::size_t capacity)
    : truth_(&truth), radius_m_(radius_m), cos_(rays), sin_(rays), capacity_(capacity) {
  for (std::uint32_t k = 0; k < rays; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / rays;
    cos_[k] = std::cos(angle);
    sin_[k] = std::sin(angle);
  }
  changed_.reserve(capacity);
}

SenseResult RangeSensor::sense(double x_m, double y_m, OccupancyGrid& known) noexcept {
  const OccupancyGrid& truth = *truth_;
  GRIP_ASSERT(known.width() == truth.width() && known.height() == truth.height());
  GRIP_ASSERT(known.resolution() == truth.resolution());
  GRIP_ASSERT(known.origin_x() == truth.origin_x() && known.origin_y() == truth.origin_y());
  changed_.clear();
  SenseResult result;
  auto see = [&](int cx, int cy) noexcept {
    const Cell value = truth.at(cx, cy);
    if (known.at(cx, cy) != value) {
      known.set(cx, cy, value);
      GRIP_ASSERT(changed_.size() < capacity_);  // so push_back never reallocates
      changed_.push_back(known.index(cx, cy));
      result.changed.add(CellBox{cx, cy, cx, cy});
    }
    return value == Cell::kFree;
  };
  for (std::size_t k = 0; k < cos_.size(); ++k) {
    const TraversalResult r = traverse_segment(truth, x_m, y_m, x_m + radius_m_ * cos_[k],
                                               y_m + radius_m_ * sin_[k], see);
    result.cells_visited += r.cells_visited;
  }
  result.changed_cells = changed_;
  return result;
}

void for_each_patch(const CellBox& box, std::uint32_t max_cells,
                    FunctionRef<void(const CellBox&)> emit) noexcept {
  GRIP_ASSERT(max_cells >= 1);
  if (box.empty()) return;
  const auto width = static_cast<std::uint32_t>(box.x1 - box.x0 + 1);
  const std::uint32_t tile_w = std::min(width, max_cells);
  const std::uint32_t tile_h = std::max(1U, max_cells / tile_w);
  for (int y = box.y0; y <= box.y1; y += static_cast<int>(tile_h)) {
    for (int x = box.x0; x <= box.x1; x += static_cast<int>(tile_w)) {
      emit(CellBox{x, y, std::min(box.x1, x + static_cast<int>(tile_w) - 1),
                   std::min(box.y1, y + static_cast<int>(tile_h) - 1)});
    }
  }
}

}  // namespace grip::sim
