#include "grip/exploration/frontier.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>

#include "../world/validation.hpp"
#include "grip/common/enum_names.hpp"
#include "grip/common/saturating_cast.hpp"
#include "sight_line.hpp"

namespace grip {

namespace {

constexpr std::array<NamedValue<ExplorationStatus>, 3> kExplorationStatusNames{{
    {ExplorationStatus::kTarget, "target"},
    {ExplorationStatus::kComplete, "complete"},
    {ExplorationStatus::kRobotOutsideGrid, "robot-outside-grid"},
}};

// label_ of a frontier cell not yet grouped.
constexpr std::uint32_t kUnlabelled = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t kUnreachable = DistanceField::kUnreachable;

// The next bound of a wavefront run in steps: twice the last, saturating at "to the end".
std::uint32_t next_limit(std::uint32_t limit) {
  return limit > kUnreachable / 2 ? kUnreachable : 2 * limit;
}

// The approach window's half side [cells], and the cells of a square of that half side.
int approach_reach(const FrontierConfig& config, double resolution_m) {
  return floor_to_cell(config.approach_range_m / resolution_m, 0, OccupancyGrid::kMaxSideCells);
}
std::size_t square_cells(int reach) {
  const auto side = static_cast<std::size_t>(2 * reach + 1);
  return side * side;
}

}  // namespace

std::string_view exploration_status_name(ExplorationStatus s) noexcept {
  return name_in(kExplorationStatusNames, s);
}

Status FrontierConfig::validate(double resolution_m) const {
  const auto bad = [](const char* name, double value, const std::string& rule) -> Status {
    return invalid_argument(std::string("frontier: ") + name + " must be " + rule + " (got " +
                            detail::format_number(value) + ")");
  };
  if (!(std::isfinite(clearance_m) && clearance_m >= 0.0)) {
    return bad("clearance_m", clearance_m, "finite and >= 0");
  }
  if (!(std::isfinite(rho_cell_m) && rho_cell_m >= 0.0)) {
    return bad("rho_cell_m", rho_cell_m, "finite and >= 0");
  }
  const double min_range = clearance_m + resolution_m * std::sqrt(2.0);
  if (!(std::isfinite(approach_range_m) && approach_range_m > min_range)) {
    return bad("approach_range_m", approach_range_m,
               "finite and > clearance_m + a cell diagonal = " + detail::format_number(min_range));
  }
  if (!(std::isfinite(size_weight) && size_weight >= 0.0)) {
    return bad("size_weight", size_weight, "finite and >= 0");
  }
  if (!(std::isfinite(size_cap_m) && size_cap_m >= 0.0)) {
    return bad("size_cap_m", size_cap_m, "finite and >= 0");
  }
  if (!(std::isfinite(give_up_radius_m) && give_up_radius_m >= 0.0)) {
    return bad("give_up_radius_m", give_up_radius_m, "finite and >= 0");
  }
  if (!(std::isfinite(search_step_m) && search_step_m >= 0.0)) {
    return bad("search_step_m", search_step_m, "finite and >= 0");
  }
  if (min_group_cells == 0) return bad("min_group_cells", 0.0, ">= 1");
  return Ok{};
}

Result<FrontierMap> FrontierMap::create(int width_cells, int height_cells, double resolution_m,
                                        const FrontierConfig& config) {
  if (auto error =
          detail::check_grid_size("FrontierMap", width_cells, height_cells, resolution_m)) {
    return *std::move(error);
  }
  if (auto s = config.validate(resolution_m); !s) return s.error();
  auto field = DistanceField::create(
      width_cells, height_cells, resolution_m,
      DistanceField::block_for(resolution_m, config.rho_cell_m, config.clearance_m));
  if (!field) return field.error();
  return FrontierMap(width_cells, height_cells, resolution_m, config, std::move(field).value());
}

FrontierMap::FrontierMap(int width_cells, int height_cells, double resolution_m,
                         const FrontierConfig& config, DistanceField field)
    : width_(width_cells),
      height_(height_cells),
      resolution_(resolution_m),
      config_(config),
      field_(std::move(field)),
      frontier_bits_(field_.cell_count() / 64 + 1, 0),
      label_(field_.cell_count()),
      cells_(field_.cell_count()),
      // Frontier cells of different groups are not 8-adjacent: at most one group per 2x2 block.
      groups_(static_cast<std::size_t>((width_cells + 1) / 2) *
              static_cast<std::size_t>((height_cells + 1) / 2)),
      // The robot's cell and the chassis cells of its approach window (a square bounds it).
      seeds_(square_cells(approach_reach(config, resolution_m)) + 1),
      approach_(field_.cell_count()),
      stamp_(field_.cell_count()),
      given_up_(field_.cell_count()) {
  reach_ = approach_reach(config, resolution_m);
  const double reach_cells = config.approach_range_m / resolution_m;
  window_costs_.assign(square_cells(reach_), kUnreachable);
  for (int dy = -reach_; dy <= reach_; ++dy) {
    for (int dx = -reach_; dx <= reach_; ++dx) {
      const double d = std::hypot(dx, dy);
      if (d > reach_cells) continue;
      window_costs_[window_index(dx, dy)] =
          static_cast<std::uint32_t>(std::lround(d * DistanceField::kCostUnitsPerCell));
    }
  }
  for (std::uint32_t c = 0; c < field_.cell_count(); ++c) {
    GRIP_ASSERT(label_.push_back(kUnlabelled));
    GRIP_ASSERT(stamp_.push_back(0));
    GRIP_ASSERT(given_up_.push_back(0));
  }
}

std::span<const std::uint32_t> FrontierMap::group_cells(std::uint32_t group) const noexcept {
  GRIP_ASSERT(group < groups_.size());
  return cells_.span().subspan(groups_[group].first, groups_[group].size);
}

void FrontierMap::give_up(std::uint32_t group) noexcept {
  const auto reach =
      floor_to_cell(config_.give_up_radius_m / resolution_, 0, OccupancyGrid::kMaxSideCells);
  const auto reach2 = reach * reach;
  for (const std::uint32_t c : group_cells(group)) {
    const int cx = static_cast<int>(c % static_cast<std::uint32_t>(width_));
    const int cy = static_cast<int>(c / static_cast<std::uint32_t>(width_));
    for (int y = std::max(0, cy - reach); y <= std::min(height_ - 1, cy + reach); ++y) {
      for (int x = std::max(0, cx - reach); x <= std::min(width_ - 1, cx + reach); ++x) {
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > reach2) continue;
        given_up_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(x)] = 1;
      }
    }
  }
}

