#include "grip/world/distance_field.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "validation.hpp"

namespace grip {

namespace {

constexpr std::uint32_t kInf = DistanceField::kUnreachable;

// Dial's algorithm over the padded grid, resumable: `queue` holds the cells labelled and not yet
// settled (the seeds at first, linked into bucket 0) and where the scan of the buckets stands.
// Settles every cell of cost <= cost_limit, calling on_settle(p) for each in nondecreasing cost;
// returns true when the queue ran empty (every label final), false when it stopped at the limit
// (the next cell to settle costs more; labels above the limit are upper bounds).
// Steps cost `orthogonal` and `diagonal`; the buckets are a power of two > diagonal, `bucket_mask`
// one less.
template <typename OnSettle>
bool run_dial(const std::uint8_t* traversable, std::uint32_t padded_width, std::uint32_t orthogonal,
              std::uint32_t diagonal, std::uint32_t bucket_mask, std::uint32_t* cost_of,
              std::uint32_t* next, std::uint32_t* prev, std::uint32_t* head,
              detail::DialQueue& queue, std::uint32_t cost_limit, OnSettle&& on_settle) noexcept {
  constexpr std::uint32_t kNil = DistanceField::kNoCell;
  const auto link = [&](std::uint32_t p, std::uint32_t bucket) {
    const std::uint32_t first = head[bucket];
    next[p] = first;
    prev[p] = kNil;
    if (first != kNil) {
      prev[first] = p;
    }
    head[bucket] = p;
  };
  const auto unlink = [&](std::uint32_t p, std::uint32_t bucket) {
    if (prev[p] != kNil) {
      next[prev[p]] = next[p];
    } else {
      head[bucket] = next[p];
    }
    if (next[p] != kNil) {
      prev[next[p]] = prev[p];
    }
  };
  std::uint32_t queued = queue.queued;
  const auto relax = [&](std::uint32_t p, std::uint32_t cost) {
    const std::uint32_t old = cost_of[p];
    if (cost < old) {
      if (old != kInf) {
        unlink(p, old & bucket_mask);
      } else {
        ++queued;
      }
      cost_of[p] = cost;
      link(p, cost & bucket_mask);
    }
  };

  const std::uint32_t w = padded_width;
  std::uint32_t cost = queue.cost;
  std::uint32_t bucket = queue.bucket;
  bool stopped = false;
  while (queued > 0) {
    while (head[bucket] == kNil) {
      ++cost;
      bucket = (bucket + 1) & bucket_mask;
    }
    if (cost > cost_limit) {
      stopped = true;
      break;
    }
    const std::uint32_t u = head[bucket];
    head[bucket] = next[u];
    if (next[u] != kNil) {
      prev[next[u]] = kNil;
    }
    --queued;
    on_settle(u);
    const std::uint32_t straight = cost + orthogonal;
    const std::uint32_t slanted = cost + diagonal;
    const bool east = traversable[u + 1] != 0;
    const bool west = traversable[u - 1] != 0;
    const bool north = traversable[u + w] != 0;
    const bool south = traversable[u - w] != 0;
    if (east) relax(u + 1, straight);
    if (west) relax(u - 1, straight);
    if (north) relax(u + w, straight);
    if (south) relax(u - w, straight);
    // Diagonals only between two traversable orthogonal neighbours: no corner cutting.
    if (north && east && traversable[u + w + 1] != 0) relax(u + w + 1, slanted);
    if (north && west && traversable[u + w - 1] != 0) relax(u + w - 1, slanted);
    if (south && east && traversable[u - w + 1] != 0) relax(u - w + 1, slanted);
    if (south && west && traversable[u - w - 1] != 0) relax(u - w - 1, slanted);
  }
  queue.queued = queued;
  queue.cost = cost;
  queue.bucket = bucket;
  return !stopped;
}

}  // namespace

DistanceField::DistanceField(int width_cells, int height_cells, double resolution_m, int block)
    : width_(width_cells),
      height_(height_cells),
      resolution_(resolution_m),
      inv_resolution_(1.0 / resolution_m),
      metres_per_unit_(resolution_m / kCostUnitsPerCell),
      block_(block),
      orthogonal_cost_(kOrthogonalCost * static_cast<std::uint32_t>(block)),
      diagonal_cost_(kDiagonalCost * static_cast<std::uint32_t>(block)),
      padded_width_(static_cast<std::uint32_t>((width_cells + block - 1) / block) + 2) {
  const std::size_t padded_cells =
      padded_width_ * (static_cast<std::size_t>((height_cells + block - 1) / block) + 2);
  traversable_.assign(padded_cells, 0);
  field_.cost.assign(padded_cells, kInf);
  field_.next.assign(padded_cells, kNil);
  field_.prev.assign(padded_cells, kNil);
  field_.head.assign(std::bit_ceil(diagonal_cost_ + 1), kNil);
}

Result<DistanceField> DistanceField::create(int width_cells, int height_cells, double resolution_m,
                                            int block) {
  if (auto error =
          detail::check_grid_size("DistanceField", width_cells, height_cells, resolution_m)) {
    return *std::move(error);
  }
  if (block < 1 || block > kMaxBlock) {
    return invalid_argument("DistanceField: block must be in [1, " + std::to_string(kMaxBlock) +
                            "] (got " + std::to_string(block) + ")");
  }
  return DistanceField(width_cells, height_cells, resolution_m, block);
}

int DistanceField::block_for(double resolution_m, double max_cell_m, double inflation_m) noexcept {
  const double side_m = std::min(max_cell_m, 0.5 * inflation_m);
  if (!(side_m > 0.0 && resolution_m > 0.0)) return 1;
  // A hair of tolerance: 0.1 m on a 0.05 m grid is two cells, whatever the rounding.
  const double cells = std::floor(side_m / resolution_m * (1.0 + 1e-9));
  return cells >= 2.0 ? static_cast<int>(std::min(cells, static_cast<double>(kMaxBlock))) : 1;
}

std::uint32_t DistanceField::unpadded(std::uint32_t padded_index) const noexcept {
  const auto b = static_cast<std::uint32_t>(block_);
  const std::uint32_t x = std::min((padded_index % padded_width_ - 1) * b + b / 2,
                                   static_cast<std::uint32_t>(width_) - 1);
  const std::uint32_t y = std::min((padded_index / padded_width_ - 1) * b + b / 2,
                                   static_cast<std::uint32_t>(height_) - 1);
  return y * static_cast<std::uint32_t>(width_) + x;
}

void DistanceField::build_mask(const OccupancyGrid& grid, const ClearanceMap* clearance,
                               double inflation_m, const CellBox& window) noexcept {
  GRIP_ASSERT(grid.width() == width_ && grid.height() == height_ &&
              grid.resolution() == resolution_);
  GRIP_ASSERT(std::isfinite(inflation_m) && inflation_m >= 0.0);
  const ClearCells traversable = clearance != nullptr ? clearance->clear_cells(grid, inflation_m)
                                                      : ClearCells::free_cells(grid);
  // A clearance map updated in windows is exact only up to its bound (ClearanceMap::update).
  GRIP_ASSERT(clearance == nullptr ||
              traversable.min_squared_clearance <= clearance->exact_up_to());
  const auto gw = static_cast<std::uint32_t>(width_);
  // The blocks that hold a cell of the window, each decided from all of its cells.
  const int b = block_;
  const CellBox box{std::max(window.x0, 0) / b, std::max(window.y0, 0) / b,
                    std::min(window.x1, width_ - 1) / b, std::min(window.y1, height_ - 1) / b};
  for (int row = box.y0; row <= box.y1 && box.x0 <= box.x1; ++row) {
    std::uint8_t* out = traversable_.data() + static_cast<std::size_t>(row + 1) * padded_width_ + 1;
    const int y_end = std::min((row + 1) * b, height_);
    for (int column = box.x0; column <= box.x1; ++column) {
      const int x_end = std::min((column + 1) * b, width_);
      bool any = false;
      for (int y = row * b; y < y_end && !any; ++y) {
        const std::uint32_t first = static_cast<std::uint32_t>(y) * gw;
        for (int x = column * b; x < x_end && !any; ++x) {
          any = traversable.contains(first + static_cast<std::uint32_t>(x));
        }
      }
      out[column] = any ? 1 : 0;
    }
  }
  mask_source_ = &grid;
  origin_x_m_ = grid.origin_x();
  origin_y_m_ = grid.origin_y();
  inflation_m_ = inflation_m;
  source_revision_ = grid.revision();
}

void DistanceField::prepare(const OccupancyGrid& grid) noexcept {
  build_mask(grid, nullptr, 0.0, whole());
}

void DistanceField::prepare(const OccupancyGrid& grid, const ClearanceMap& clearance,
                            double inflation_m) noexcept {
  GRIP_ASSERT(clearance.width() == width_ && clearance.height() == height_ &&
              clearance.resolution() == resolution_);
  if (inflation_m > 0.0) {
    GRIP_ASSERT(clearance.computed() && clearance.source_revision() == grid.revision());
    build_mask(grid, &clearance, inflation_m, whole());
  } else {
    build_mask(grid, nullptr, inflation_m, whole());
  }
}

void DistanceField::prepare(const OccupancyGrid& grid, const ClearanceMap& clearance,
                            double inflation_m, const CellBox& window) noexcept {
  GRIP_ASSERT(clearance.width() == width_ && clearance.height() == height_ &&
              clearance.resolution() == resolution_);
  GRIP_ASSERT(mask_source_ == &grid && inflation_m == inflation_m_);
  GRIP_ASSERT(inflation_m == 0.0 ||
              (clearance.computed() && clearance.source_revision() == grid.revision()));
  build_mask(grid, inflation_m > 0.0 ? &clearance : nullptr, inflation_m, window);
}

std::uint32_t DistanceField::compute(const OccupancyGrid& grid,
                                     std::span<const std::uint32_t> target_cells) noexcept {
  prepare(grid);
  return propagate(target_cells);
}

std::uint32_t DistanceField::compute(const OccupancyGrid& grid, const ClearanceMap& clearance,
                                     std::span<const std::uint32_t> target_cells,
                                     double inflation_m) noexcept {
  prepare(grid, clearance, inflation_m);
  return propagate(target_cells);
}

std::uint32_t DistanceField::propagate(std::span<const std::uint32_t> target_cells) noexcept {
  start(target_cells);
  settle(kUnreachable);
  return settled_;
}

std::uint32_t DistanceField::propagate_within(std::span<const std::uint32_t> target_cells,
                                              std::uint32_t cost_limit) noexcept {
  GRIP_ASSERT(cost_limit < kUnreachable);
  start(target_cells);
  if (!settle(cost_limit)) read_limit_ = cost_limit;
  return settled_;
}

void DistanceField::start(std::span<const std::uint32_t> target_cells) noexcept {
  // Only what the last wavefront labelled is not kInf: the cells it settled, and those it left
  // queued beside them. The box of the settled cells grown by one bounds them (inside the
  // padding ring: a real cell's neighbours). A box, not an index range: on a wide map the rows a
  // wavefront spans hold many times the cells it reached.
  if (reached_.x0 <= reached_.x1) {
    for (std::uint32_t row = reached_.y0 - 1; row <= reached_.y1 + 1; ++row) {
      const auto first = field_.cost.begin() + row * padded_width_;
      std::fill(first + reached_.x0 - 1, first + reached_.x1 + 2, kInf);
    }
  }
  reached_ = ReachedBox{};
  settled_ = 0;
  read_limit_ = kUnreachable;
  std::fill(field_.head.begin(), field_.head.end(), kNil);
  field_.queue = detail::DialQueue{};
  for (const std::uint32_t target : target_cells) {
    GRIP_ASSERT(target < cell_count());
    const std::uint32_t p = padded(target);
    if (field_.cost[p] != 0) {
      field_.cost[p] = 0;
      field_.next[p] = field_.head[0];
      field_.prev[p] = kNil;
      if (field_.head[0] != kNil) {
        field_.prev[field_.head[0]] = p;
      }
      field_.head[0] = p;
      ++field_.queue.queued;
      note_reached(p);
    }
  }
  // The seeds' labels (0) are final at once; with none, everything is.
  settled_limit_ = field_.queue.queued == 0 ? kUnreachable : 0;
}

bool DistanceField::settle(std::uint32_t cost_limit) noexcept {
  if (settled_limit_ == kUnreachable) return true;
  const bool complete = run_dial(
      traversable_.data(), padded_width_, orthogonal_cost_, diagonal_cost_,
      static_cast<std::uint32_t>(field_.head.size()) - 1, field_.cost.data(), field_.next.data(),
      field_.prev.data(), field_.head.data(), field_.queue, cost_limit, [&](std::uint32_t p) {
        ++settled_;
        note_reached(p);
      });
  settled_limit_ = complete ? kUnreachable : std::max(settled_limit_, cost_limit);
  return complete;
}

void DistanceField::note_reached(std::uint32_t padded_index) noexcept {
  const std::uint32_t row = padded_index / padded_width_;
  const std::uint32_t column = padded_index - row * padded_width_;
  reached_.x0 = std::min(reached_.x0, column);
  reached_.x1 = std::max(reached_.x1, column);
  reached_.y0 = std::min(reached_.y0, row);
  reached_.y1 = std::max(reached_.y1, row);
}

double DistanceField::at(std::uint32_t cell_index) const noexcept {
  const std::uint32_t cost = cost_at(cell_index);
  return cost == kInf ? std::numeric_limits<double>::infinity() : cost * metres_per_unit_;
}

bool DistanceField::traversable(std::uint32_t cell_index) const noexcept {
  GRIP_ASSERT(cell_index < cell_count());
  return traversable_[padded(cell_index)] != 0;
}

std::uint32_t DistanceField::cell_at(double x_m, double y_m) const noexcept {
  const double u = (x_m - origin_x_m_) * inv_resolution_;
  const double v = (y_m - origin_y_m_) * inv_resolution_;
  if (!(u >= 0.0 && v >= 0.0 && u < width_ && v < height_)) return kNoCell;
  return static_cast<std::uint32_t>(v) * static_cast<std::uint32_t>(width_) +
         static_cast<std::uint32_t>(u);
}

double DistanceField::distance_m(double x_m, double y_m) const noexcept {
  const double u = (x_m - origin_x_m_) * inv_resolution_;
  const double v = (y_m - origin_y_m_) * inv_resolution_;
  if (!(u >= 0.0 && v >= 0.0 && u < width_ && v < height_)) {
    return std::numeric_limits<double>::infinity();
  }
  const std::uint32_t cost =
      read(padded(static_cast<std::uint32_t>(u), static_cast<std::uint32_t>(v)));
  return cost == kInf ? std::numeric_limits<double>::infinity() : cost * metres_per_unit_;
}

std::uint32_t DistanceField::descend(std::uint32_t cell_index,
                                     std::uint32_t cost_drop) const noexcept {
  const std::uint32_t from = padded(cell_index);
  std::uint32_t p = from;
  const std::uint32_t start = read(p);
  if (start == kInf) return cell_index;
  const auto w = static_cast<std::int64_t>(padded_width_);
  const std::int64_t offsets[8] = {-1, 1, -w, w, -w - 1, -w + 1, w - 1, w + 1};
  const std::uint32_t steps[8] = {orthogonal_cost_, orthogonal_cost_, orthogonal_cost_,
                                  orthogonal_cost_, diagonal_cost_,   diagonal_cost_,
                                  diagonal_cost_,   diagonal_cost_};
  // Every step lowers the cost (a neighbour on a shortest path costs the step less), and the
  // padding ring is never reached, so no bounds test is needed.
  for (std::uint32_t here = start; here != 0 && start - here < cost_drop; here = read(p)) {
    std::uint32_t best = p;
    std::uint64_t best_via = here;
    for (int k = 0; k < 8; ++k) {
      const auto n = static_cast<std::uint32_t>(static_cast<std::int64_t>(p) + offsets[k]);
      const std::uint32_t cost = read(n);
      const std::uint64_t via = static_cast<std::uint64_t>(cost) + steps[k];
      if (cost < here && via <= best_via) {
        best_via = via;
        best = n;
      }
    }
    if (best == p) break;
    p = best;
  }
  return p == from ? cell_index : unpadded(p);
}

}  // namespace grip
