#include "grip/world/clearance_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "validation.hpp"

namespace grip {

namespace {

// update()'s scratch holds a window of at least this many cells, or an eighth of the map: a
// sensor sweep's change grown by the clearance the users ask for fits many times over, and a
// larger change costs about as much as compute(), which update() then does instead. A scratch
// the size of the map would double what every clearance map costs per cell.
constexpr std::size_t kMinWindowCells = std::size_t{1} << 20;

// 1-D squared distance transform of the sampled function f over 0..n-1 (Felzenszwalb &
// Huttenlocher, "Distance Transforms of Sampled Functions", 2012): d[q] = min_p (q - p)^2 + f[p].
// All f are finite integers here; the parabola intersections are exact rationals whose
// comparison with the integers q is decided exactly in double (correctly rounded division).
void transform_1d(const std::int64_t* f, int n, std::int64_t* d, int* v, double* z) noexcept {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = 1; q < n; ++q) {
    double s = 0.0;
    while (true) {
      const int p = v[k];
      const std::int64_t numerator = (f[q] + std::int64_t{q} * q) - (f[p] + std::int64_t{p} * p);
      s = static_cast<double>(numerator) / static_cast<double>(2 * (q - p));
      if (s > z[k]) {
        break;
      }
      --k;  // z[0] = -inf ends this loop with k >= 0
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) {
      ++k;
    }
    const std::int64_t offset = q - v[k];
    d[q] = offset * offset + f[v[k]];
  }
}

}  // namespace

ClearanceMap::ClearanceMap(int width_cells, int height_cells, double resolution_m)
    : width_(width_cells),
      height_(height_cells),
      resolution_(resolution_m),
      half_diagonal_m_(resolution_m * std::sqrt(0.5)),
      d2_(static_cast<std::size_t>(width_cells) * static_cast<std::size_t>(height_cells), 0),
      columns_(std::min(d2_.size(), std::max(kMinWindowCells, d2_.size() / 8)), 0) {
  const auto longest = static_cast<std::size_t>(std::max(width_cells, height_cells)) + 2;
  f_.resize(longest);
  d_.resize(longest);
  v_.resize(longest);
  z_.resize(longest + 1);
}

Result<ClearanceMap> ClearanceMap::create(int width_cells, int height_cells, double resolution_m) {
  if (auto error =
          detail::check_grid_size("ClearanceMap", width_cells, height_cells, resolution_m)) {
    return *std::move(error);
  }
  return ClearanceMap(width_cells, height_cells, resolution_m);
}

Result<ClearanceMap> ClearanceMap::create_for(const OccupancyGrid& grid) {
  auto map = create(grid.width(), grid.height(), grid.resolution());
  if (map.ok()) {
    map->compute(grid);
  }
  return map;
}

void ClearanceMap::compute(const OccupancyGrid& grid) noexcept {
  GRIP_ASSERT(grid.width() == width_ && grid.height() == height_ &&
              grid.resolution() == resolution_);
  const auto w = static_cast<std::size_t>(width_);
  const auto h = static_cast<std::size_t>(height_);
  const std::span<const Cell> cells = grid.cells();

  // Pass 1, per column: distance in cells to the nearest non-free cell of the same column, the
  // rows -1 and height (outside) counting as non-free. Stored in d2_ for now.
  for (std::size_t x = 0; x < w; ++x) {
    std::int64_t last = -1;
    for (std::size_t y = 0; y < h; ++y) {
      const std::size_t i = y * w + x;
      if (cells[i] != Cell::kFree) {
        last = static_cast<std::int64_t>(y);
      }
      d2_[i] = static_cast<std::uint32_t>(static_cast<std::int64_t>(y) - last);
    }
    last = static_cast<std::int64_t>(h);
    for (std::size_t y = h; y-- > 0;) {
      const std::size_t i = y * w + x;
      if (cells[i] != Cell::kFree) {
        last = static_cast<std::int64_t>(y);
      }
      const auto below = static_cast<std::uint32_t>(last - static_cast<std::int64_t>(y));
      d2_[i] = std::min(d2_[i], below);
    }
  }

  // Pass 2, per row: squared Euclidean distance over positions -1..width (the outside columns
  // -1 and width are non-free in every row, so f = 0 there).
  const int n = width_ + 2;
  for (std::size_t y = 0; y < h; ++y) {
    std::uint32_t* row = d2_.data() + y * w;
    f_[0] = 0;
    for (std::size_t x = 0; x < w; ++x) {
      const auto g = static_cast<std::int64_t>(row[x]);
      f_[x + 1] = g * g;
    }
    f_[w + 1] = 0;
    transform_1d(f_.data(), n, d_.data(), v_.data(), z_.data());
    for (std::size_t x = 0; x < w; ++x) {
      row[x] = static_cast<std::uint32_t>(d_[x + 1]);
    }
  }
  source_revision_ = grid.revision();
  computed_ = true;
  exact_up_to_d2_ = std::numeric_limits<std::uint32_t>::max();
}