void FrontierMap::forgive_all() noexcept {
  std::fill(given_up_.begin(), given_up_.end(), std::uint8_t{0});
}

std::span<const std::uint32_t> FrontierMap::target_cells() const noexcept {
  return target_ == kNoGroup ? std::span<const std::uint32_t>{} : group_cells(target_);
}

ExplorationStatus FrontierMap::update(const OccupancyGrid& grid, const ClearanceMap& clearance,
                                      double robot_x_m, double robot_y_m,
                                      const KinematicReachability& reached) noexcept {
  return update(grid, clearance, robot_x_m, robot_y_m, nullptr, reached);
}

ExplorationStatus FrontierMap::update(const OccupancyGrid& grid, const ClearanceMap& clearance,
                                      double robot_x_m, double robot_y_m, const MapChange& change,
                                      const KinematicReachability& reached) noexcept {
  return update(grid, clearance, robot_x_m, robot_y_m, &change, reached);
}

ExplorationStatus FrontierMap::update(const OccupancyGrid& grid, const ClearanceMap& clearance,
                                      double robot_x_m, double robot_y_m, const MapChange* change,
                                      const KinematicReachability& reached) noexcept {
  GRIP_ASSERT(grid.width() == width_ && grid.height() == height_ &&
              grid.resolution() == resolution_);
  // Without a full pass since the grid was last seen, a change cannot say what is stale.
  if (!detected_) change = nullptr;
  target_ = kNoGroup;
  approach_.clear();
  int robot_cx = 0;
  int robot_cy = 0;
  const CellBox whole{0, 0, width_ - 1, height_ - 1};
  if (change == nullptr) {
    detect(grid, whole);
    field_.prepare(grid, clearance, config_.clearance_m);
    detected_ = true;
  } else {
    // A cell's frontier status reads its 4 side neighbours.
    const CellBox& w = change->written;
    if (!w.empty()) detect(grid, CellBox{w.x0 - 1, w.y0 - 1, w.x1 + 1, w.y1 + 1});
    // Traversability reads freedom and clearance: both changed within the clearance window.
    const CellBox& window = change->clearance_window;
    if (!window.empty()) field_.prepare(grid, clearance, config_.clearance_m, window);
  }
  if (!grid.to_cell(robot_x_m, robot_y_m, robot_cx, robot_cy)) {
    groups_.clear();
    cells_.clear();
    status_ = ExplorationStatus::kRobotOutsideGrid;
    return status_;
  }
  const ChassisCells chassis = clearance.clear_cells(grid, config_.clearance_m);
  group(grid);
  seed_robot_field(grid, chassis, robot_cx, robot_cy);
  choose_target(grid, chassis, reached);
  if (target_ == kNoGroup) {
    status_ = ExplorationStatus::kComplete;
    return status_;
  }
  collect_approach_cells(grid, chassis, groups_[target_]);
  status_ = ExplorationStatus::kTarget;
  return status_;
}

