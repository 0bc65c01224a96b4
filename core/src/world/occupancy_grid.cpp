#include "grip/world/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "validation.hpp"

namespace grip {

OccupancyGrid::OccupancyGrid(int width_cells, int height_cells, double resolution_m,
                             double origin_x_m, double origin_y_m, Cell fill)
    : width_(width_cells),
      height_(height_cells),
      resolution_(resolution_m),
      inv_resolution_(1.0 / resolution_m),
      origin_x_(origin_x_m),
      origin_y_(origin_y_m),
      cells_(static_cast<std::size_t>(width_cells) * static_cast<std::size_t>(height_cells), fill) {
}

Result<OccupancyGrid> OccupancyGrid::create(int width_cells, int height_cells, double resolution_m,
                                            double origin_x_m, double origin_y_m, Cell fill) {
  if (auto error =
          detail::check_grid_size("OccupancyGrid", width_cells, height_cells, resolution_m)) {
    return *std::move(error);
  }
  if (!std::isfinite(origin_x_m)) {
    return invalid_argument("OccupancyGrid: origin_x_m must be finite (got " +
                            detail::format_number(origin_x_m) + ")");
  }
  if (!std::isfinite(origin_y_m)) {
    return invalid_argument("OccupancyGrid: origin_y_m must be finite (got " +
                            detail::format_number(origin_y_m) + ")");
  }
  const auto fill_value = static_cast<unsigned>(fill);
  if (fill_value > static_cast<unsigned>(Cell::kUnknown)) {
    return invalid_argument("OccupancyGrid: fill must be kFree, kObstacle or kUnknown (got " +
                            std::to_string(fill_value) + ")");
  }
  return OccupancyGrid(width_cells, height_cells, resolution_m, origin_x_m, origin_y_m, fill);
}

void OccupancyGrid::set(int cx, int cy, Cell value) noexcept {
  Cell& cell = cells_[index(cx, cy)];
  if (cell != value) {
    cell = value;
    ++revision_;
  }
}

bool OccupancyGrid::to_cell(double x_m, double y_m, int& cx, int& cy) const noexcept {
  const double u = (x_m - origin_x_) * inv_resolution_;
  const double v = (y_m - origin_y_) * inv_resolution_;
  // The negated form also rejects NaN.
  if (!(u >= 0.0 && v >= 0.0 && u < width_ && v < height_)) {
    return false;
  }
  cx = static_cast<int>(u);
  cy = static_cast<int>(v);
  // u < width_ can round to exactly width_ after the cast only in theory; keep it safe.
  cx = std::min(cx, width_ - 1);
  cy = std::min(cy, height_ - 1);
  return true;
}

void OccupancyGrid::fill_rect(double x0_m, double y0_m, double x1_m, double y1_m,
                              Cell value) noexcept {
  const double xlo = std::min(x0_m, x1_m);
  const double xhi = std::max(x0_m, x1_m);
  const double ylo = std::min(y0_m, y1_m);
  const double yhi = std::max(y0_m, y1_m);
  if (!(std::isfinite(xlo) && std::isfinite(xhi) && std::isfinite(ylo) && std::isfinite(yhi))) {
    return;
  }
  // Candidate ranges one cell wider than needed, clipped; the centre test below is the rule.
  const auto first = [&](double lo, double origin, int size) {
    const double c = std::floor((lo - origin) * inv_resolution_ - 0.5);
    return c < 0.0 ? 0 : (c >= size ? size : static_cast<int>(c));
  };
  const auto last = [&](double hi, double origin, int size) {
    const double c = std::ceil((hi - origin) * inv_resolution_);
    return c < 0.0 ? -1 : (c >= size ? size - 1 : static_cast<int>(c));
  };
  const int cx0 = first(xlo, origin_x_, width_);
  const int cx1 = last(xhi, origin_x_, width_);
  const int cy0 = first(ylo, origin_y_, height_);
  const int cy1 = last(yhi, origin_y_, height_);
  bool changed = false;
  for (int cy = cy0; cy <= cy1; ++cy) {
    const double yc = cell_center_y(cy);
    if (yc < ylo || yc > yhi) {
      continue;
    }
    for (int cx = cx0; cx <= cx1; ++cx) {
      const double xc = cell_center_x(cx);
      if (xc < xlo || xc > xhi) {
        continue;
      }
      Cell& cell = cells_[index(cx, cy)];
      changed = changed || cell != value;
      cell = value;
    }
  }
  if (changed) {
    ++revision_;
  }
}

}  // namespace grip
