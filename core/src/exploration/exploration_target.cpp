#include "grip/exploration/exploration_target.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "../world/validation.hpp"
#include "grip/common/assert.hpp"

namespace grip {

Status ExplorationTargetConfig::validate(double resolution_m) const {
  if (Status s = frontier.validate(resolution_m); !s) return s;
  const auto positive = [](const char* name, double value) -> Status {
    if (std::isfinite(value) && value > 0.0) return Ok{};
    return invalid_argument(std::string("exploration target: ") + name +
                            " must be finite and > 0 (got " + detail::format_number(value) + ")");
  };
  if (Status s = positive("give_up_after_s", give_up_after_s); !s) return s;
  if (Status s = positive("give_up_reached_after_s", give_up_reached_after_s); !s) return s;
  if (Status s = positive("progress_m", progress_m); !s) return s;
  if (Status s = positive("rho_margin_m", rho_margin_m); !s) return s;
  if (kinematics) {
    if (Status s = kinematics->validate(); !s) return s;
  }
  return positive("retarget_m", retarget_m);
}

Result<ExplorationTarget> ExplorationTarget::create(const OccupancyGrid& like,
                                                    const ExplorationTargetConfig& config) {
  if (Status s = config.validate(like.resolution()); !s) return s.error();
  auto clearance = ClearanceMap::create_for(like);
  if (!clearance) return clearance.error();
  auto frontiers =
      FrontierMap::create(like.width(), like.height(), like.resolution(), config.frontier);
  if (!frontiers) return frontiers.error();
  auto rho =
      DistanceField::create(like.width(), like.height(), like.resolution(),
                            DistanceField::block_for(like.resolution(), config.frontier.rho_cell_m,
                                                     config.frontier.clearance_m));
  if (!rho) return rho.error();
  auto map = std::make_unique<OccupancyGrid>(like);
  std::optional<KinematicReach> reach;
  if (config.kinematics) {
    auto made = KinematicReach::create(*map, *config.kinematics);
    if (!made) return made.error();
    reach.emplace(std::move(made).value());
  }
  return ExplorationTarget(config, std::move(map), std::move(clearance).value(),
                           std::move(frontiers).value(), std::move(rho).value(), std::move(reach));
}

ExplorationTarget::ExplorationTarget(const ExplorationTargetConfig& config,
                                     std::unique_ptr<OccupancyGrid> map, ClearanceMap clearance,
                                     FrontierMap frontiers, DistanceField rho,
                                     std::optional<KinematicReach> reach)
    : config_(config),
      map_(std::move(map)),
      clearance_(std::move(clearance)),
      frontiers_(std::move(frontiers)),
      rho_(std::move(rho)),
      reach_(std::move(reach)),
      clearance_exact_d2_(clearance_.squared_cells_at_least(config.frontier.clearance_m)),
      retries_left_(config.retry_rounds) {}

void ExplorationTarget::copy_map(const OccupancyGrid& map, const CellBox& written) noexcept {
  GRIP_ASSERT(map.width() == map_->width() && map.height() == map_->height() &&
              map.resolution() == map_->resolution());
  const CellBox box{std::max(written.x0, 0), std::max(written.y0, 0),
                    std::min(written.x1, map.width() - 1), std::min(written.y1, map.height() - 1)};
  if (box.empty()) return;
  const auto n = static_cast<std::size_t>(box.x1 - box.x0 + 1);
  for (int y = box.y0; y <= box.y1; ++y) {
    const Cell* from = map.cells().data() + map.index(box.x0, y);
    Cell* to = map_->mutable_cells().data() + map.index(box.x0, y);
    if (std::memcmp(from, to, n) == 0) continue;  // much of a sweep's box is as it was
    // The row's first and last cells that changed between free and not free.
    std::size_t first = 0;
    while (first < n && (to[first] == Cell::kFree) == (from[first] == Cell::kFree)) ++first;
    if (first < n) {
      std::size_t last = n - 1;
      while ((to[last] == Cell::kFree) == (from[last] == Cell::kFree)) --last;
      clearance_changed_.add(
          CellBox{box.x0 + static_cast<int>(first), y, box.x0 + static_cast<int>(last), y});
    }
    std::memcpy(to, from, n);
  }
  written_.add(box);
  map_changed_ = true;
}

// The fields rho_ holds go to the planner and come back (Planner::adopt_goal swaps them): one
// of ours (tagged 1 or 2), still built from this map, is rebuilt only where traversability
// changed since; any other is built whole and tagged apart from the one the planner holds.
void ExplorationTarget::prepare_rho() noexcept {
  std::uint32_t tag = rho_.tag();
  if ((tag == 1 || tag == 2) && rho_.mask_source() == map_.get()) {
    rho_.prepare(*map_, clearance_, config_.frontier.clearance_m, rho_windows_[tag - 1]);
  } else {
    tag = last_rho_tag_ == 1 ? 2 : 1;
    rho_.set_tag(tag);
    rho_.prepare(*map_, clearance_, config_.frontier.clearance_m);
  }
  rho_windows_[tag - 1] = CellBox{};
  last_rho_tag_ = tag;
}

ExplorationStatus ExplorationTarget::choose(double robot_x_m, double robot_y_m, double robot_theta,
                                            std::int64_t now_ns) noexcept {
  const OccupancyGrid& map = *map_;
  const bool map_changed = std::exchange(map_changed_, false);
  // Clearance, frontiers and the robot's traversable set near what changed only (the clearance
  // created computed; exact as far as frontiers and rho ask).
  FrontierMap::MapChange change;
  const CellBox freedom_changed = std::exchange(clearance_changed_, CellBox{});
  if (map_changed) {
    change.clearance_window = clearance_.update(map, freedom_changed, clearance_exact_d2_);
    change.written = std::exchange(written_, CellBox{});
    for (CellBox& window : rho_windows_) window.add(change.clearance_window);
  }
  // Until its search is complete, the kinematic reach cannot tell a group out of reach.
  KinematicReachability reached;
  if (reach_) {
    reach_->update(freedom_changed, robot_x_m, robot_y_m, robot_theta);
    if (reach_->complete()) {
      const Footprint& chassis = config_.kinematics->footprint;
      reached.passed = reach_->passed();
      reached.range_m =
          config_.frontier.approach_range_m + std::max(chassis.front_m, chassis.rear_m);
    }
  }
  ExplorationStatus status =
      frontiers_.update(map, clearance_, robot_x_m, robot_y_m, change, reached);
  if (status == ExplorationStatus::kComplete && frontiers_.given_up_groups() > 0 &&
      retries_left_ > 0) {
    --retries_left_;
    frontiers_.forgive_all();
    status =
        frontiers_.update(map, clearance_, robot_x_m, robot_y_m, FrontierMap::MapChange{}, reached);
  }
  if (status != ExplorationStatus::kTarget) return status;
  const FrontierGroup& group = frontiers_.groups()[frontiers_.target()];
  prepare_rho();
  // The robot's wavefront measured the vehicle's rho_A* toward the approach cells (from seeds
  // within the approach range of it, which the margin covers).
  const double limit_units =
      (group.rho_m + config_.rho_margin_m) / map.resolution() * DistanceField::kCostUnitsPerCell;
  rho_.propagate_within(frontiers_.approach_cells(),
                        static_cast<std::uint32_t>(std::min(
                            limit_units, static_cast<double>(DistanceField::kUnreachable - 1))));
  if (group.nearest_cell != FrontierGroup::kNoCell) {
    const double x = map.cell_center_x(map.cell_x(group.nearest_cell));
    const double y = map.cell_center_y(map.cell_y(group.nearest_cell));
    if (std::hypot(x - target_x_m_, y - target_y_m_) > config_.retarget_m ||
        group.rho_m < best_rho_m_ - config_.progress_m || map_changed) {
      best_rho_m_ = group.rho_m;
      progress_ns_ = now_ns;
    }
    target_x_m_ = x;
    target_y_m_ = y;
  }
  note_reached(robot_x_m, robot_y_m, now_ns);
  // No closer for a long while: dynamics or a gap the chassis cannot pass keep the vehicle from
  // it; or reached, and still there: the sensor does not resolve it from where it is approached.
  // Set it aside; the next choice takes another target, or ends exploration.
  const auto longer_than = [now_ns](std::int64_t since_ns, double limit_s) {
    return static_cast<double>(now_ns - since_ns) > limit_s * 1e9;
  };
  if (longer_than(progress_ns_, config_.give_up_after_s) ||
      (reached_cell_ != FrontierGroup::kNoCell &&
       longer_than(reached_ns_, config_.give_up_reached_after_s))) {
    frontiers_.give_up(frontiers_.target());
    best_rho_m_ = std::numeric_limits<double>::infinity();
    progress_ns_ = now_ns;
    reached_cell_ = FrontierGroup::kNoCell;
  }
  return status;
}

void ExplorationTarget::note_reached(double robot_x_m, double robot_y_m,
                                     std::int64_t now_ns) noexcept {
  const OccupancyGrid& map = *map_;
  double nearest_m = std::numeric_limits<double>::infinity();
  std::uint32_t nearest = FrontierGroup::kNoCell;
  for (const std::uint32_t c : frontiers_.target_cells()) {
    const double d = std::hypot(map.cell_center_x(map.cell_x(c)) - robot_x_m,
                                map.cell_center_y(map.cell_y(c)) - robot_y_m);
    if (d < nearest_m) {
      nearest_m = d;
      nearest = c;
    }
  }
  const double range_m = config_.frontier.approach_range_m;
  // On an approach cell (rho 0) the vehicle is as near as rho can bring it even when it is beyond
  // the range (the cell's centre is within it): the path selector, whose sight of the target is
  // coarser, may see no target cell from there and then has nothing nearer to offer.
  int cx = 0;
  int cy = 0;
  const bool approached = nearest_m <= range_m || (map.to_cell(robot_x_m, robot_y_m, cx, cy) &&
                                                   rho_.cost_at(map.index(cx, cy)) == 0);
  // A vehicle stopped at the edge of the range sways across it: the cell stays reached until the
  // vehicle is twice the range away.
  if (nearest == reached_cell_ && (approached || nearest_m <= 2.0 * range_m)) return;
  reached_cell_ = approached ? nearest : FrontierGroup::kNoCell;
  reached_ns_ = now_ns;
}

}  // namespace grip