std::uint32_t FrontierMap::search_step_cost() const noexcept {
  if (config_.search_step_m == 0.0) return kUnreachable;
  const double cells = config_.search_step_m / resolution_;
  return saturating_cast<std::uint32_t>(std::ceil(cells * DistanceField::kCostUnitsPerCell));
}

void FrontierMap::choose_target(const OccupancyGrid& grid, const ChassisCells& chassis,
                                const KinematicReachability& reached) noexcept {
  // The robot's wavefront in steps of search_step_m. After each, a group is measured when the
  // cells settled so far decide its rho (any cell not settled yet costs more than the step's
  // limit), and the choice is made once no group left unmeasured could beat the best score (its
  // rho, and so its score, exceeds the limit). The least score wins, ties the lowest index:
  // what one wavefront over all the known space would choose.
  field_.start(seeds_.span());
  given_up_groups_ = 0;
  unreachable_groups_ = 0;
  for (FrontierGroup& group : groups_) group = FrontierGroup{group.first, group.size};
  const std::uint32_t step = search_step_cost();
  const double metres_per_unit = resolution_ / DistanceField::kCostUnitsPerCell;
  const auto w = static_cast<std::uint32_t>(width_);
  const int robot_cx = static_cast<int>(seeds_[0] % w);
  const int robot_cy = static_cast<int>(seeds_[0] / w);
  double best = std::numeric_limits<double>::infinity();
  for (std::uint32_t limit = step;; limit = next_limit(limit)) {
    const bool complete = field_.settle(limit);
    const std::uint32_t settled = field_.settled_limit();
    for (std::uint32_t g = 0; g < groups_.size(); ++g) {
      FrontierGroup& group = groups_[g];
      // A group the wavefront cannot have come near yet is not measured: measuring reads the
      // whole approach window of each of its cells, and a group is pending for many steps.
      if (group.searched || rho_lower_bound(group, robot_cx, robot_cy) > settled ||
          !measure_group(grid, chassis, group, settled)) {
        continue;
      }
      group.searched = true;
      if (!group.reachable() || group.size < config_.min_group_cells) continue;
      const auto cells = group_cells(g);
      if (std::all_of(cells.begin(), cells.end(),
                      [&](std::uint32_t c) { return given_up_[c] != 0; })) {
        ++given_up_groups_;
        continue;
      }
      if (!reached.passed.empty() && !reached_by(grid, group, reached)) {
        ++unreachable_groups_;
        continue;
      }
      const double size_m = group.size * resolution_;
      group.score_m = group.rho_m + config_.size_weight * std::min(size_m, config_.size_cap_m);
      if (group.score_m < best || (group.score_m == best && g < target_)) {
        best = group.score_m;
        target_ = g;
      }
    }
    if (complete || best <= settled * metres_per_unit) return;
  }
}

