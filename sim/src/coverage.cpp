#include "grip/sim/coverage.hpp"

#include <iterator>
#include <limits>

#include "grip/world/distance_field.hpp"

namespace grip::sim {

Result<std::vector<std::uint32_t>> reachable_free_cells(const OccupancyGrid& truth, double x_m,
                                                        double y_m, const Footprint& footprint) {
  auto clearance = ClearanceMap::create_for(truth);
  if (!clearance) return clearance.error();
  auto centres = DistanceField::create(truth.width(), truth.height(), truth.resolution());
  if (!centres) return centres.error();
  auto body = DistanceField::create(truth.width(), truth.height(), truth.resolution());
  if (!body) return body.error();
  int cx = 0;
  int cy = 0;
  if (!truth.to_cell(x_m, y_m, cx, cy)) return invalid_argument("the start is outside the map");
  const std::uint32_t start[] = {truth.index(cx, cy)};
  centres->compute(truth, *clearance, start, footprint.half_width_m);
  const bool by_chassis = centres->traversable(start[0]);
  std::vector<std::uint32_t> from;
  if (by_chassis) {
    for (std::uint32_t c = 0; c < truth.cell_count(); ++c) {
      if (centres->reachable(c)) from.push_back(c);
    }
  } else {
    from.assign(std::begin(start), std::end(start));
  }
  body->compute(truth, from);
  const double reach =
      by_chassis ? footprint.circumscribed_radius() : std::numeric_limits<double>::infinity();
  std::vector<std::uint32_t> cells;
  for (std::uint32_t c = 0; c < truth.cell_count(); ++c) {
    if (body->reachable(c) && body->distance_m(truth.cell_center_x(truth.cell_x(c)),
                                               truth.cell_center_y(truth.cell_y(c))) <= reach) {
      cells.push_back(c);
    }
  }
  return cells;
}

std::size_t sensed_cells(const OccupancyGrid& known, const std::vector<std::uint32_t>& reachable) {
  std::size_t sensed = 0;
  for (const std::uint32_t c : reachable) sensed += known.at(c) != Cell::kUnknown ? 1U : 0U;
  return sensed;
}

double coverage_of(const OccupancyGrid& known, const std::vector<std::uint32_t>& reachable) {
  return reachable.empty() ? 1.0
                           : static_cast<double>(sensed_cells(known, reachable)) /
                                 static_cast<double>(reachable.size());
}

Result<UnsensedDistance> UnsensedDistance::create(const OccupancyGrid& truth,
                                                  const std::vector<std::uint32_t>& reachable) {
  auto field = DistanceField::create(truth.width(), truth.height(), truth.resolution());
  if (!field) return field.error();
  return UnsensedDistance(truth, reachable, std::move(field).value());
}

double UnsensedDistance::from(const OccupancyGrid& known, double x_m, double y_m) {
  unsensed_.clear();
  for (const std::uint32_t c : *reachable_) {
    if (known.at(c) == Cell::kUnknown) unsensed_.push_back(c);
  }
  if (unsensed_.empty()) return std::numeric_limits<double>::infinity();
  field_.compute(*truth_, unsensed_);
  return field_.distance_m(x_m, y_m);
}

}  // namespace grip::sim