CellBox ClearanceMap::update(const OccupancyGrid& grid, const CellBox& changed,
                             std::uint32_t exact_up_to_d2) noexcept {
  GRIP_ASSERT(grid.width() == width_ && grid.height() == height_ &&
              grid.resolution() == resolution_);
  GRIP_ASSERT(computed_);
  exact_up_to_d2_ = std::min(exact_up_to_d2_, exact_up_to_d2);
  source_revision_ = grid.revision();
  if (changed.empty()) return CellBox{};
  // reach^2 > exact_up_to_d2. The values that can change lie within reach of `changed` (the
  // window W): a cell farther away keeps its nearest non-free cell if that is within reach, and
  // stays beyond the bound otherwise. The nearest non-free cell of a W cell, when within reach,
  // lies in W grown by reach (the source S); the edge of S inside the grid is not an obstacle,
  // so a W cell with nothing in reach gets a value at least its exact one, beyond the bound.
  const auto reach = static_cast<int>(std::sqrt(static_cast<double>(exact_up_to_d2))) + 1;
  const auto clip = [&](const CellBox& b, int grow) {
    return CellBox{std::max(b.x0 - grow, 0), std::max(b.y0 - grow, 0),
                   std::min(b.x1 + grow, width_ - 1), std::min(b.y1 + grow, height_ - 1)};
  };
  const CellBox window = clip(changed, reach);
  const CellBox source = clip(window, reach);
  if (static_cast<std::size_t>(source.x1 - source.x0 + 1) *
          static_cast<std::size_t>(window.y1 - window.y0 + 1) >
      columns_.size()) {
    compute(grid);
    return CellBox{0, 0, width_ - 1, height_ - 1};
  }
  // Distances that no cell of S can reach: no obstacle in that direction within S.
  constexpr std::int64_t kFar = std::int64_t{1} << 24;
  const std::span<const Cell> cells = grid.cells();
  const auto w = static_cast<std::size_t>(width_);
  const int source_w = source.x1 - source.x0 + 1;
  // Pass 1's result for cell (x, y) of W's rows and S's columns.
  const auto column_distance = [&](int x, int y) -> std::uint32_t& {
    return columns_[static_cast<std::size_t>(y - window.y0) * static_cast<std::size_t>(source_w) +
                    static_cast<std::size_t>(x - source.x0)];
  };

  // Pass 1, per column of S: distance to the nearest non-free cell of the column within S (or
  // the grid's outside rows where S reaches them), kept for the rows of W.
  for (int x = source.x0; x <= source.x1; ++x) {
    std::int64_t last = source.y0 == 0 ? -1 : -kFar;
    for (int y = source.y0; y <= source.y1; ++y) {
      if (cells[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] != Cell::kFree) {
        last = y;
      }
      if (y >= window.y0 && y <= window.y1) {
        column_distance(x, y) = static_cast<std::uint32_t>(std::min<std::int64_t>(y - last, kFar));
      }
    }
    last = source.y1 == height_ - 1 ? height_ : source.y1 + kFar;
    for (int y = source.y1; y >= source.y0; --y) {
      if (cells[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] != Cell::kFree) {
        last = y;
      }
      if (y >= window.y0 && y <= window.y1) {
        std::uint32_t& g = column_distance(x, y);
        g = std::min(g, static_cast<std::uint32_t>(std::min<std::int64_t>(last - y, kFar)));
      }
    }
  }

  // Pass 2, per row of W over the columns of S, with the grid's outside columns where S reaches
  // them (f = 0 there); only W's cells are written.
  const bool left_border = source.x0 == 0;
  const bool right_border = source.x1 == width_ - 1;
  const int first = left_border ? 1 : 0;  // f index of column source.x0
  const int n = source_w + (left_border ? 1 : 0) + (right_border ? 1 : 0);
  for (int y = window.y0; y <= window.y1; ++y) {
    if (left_border) f_[0] = 0;
    for (int i = 0; i < source_w; ++i) {
      const auto gi = static_cast<std::int64_t>(column_distance(source.x0 + i, y));
      f_[static_cast<std::size_t>(first + i)] = gi * gi;
    }
    if (right_border) f_[static_cast<std::size_t>(n - 1)] = 0;
    transform_1d(f_.data(), n, d_.data(), v_.data(), z_.data());
    std::uint32_t* row = d2_.data() + static_cast<std::size_t>(y) * w;
    for (int x = window.x0; x <= window.x1; ++x) {
      const std::int64_t value = d_[static_cast<std::size_t>(first + x - source.x0)];
      row[x] = static_cast<std::uint32_t>(
          std::min<std::int64_t>(value, std::numeric_limits<std::uint32_t>::max()));
    }
  }
  return window;
}

double ClearanceMap::clearance_m(std::uint32_t index) const noexcept {
  const std::uint32_t d2 = squared_cells(index);
  if (d2 == 0) {
    return 0.0;
  }
  return std::sqrt(static_cast<double>(d2)) * resolution_ - half_diagonal_m_;
}

std::uint32_t ClearanceMap::squared_cells_at_least(double min_clearance_m) const noexcept {
  if (!(min_clearance_m > 0.0)) {
    return 0;
  }
  // clearance_m >= c  <=>  sqrt(d2) * res >= c + hd  <=>  d2 >= ((c + hd) / res)^2.
  const double q = (min_clearance_m + half_diagonal_m_) / resolution_;
  const double q2 = q * q * (1.0 + 1e-12);
  constexpr double kMax = static_cast<double>(std::numeric_limits<std::uint32_t>::max());
  if (!(q2 < kMax)) {
    return std::numeric_limits<std::uint32_t>::max();
  }
  return static_cast<std::uint32_t>(std::ceil(q2));
}

}  // namespace grip