void FrontierMap::detect(const OccupancyGrid& grid, const CellBox& box) noexcept {
  const std::span<const Cell> map = grid.cells();
  const auto w = static_cast<std::uint32_t>(width_);
  const auto h = static_cast<std::uint32_t>(height_);
  const auto unknown = [&](std::uint32_t i) { return map[i] == Cell::kUnknown; };
  const auto y0 = static_cast<std::uint32_t>(std::max(box.y0, 0));
  const auto y1 = static_cast<std::uint32_t>(std::min(box.y1, height_ - 1));
  const auto x0 = static_cast<std::uint32_t>(std::max(box.x0, 0));
  const auto x1 = static_cast<std::uint32_t>(std::min(box.x1, width_ - 1));
  for (std::uint32_t y = y0; y <= y1 && x0 <= x1; ++y) {
    bool any = false;
    for (std::uint32_t x = x0; x <= x1; ++x) {
      const std::uint32_t i = y * w + x;
      const bool frontier =
          map[i] == Cell::kFree && ((x > 0 && unknown(i - 1)) || (x + 1 < w && unknown(i + 1)) ||
                                    (y > 0 && unknown(i - w)) || (y + 1 < h && unknown(i + w)));
      const std::uint64_t bit = std::uint64_t{1} << (i & 63U);
      frontier_bits_[i >> 6] =
          frontier ? frontier_bits_[i >> 6] | bit : frontier_bits_[i >> 6] & ~bit;
      any = any || frontier;
    }
    if (any) frontier_rows_.add(CellBox{0, static_cast<int>(y), 0, static_cast<int>(y)});
  }
}

void FrontierMap::group(const OccupancyGrid& grid) noexcept {
  const auto w = static_cast<std::uint32_t>(width_);
  // Calls f(cell) for every frontier cell in index order: a word of bits at a time, over the
  // rows that have held one (a map grows around the vehicle: not the whole of a large one).
  const std::size_t first_word =
      frontier_rows_.empty() ? 0 : static_cast<std::size_t>(frontier_rows_.y0) * w / 64;
  const std::size_t end_word =
      frontier_rows_.empty() ? 0 : (static_cast<std::size_t>(frontier_rows_.y1) + 1) * w / 64 + 1;
  const auto for_each_frontier_cell = [&](auto&& f) {
    for (std::size_t word = first_word; word < end_word; ++word) {
      for (std::uint64_t bits = frontier_bits_[word]; bits != 0; bits &= bits - 1) {
        f(static_cast<std::uint32_t>(word * 64 + static_cast<std::size_t>(std::countr_zero(bits))));
      }
    }
  };
  for_each_frontier_cell([this](std::uint32_t c) { label_[c] = kUnlabelled; });
  // Flood fill, 8-connected, from each unlabelled cell in index order. cells_ is the queue:
  // what the fill appends from `first` on is the group.
  cells_.clear();
  groups_.clear();
  for_each_frontier_cell([&](std::uint32_t start) {
    if (label_[start] != kUnlabelled) return;
    const auto g = static_cast<std::uint32_t>(groups_.size());
    FrontierGroup group;
    group.first = static_cast<std::uint32_t>(cells_.size());
    label_[start] = g;
    GRIP_ASSERT(cells_.push_back(start));  // sized to the grid
    for (std::size_t head = group.first; head < cells_.size(); ++head) {
      const std::uint32_t c = cells_[head];
      const int cx = static_cast<int>(c % w);
      const int cy = static_cast<int>(c / w);
      for (int ny = cy - 1; ny <= cy + 1; ++ny) {
        for (int nx = cx - 1; nx <= cx + 1; ++nx) {
          if (!grid.in_bounds(nx, ny)) continue;
          const std::uint32_t nc = grid.index(nx, ny);
          if (!is_frontier(nc) || label_[nc] != kUnlabelled) continue;
          label_[nc] = g;
          GRIP_ASSERT(cells_.push_back(nc));
        }
      }
    }
    group.size = static_cast<std::uint32_t>(cells_.size()) - group.first;
    GRIP_ASSERT(groups_.push_back(group));  // sized for one group per 2x2 block
  });
}

template <typename Visit>
void FrontierMap::for_each_window_block(int cx, int cy, Visit&& visit) const noexcept {
  const int b = field_.block();
  const int x_lo = std::max(cx - reach_, 0);
  const int x_hi = std::min(cx + reach_, width_ - 1);
  const int y_lo = std::max(cy - reach_, 0);
  const int y_hi = std::min(cy + reach_, height_ - 1);
  for (int by0 = y_lo / b * b; by0 <= y_hi; by0 += b) {
    const int y0 = std::max(by0, y_lo);
    const int y1 = std::min(by0 + b - 1, y_hi);
    const int near_y = std::clamp(cy, y0, y1);
    for (int bx0 = x_lo / b * b; bx0 <= x_hi; bx0 += b) {
      const int x0 = std::max(bx0, x_lo);
      const int x1 = std::min(bx0 + b - 1, x_hi);
      const int near_x = std::clamp(cx, x0, x1);
      const std::uint32_t least = window_cost(near_x - cx, near_y - cy);
      if (least != kUnreachable) visit(x0, y0, x1, y1, near_x, near_y, least);
    }
  }
}

