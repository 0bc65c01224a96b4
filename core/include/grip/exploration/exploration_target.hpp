#pragma once
// The exploration target of the paper's Sec. IV, chosen again and again as the map grows: the
// frontier group to head for (FrontierMap: close by rho_A*, small groups first), the cells it is
// approached from (the planner's target set F) and its own cells (the c of the path selector's
// weight), and when to set a group aside because the vehicle gets no closer to it.
//
// It works on its own copy of the map, so that a runtime can run it beside the planning thread
// (its wavefronts run as far as the target and the vehicle's distance from it: milliseconds on a
// large map) and hand its result over, or inline. For the same reason it also computes the
// planner's rho toward the approach cells (Planner::adopt_goal): out to the vehicle's own rho plus
// rho_margin_m, not over the whole known space. The tree grows around the vehicle, and a state that
// much farther from the target than the vehicle is as good as lost to the greedy selection whatever
// its exact rho; on a building's map the rest is most of the known space. The copy, the clearance,
// the frontier cells and the traversable sets follow the map where it was written, not over the
// whole map.
//
// Giving up: a target the vehicle gets no closer to (its rho_A* down by progress_m) for
// give_up_after_s of vehicle time is given up (FrontierMap::give_up), and the next choice takes
// another group or ends exploration. A new target (its nearest cell moved by more than
// retarget_m), progress, or a changed map restart that clock: a vehicle that still senses new
// cells is not stuck, and in a small space successive targets lie within a few metres of each
// other. A target the vehicle has reached is given up sooner: when one of its cells lies within
// the approach range of the reference point, or the reference point's cell is one the target is
// approached from (rho 0), and the nearest cell is still the nearest give_up_reached_after_s
// later (the vehicle may sway out to twice the range meanwhile: one stopped at the range's edge
// does), the sensor does not resolve the unknown beside it from there (a crack or a pocket its
// rays do not enter: the cell may be out of straight sight from where the vehicle stopped), and
// the vehicle, already where the target is approached from, has no plan that ends closer:
// waiting for the clock would stand it still.
// Once only given-up groups are left they are all taken back, retry_rounds times: a vehicle often
// gets no closer because its planner found no plan for a while (a real-time run through a period of
// stalls), not because the group is out of its reach; without the retries a fast vehicle ends
// `stuck` having given up corners it could reach.
//
// A vehicle that cannot turn in place (the car) also keeps KinematicReach on the copy: groups
// whose approach its turning radius cannot reach are passed over as soon as its search is
// complete, and counted (unreachable_groups()) rather than chased until the clock gives up.
//
// Memory is reserved by create(); copy_map() and choose() never allocate and never throw.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>

#include "grip/common/result.hpp"
#include "grip/exploration/frontier.hpp"
#include "grip/exploration/kinematic_reach.hpp"
#include "grip/world/clearance_map.hpp"
#include "grip/world/distance_field.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

struct ExplorationTargetConfig {
  FrontierConfig frontier;
  double give_up_after_s = 60.0;         // [s of vehicle time] without progress toward a target
  double give_up_reached_after_s = 3.0;  // [s of vehicle time] reached and still a frontier
  double progress_m = 0.5;               // rho_A* must drop by this much to count as progress
  double retarget_m = 3.0;               // a nearest cell that moves this far is a new target
  std::uint32_t retry_rounds = 1;  // times the groups given up are retried when nothing is left
  // [m] rho() runs out to the vehicle's own rho_A* toward the target plus this margin; farther
  // states read as that far (DistanceField::propagate_within).
  double rho_margin_m = 20.0;
  // For a vehicle with a minimum turning radius; none for one that turns in place.
  std::optional<KinematicReachConfig> kinematics;
  // Errors name the bad value: FrontierConfig's, KinematicReachConfig's, and any of the above
  // not finite or not > 0.
  Status validate(double resolution_m) const;
};

class ExplorationTarget {
 public:
  // For maps of the geometry of `like` (its cells are copied: the first map). Errors as for
  // OccupancyGrid::create and validate().
  static Result<ExplorationTarget> create(const OccupancyGrid& like,
                                          const ExplorationTargetConfig& config);