template <typename Wanted, typename Visit>
void FrontierMap::for_each_approach(const OccupancyGrid& grid, const ChassisCells& chassis, int cx,
                                    int cy, Wanted&& wanted, Visit&& visit) const noexcept {
  for_each_window_block(
      cx, cy, [&](int x0, int y0, int x1, int y1, int near_x, int near_y, std::uint32_t least) {
        const std::uint32_t reached = field_.cost_at(grid.index(near_x, near_y));
        if (reached == kUnreachable || !wanted(reached, least)) return;
        for (int y = y0; y <= y1; ++y) {
          for (int x = x0; x <= x1; ++x) {
            const std::uint32_t straight = window_cost(x - cx, y - cy);
            // On blocks, a reached block's cells are not all chassis cells.
            if (straight != kUnreachable && approach_start(chassis, grid.index(x, y))) {
              visit(x, y, reached + straight);
            }
          }
        }
      });
}

void FrontierMap::seed_robot_field(const OccupancyGrid& grid, const ChassisCells& chassis,
                                   int robot_cx, int robot_cy) noexcept {
  seeds_.clear();
  GRIP_ASSERT(seeds_.push_back(grid.index(robot_cx, robot_cy)));
  for (int y = std::max(robot_cy - reach_, 0); y <= std::min(robot_cy + reach_, height_ - 1); ++y) {
    for (int x = std::max(robot_cx - reach_, 0); x <= std::min(robot_cx + reach_, width_ - 1);
         ++x) {
      if ((x == robot_cx && y == robot_cy) ||
          window_cost(x - robot_cx, y - robot_cy) == kUnreachable) {
        continue;
      }
      const std::uint32_t c = grid.index(x, y);
      if (chassis.contains(c) && detail::in_sight(grid, robot_cx, robot_cy, x, y)) {
        GRIP_ASSERT(seeds_.push_back(c));  // at most the window's size, < cells
      }
    }
  }
}

std::uint32_t FrontierMap::rho_lower_bound(const FrontierGroup& group, int robot_cx,
                                           int robot_cy) const noexcept {
  // A path's cost is at least 70 per cell of straight-line length (a diagonal step's 99 is more
  // than 70 sqrt 2), and the window's cost rounds its straight line to the nearest unit.
  const auto w = static_cast<std::uint32_t>(width_);
  long nearest2 = std::numeric_limits<long>::max();
  for (std::uint32_t i = group.first; i < group.first + group.size; ++i) {
    const long dx = static_cast<long>(cells_[i] % w) - robot_cx;
    const long dy = static_cast<long>(cells_[i] / w) - robot_cy;
    nearest2 = std::min(nearest2, dx * dx + dy * dy);
  }
  const double straight = std::sqrt(static_cast<double>(nearest2)) -
                          config_.approach_range_m / resolution_ -  // a seed's offset at most
                          std::sqrt(2.0) * (field_.block() - 1);    // cells from their blocks'
  const double bound = straight * DistanceField::kCostUnitsPerCell - 2.0;
  return bound <= 0.0 ? 0U : saturating_cast<std::uint32_t>(std::floor(bound));
}

bool FrontierMap::measure_group(const OccupancyGrid& grid, const ChassisCells& chassis,
                                FrontierGroup& group, std::uint32_t settled) noexcept {
  // Per cell: the cheapest chassis cell in its window, in sight, among the cells settled.
  // Candidates that cannot improve on the best so far skip the sight test, the costly part, and
  // blocks none of whose cells could are not read.
  const auto w = static_cast<std::uint32_t>(width_);
  std::uint32_t best = kUnreachable;
  std::uint32_t nearest = FrontierGroup::kNoCell;
  for (std::uint32_t i = group.first; i < group.first + group.size; ++i) {
    const std::uint32_t c = cells_[i];
    const int cx = static_cast<int>(c % w);
    const int cy = static_cast<int>(c / w);
    for_each_approach(
        grid, chassis, cx, cy,
        [&](std::uint32_t reached, std::uint32_t least) {
          return reached <= settled && reached + least < best;
        },
        [&](int x, int y, std::uint32_t cost) {
          if (cost >= best || !detail::in_sight(grid, x, y, cx, cy)) return;
          best = cost;
          nearest = c;
        });
  }
  // Decided when no cell beyond the settled ones could give less: they cost more than `settled`
  // (or there are none: the wavefront has run to the end).
  if (settled != kUnreachable && best > settled) return false;
  group.rho_m = best == kUnreachable ? std::numeric_limits<double>::infinity()
                                     : best * (resolution_ / DistanceField::kCostUnitsPerCell);
  group.nearest_cell = nearest;
  return true;
}