  // The map the next choose() reads: the caller copies in the cells of its map it wrote since
  // the last copy (`written`, clipped to the map), or all of them (asserts the same width,
  // height and resolution). Not while choose() runs.
  void copy_map(const OccupancyGrid& map, const CellBox& written) noexcept;
  void copy_map(const OccupancyGrid& map) noexcept {
    copy_map(map, CellBox{0, 0, map.width() - 1, map.height() - 1});
  }
  // Chooses the target for a robot (its reference point) at (robot_x_m, robot_y_m), heading
  // robot_theta, at vehicle time now_ns. kTarget: approach_cells() and target_cells() describe
  // it; kComplete: no reachable frontier is left; kRobotOutsideGrid: no target.
  ExplorationStatus choose(double robot_x_m, double robot_y_m, double robot_theta,
                           std::int64_t now_ns) noexcept;

  // Of the last choose(); valid until the next.
  ExplorationStatus status() const noexcept { return frontiers_.status(); }
  std::span<const std::uint32_t> approach_cells() const noexcept {
    return frontiers_.approach_cells();
  }
  std::span<const std::uint32_t> target_cells() const noexcept { return frontiers_.target_cells(); }
  // The target group's cell nearest to the robot by rho_A* (its centre).
  double target_x_m() const noexcept { return target_x_m_; }
  double target_y_m() const noexcept { return target_y_m_; }
  std::uint32_t groups() const noexcept {
    return static_cast<std::uint32_t>(frontiers_.groups().size());
  }
  std::uint32_t given_up_groups() const noexcept { return frontiers_.given_up_groups(); }
  // Groups the vehicle's kinematics cannot reach (config kinematics), of the last choose().
  std::uint32_t unreachable_groups() const noexcept { return frontiers_.unreachable_groups(); }
  const OccupancyGrid& map() const noexcept { return *map_; }
  const KinematicReach* kinematics() const noexcept { return reach_ ? &*reach_ : nullptr; }
  // rho_A* toward approach_cells() on this map, with the planner's inflation
  // (frontier.clearance_m, which equals PlannerConfig::rho_clearance_m), for Planner::adopt_goal;
  // the caller may swap its contents for another field of the same size until the next
  // choose(), which overwrites it. Computed when status() is kTarget, out to rho_margin_m past
  // the vehicle.
  DistanceField& rho() noexcept { return rho_; }

 private:
  ExplorationTarget(const ExplorationTargetConfig& config, std::unique_ptr<OccupancyGrid> map,
                    ClearanceMap clearance, FrontierMap frontiers, DistanceField rho,
                    std::optional<KinematicReach> reach);
  void prepare_rho() noexcept;
  // Notes the target's cell nearest to the robot's reference point as reached (reached_cell_,
  // since now_ns) when it lies within the approach range or the robot stands on an approach cell,
  // and keeps it so while the robot stays within twice that range of it or on an approach cell.
  void note_reached(double robot_x_m, double robot_y_m, std::int64_t now_ns) noexcept;

  ExplorationTargetConfig config_;
  std::unique_ptr<OccupancyGrid> map_;  // on the heap: reach_ keeps its address
  ClearanceMap clearance_;
  FrontierMap frontiers_;
  DistanceField rho_;
  std::optional<KinematicReach> reach_;
  bool map_changed_ = true;           // since the last choose()
  CellBox written_;                   // cells copied in since the last choose()
  CellBox clearance_changed_;         // of those, the ones that changed between free and not free
  std::uint32_t clearance_exact_d2_;  // what frontiers and rho compare clearance with
  // Per rho field of ours (DistanceField::tag() 1 and 2): where traversability can have changed
  // since its traversable set was built; the tag of the one built last.
  CellBox rho_windows_[2];
  std::uint32_t last_rho_tag_ = 0;
  double target_x_m_ = 0.0;
  double target_y_m_ = 0.0;
  // Progress toward the target: its best rho_A* and when (vehicle time) it was reached.
  double best_rho_m_ = std::numeric_limits<double>::infinity();
  std::int64_t progress_ns_ = 0;
  // The target's cell nearest to the vehicle once reached, and since when (vehicle time);
  // kNoCell while not reached (see note_reached()).
  std::uint32_t reached_cell_ = FrontierGroup::kNoCell;
  std::int64_t reached_ns_ = 0;
  std::uint32_t retries_left_;
};

}  // namespace grip