bool FrontierMap::reached_by(const OccupancyGrid& grid, const FrontierGroup& group,
                             const KinematicReachability& reached) const noexcept {
  const auto w = static_cast<std::uint32_t>(width_);
  const int r = static_cast<int>(reached.range_m / resolution_);
  const long r2 = static_cast<long>(r) * r;
  for (std::uint32_t i = group.first; i < group.first + group.size; ++i) {
    const std::uint32_t c = cells_[i];
    const int cx = static_cast<int>(c % w);
    const int cy = static_cast<int>(c / w);
    for (int y = std::max(cy - r, 0); y <= std::min(cy + r, height_ - 1); ++y) {
      for (int x = std::max(cx - r, 0); x <= std::min(cx + r, width_ - 1); ++x) {
        const long dx = x - cx;
        const long dy = y - cy;
        const std::uint32_t a = grid.index(x, y);
        if (dx * dx + dy * dy <= r2 && ((reached.passed[a >> 6] >> (a & 63U)) & 1U) != 0 &&
            detail::in_sight(grid, x, y, cx, cy)) {
          return true;
        }
      }
    }
  }
  return false;
}

void FrontierMap::collect_approach_cells(const OccupancyGrid& grid, const ChassisCells& chassis,
                                         const FrontierGroup& group) noexcept {
  if (++generation_ == 0) {  // wrapped: old stamps could alias the new generation
    std::fill(stamp_.begin(), stamp_.end(), 0U);
    generation_ = 1;
  }
  // The window cells in sight that the wavefront reached, or may still reach (traversable, not
  // labelled yet: it stopped at the target's score).
  const auto w = static_cast<std::uint32_t>(width_);
  const int robot_x = static_cast<int>(seeds_[0] % w);
  const int robot_y = static_cast<int>(seeds_[0] / w);
  for (std::uint32_t i = group.first; i < group.first + group.size; ++i) {
    const std::uint32_t c = cells_[i];
    const int cx = static_cast<int>(c % w);
    const int cy = static_cast<int>(c / w);
    // A block holds a chassis cell exactly when it is traversable (the same rule); the robot's
    // cell is one of the approach's starts too.
    for_each_window_block(
        cx, cy, [&](int x0, int y0, int x1, int y1, int near_x, int near_y, std::uint32_t) {
          const bool holds_robot = robot_x >= x0 && robot_x <= x1 && robot_y >= y0 && robot_y <= y1;
          if (!holds_robot && !field_.traversable(grid.index(near_x, near_y))) return;
          for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
              const std::uint32_t a = grid.index(x, y);
              if (window_cost(x - cx, y - cy) == kUnreachable || stamp_[a] == generation_ ||
                  !approach_start(chassis, a) || !detail::in_sight(grid, x, y, cx, cy)) {
                continue;
              }
              stamp_[a] = generation_;
              GRIP_ASSERT(approach_.push_back(a));  // each cell once: at most the grid
            }
          }
        });
  }
  // On until each is labelled (a label, final or not, means reached) or the wavefront ends, a
  // search step at a time: the wavefront has come as far as the target already, and the group's
  // other approach cells usually lie a few metres beyond (doubling would cover the known space
  // again for them).
  const auto unlabelled = [this](std::uint32_t a) { return !field_.reachable(a); };
  const std::uint32_t step = search_step_cost();
  std::uint32_t limit = std::max(field_.settled_limit(), step);
  while (std::any_of(approach_.begin(), approach_.end(), unlabelled) && !field_.settle(limit)) {
    limit = limit > kUnreachable - step ? kUnreachable : limit + step;
  }
  approach_.truncate(static_cast<std::size_t>(
      std::remove_if(approach_.begin(), approach_.end(), unlabelled) - approach_.begin()));
}

}  // namespace grip
