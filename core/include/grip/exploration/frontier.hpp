#pragma once
// Frontier-based targets for mapping an unknown workspace (the paper's Sec. IV): frontier cells
// on the three-valued map, grouped by flood fill, each group's rho_A* distance from the robot,
// and the choice of the target group: close by rho_A* and small first.
//
// Definitions (the choices the paper leaves open):
//  - A frontier cell is a kFree cell with a kUnknown cell among its 4 side neighbours. Side
//    neighbours only: a free cell that touches unknown space at a corner alone lies beside a
//    frontier cell already, and counting it would thicken every frontier and turn wall corners
//    into one-cell groups. Outside the grid is not unknown (it reads as obstacle).
//  - Groups are the 8-connected components of frontier cells: a diagonal (staircase) frontier,
//    which side-neighbour frontiers produce, stays one group.
//  - The reference point cannot stand on a frontier cell: it lies one cell from unknown space,
//    which counts as an obstacle. A frontier cell is *approached* from a cell the chassis can
//    occupy (free, clearance >= clearance_m: the cells the planner's rho wavefront traverses)
//    within approach_range_m of it, in sight of it (only free cells in between). Its rho_A* is
//    the wavefront distance from the robot to that cell plus the straight distance to the
//    frontier cell, minimised over such cells. A group is reachable when one of its cells is.
//    This is what makes a frontier behind a gap too narrow for the chassis unreachable.
//  - The robot's wavefront starts from its own cell and from the chassis cells in sight within
//    approach_range_m of it (all at distance 0), so that a robot standing closer to a wall than
//    clearance_m (where the wavefront could not leave its cell) still reaches the open space.
//
// Capacity is fixed by create() (every buffer sized from the grid); update() and the accessors
// never allocate and never throw.

#include <cstdint>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/world/clearance_map.hpp"
#include "grip/world/distance_field.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

enum class ExplorationStatus {
  kTarget,            // a reachable frontier group was chosen: target() and approach_cells()
  kComplete,          // no reachable frontier remains: exploration is over
  kRobotOutsideGrid,  // the robot's position is not a cell of the grid (or not finite)
};
std::string_view exploration_status_name(ExplorationStatus s) noexcept;

struct FrontierConfig {
  // [m] The clearance the chassis' reference point needs. Must equal the planner's
  // PlannerConfig::rho_clearance_m: approach cells are handed to the planner as its target set
  // F, and its rho wavefront only leaves target cells it can traverse.
  double clearance_m = 0.3;
  // [m] The robot's wavefront runs on blocks of cells at most this large (and half clearance_m;
  // world/distance_field.hpp), as the planner's rho does: must equal PlannerConfig::rho_cell_m,
  // whose rho toward the approach cells ExplorationTarget computes with it. Approach cells and
  // the wavefront's seeds stay chassis cells; the wavefront may pass a gap a little narrower
  // than one the cells pass. 0: the map's cells.
  double rho_cell_m = 0.1;
  // [m] How close the reference point must come to a frontier cell (straight, in sight). At
  // least clearance_m plus a cell diagonal, or a frontier along a straight wall of unknown space
  // could never be approached: the nearest chassis cell lies about clearance_m + 0.07 m away.
  double approach_range_m = 0.5;
  // Target score [m] = rho_m + size_weight * min(size_m, size_cap_m), where size_m is the
  // group's frontier length (cells x resolution). Why: a small group left behind costs a trip
  // back later (the paper's reason to prefer small groups), while a long frontier will be
  // crossed anyway on the way into the space behind it. With the defaults a group of 1 m beats
  // a 6 m one up to 2.5 m farther; beyond the cap every long frontier weighs the same, so that
  // distance decides among them and the robot does not cross the map for a shorter one.
  double size_weight = 0.5;
  double size_cap_m = 6.0;
  // Groups with fewer cells are ignored (1: none is). Raise it to skip single unknown cells
  // a sensor may leave between its rays.
  std::uint32_t min_group_cells = 1;
  // [m] The robot's wavefront runs in steps of this length (doubling), until no group beyond
  // could beat the best one found: near targets cost the cells around the robot, not the whole
  // known space. The choice is the same for every step; 0: one wavefront over all of it.
  double search_step_m = 4.0;
  // [m] give_up() sets aside the frontier cells within this distance of a group's cells: the
  // group, and what it becomes while the map around it does not change, is no longer a target.
  double give_up_radius_m = 1.0;

  // Errors name the bad value: clearance_m < 0, rho_cell_m < 0, approach_range_m not >
  // clearance_m + one cell diagonal, size_weight < 0, size_cap_m < 0, give_up_radius_m < 0,
  // search_step_m < 0 (or any of them not finite), min_group_cells 0.
  Status validate(double resolution_m) const;
  bool operator==(const FrontierConfig&) const = default;
};

// Where a vehicle's kinematics can take its reference point (KinematicReach::passed()), for
// FrontierMap::update: a group counts as reachable when a passed cell lies within range_m of one
// of its cells, in sight. range_m reaches past the approach range by the chassis' length ahead
// of the reference point: a car drives nose first up to unknown space, which its sensor then
// sees into, and cannot bring its reference point nearer.
struct KinematicReachability {
  std::span<const std::uint64_t> passed;  // a bit per cell, row-major; empty: no test
  double range_m = 0.0;
};

struct FrontierGroup {
  static constexpr std::uint32_t kNoCell = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t first = 0;  // its cells are FrontierMap::frontier_cells()[first, first + size)
  std::uint32_t size = 0;   // [cells]
  double rho_m = std::numeric_limits<double>::infinity();    // +inf: not reachable
  std::uint32_t nearest_cell = kNoCell;                      // the cell that gives rho_m
  double score_m = std::numeric_limits<double>::infinity();  // see FrontierConfig; +inf: ignored
  // Whether the robot's wavefront got far enough to measure it (rho_m, nearest_cell, score_m):
  // it stops once no group beyond could beat the target (FrontierConfig::search_step_m).
  bool searched = false;
  bool reachable() const noexcept { return rho_m < std::numeric_limits<double>::infinity(); }
};

class FrontierMap {
 public:
  static constexpr std::uint32_t kNoGroup = std::numeric_limits<std::uint32_t>::max();

  // Allocates every buffer for grids of this size and resolution. Errors as for
  // OccupancyGrid::create and FrontierConfig::validate.
  static Result<FrontierMap> create(int width_cells, int height_cells, double resolution_m,
                                    const FrontierConfig& config);

  // Recomputes everything from the grid (a full pass: O(cells) for detection and grouping, the
  // robot's wavefront as far as the choice needs, plus the approach windows of the frontier
  // cells). `clearance` must be computed from this grid at its current revision (e.g. the
  // planner's CollisionChecker::clearance() after a refresh; asserted). The robot is the reference
  // point at (robot_x_m, robot_y_m). kTarget when a group was chosen, kComplete when no reachable
  // frontier group remains, kRobotOutsideGrid (nothing computed, no target) when the position
  // is not in the grid.
  //
  // `reached`: where the vehicle's kinematics can take its reference point, or empty when any
  // cell the chassis' clearance allows will do. A group it does not reach is not a target and
  // is counted in unreachable_groups().
  ExplorationStatus update(const OccupancyGrid& grid, const ClearanceMap& clearance,
                           double robot_x_m, double robot_y_m,
                           const KinematicReachability& reached = {}) noexcept;
  // The same after `change` to the grid of the last update(): frontier cells are detected again
  // and the robot's traversable set rebuilt only where it changed; grouping scans the frontier
  // cells (a bit per cell), and the wavefront goes as far as the choice needs
  // (FrontierConfig::search_step_m). Equal to a full update().
  struct MapChange {
    CellBox written;  // every cell written since the last update()
    // Where traversability can have changed: ClearanceMap::update's window (which holds every
    // cell that changed between free and not free) since the last update().
    CellBox clearance_window;
  };
  ExplorationStatus update(const OccupancyGrid& grid, const ClearanceMap& clearance,
                           double robot_x_m, double robot_y_m, const MapChange& change,
                           const KinematicReachability& reached = {}) noexcept;

  ExplorationStatus status() const noexcept { return status_; }
  // Sets group `group` of the last update aside (until forgive_all()): a frontier the vehicle could
  // not get closer to (its dynamics, a gap the wavefront passes but the chassis does not). A group
  // all of whose cells lie within give_up_radius_m of cells given up is not a target; when only
  // such groups remain, update() says kComplete and given_up_groups() counts them.
  void give_up(std::uint32_t group) noexcept;
  // Takes every group given up back (ExplorationTarget retries them once nothing else is left).
  void forgive_all() noexcept;
  // Reachable groups of the last update passed over because they were given up (of those
  // searched: all of them when no target was left).
  std::uint32_t given_up_groups() const noexcept { return given_up_groups_; }
  // Groups of the last update (searched) the chassis' clearance reaches but the vehicle's
  // kinematics does not (see update()'s `reached`), and not given up.
  std::uint32_t unreachable_groups() const noexcept { return unreachable_groups_; }
  // Every frontier cell, grouped: group g's cells are contiguous (see FrontierGroup::first), in
  // flood-fill order from the group's lowest cell index.
  std::span<const std::uint32_t> frontier_cells() const noexcept { return cells_.span(); }
  // The groups in order of their lowest cell index.
  std::span<const FrontierGroup> groups() const noexcept { return groups_.span(); }
  std::span<const std::uint32_t> group_cells(std::uint32_t group) const noexcept;
  // The chosen group (an index into groups()), kNoGroup unless status() is kTarget.
  std::uint32_t target() const noexcept { return target_; }
  // The target group's cells (empty without a target): the cells c of Sec. IV's d(tr).
  std::span<const std::uint32_t> target_cells() const noexcept;
  // The cells from which the target group is approached (each once; empty without a
  // target): the planner's target set F, Planner::retain(root, Goal::cells(approach_cells()), T).
  std::span<const std::uint32_t> approach_cells() const noexcept { return approach_.span(); }
  // The robot's wavefront of the last update (rho_A* from the robot, in the chassis' space), as
  // far as the search went (DistanceField::settled_limit()).
  const DistanceField& robot_field() const noexcept { return field_; }
  const FrontierConfig& config() const noexcept { return config_; }

 private:
  // The chassis cells (kFree, clearance >= clearance_m) of an update()'s grid and clearance
  // map, read cell by cell: the robot's wavefront may run on blocks.
  using ChassisCells = ClearCells;

  FrontierMap(int width_cells, int height_cells, double resolution_m, const FrontierConfig& config,
              DistanceField field);
  ExplorationStatus update(const OccupancyGrid& grid, const ClearanceMap& clearance,
                           double robot_x_m, double robot_y_m, const MapChange* change,
                           const KinematicReachability& reached) noexcept;
  bool reached_by(const OccupancyGrid& grid, const FrontierGroup& group,
                  const KinematicReachability& reached) const noexcept;
  void detect(const OccupancyGrid& grid, const CellBox& box) noexcept;
  void group(const OccupancyGrid& grid) noexcept;
  bool is_frontier(std::uint32_t c) const noexcept {
    return ((frontier_bits_[c >> 6] >> (c & 63U)) & 1U) != 0;
  }
  void seed_robot_field(const OccupancyGrid& grid, const ChassisCells& chassis, int robot_cx,
                        int robot_cy) noexcept;
  std::uint32_t search_step_cost() const noexcept;
  void choose_target(const OccupancyGrid& grid, const ChassisCells& chassis,
                     const KinematicReachability& reached) noexcept;
  // [cost units] A bound the group's rho cannot beat, from straight lines alone: every approach
  // path starts at a seed, within the approach range of the robot's cell (robot_cx, robot_cy),
  // and a path over blocks may be shorter by up to a block's diagonal.
  std::uint32_t rho_lower_bound(const FrontierGroup& group, int robot_cx,
                                int robot_cy) const noexcept;
  // Sets the group's rho_m and nearest_cell from the cells the robot's wavefront has settled up
  // to cost `settled`; false (nothing set) when cells beyond could still give a smaller rho.
  bool measure_group(const OccupancyGrid& grid, const ChassisCells& chassis, FrontierGroup& group,
                     std::uint32_t settled) noexcept;
  void collect_approach_cells(const OccupancyGrid& grid, const ChassisCells& chassis,
                              const FrontierGroup& group) noexcept;
  // Whether the approach may start at cell c: a chassis cell, or the robot's own (a seed).
  bool approach_start(const ChassisCells& chassis, std::uint32_t c) const noexcept {
    return chassis.contains(c) || c == seeds_[0];
  }
  // Calls visit(x0, y0, x1, y1, nx, ny, least) for every block of the robot's wavefront that
  // holds a cell of the approach window of (cx, cy): [x0, x1] x [y0, y1] are the block's cells
  // within the window's square, (nx, ny) the one nearest (cx, cy) and `least` its straight cost
  // (blocks wholly outside the window's disk are not visited). Every cell of a block reads the
  // block's wavefront cost and traversability, and the straight cost grows with distance: a
  // block's nearest cell decides whether any of its cells could matter.
  template <typename Visit>
  void for_each_window_block(int cx, int cy, Visit&& visit) const noexcept;
  // Calls visit(x, y, the cost via it) for every approach start (x, y) the wavefront reached
  // within the approach window of (cx, cy), of the blocks for which wanted(the block's cost,
  // least) holds. The caller tests sight.
  template <typename Wanted, typename Visit>
  void for_each_approach(const OccupancyGrid& grid, const ChassisCells& chassis, int cx, int cy,
                         Wanted&& wanted, Visit&& visit) const noexcept;
  // [cost units] The straight cost of window offset (dx, dy), kUnreachable outside the disk.
  std::uint32_t window_cost(int dx, int dy) const noexcept {
    return window_costs_[window_index(dx, dy)];
  }
  std::size_t window_index(int dx, int dy) const noexcept {
    const auto side = static_cast<std::size_t>(2 * reach_ + 1);
    return static_cast<std::size_t>(dy + reach_) * side + static_cast<std::size_t>(dx + reach_);
  }

  int width_;
  int height_;
  double resolution_;
  FrontierConfig config_;
  DistanceField field_;
  int reach_ = 0;                             // the approach window's half side [cells]
  std::vector<std::uint32_t> window_costs_;   // its disk in a square (see window_cost())
  std::vector<std::uint64_t> frontier_bits_;  // per cell: a frontier cell (row-major bits)
  bool detected_ = false;                     // frontier_bits_ hold the last update's grid
  CellBox frontier_rows_;                     // rows that have held a frontier cell (x unused)
  BoundedVector<std::uint32_t> label_;        // per frontier cell: kUnlabelled or its group
  BoundedVector<std::uint32_t> cells_;        // frontier cells, grouped (the flood fill's queue)
  BoundedVector<FrontierGroup> groups_;
  BoundedVector<std::uint32_t> seeds_;     // the robot wavefront's start cells
  BoundedVector<std::uint32_t> approach_;  // the target's approach cells
  BoundedVector<std::uint32_t> stamp_;     // per cell: approach_ membership, by generation
  BoundedVector<std::uint8_t> given_up_;   // per cell: 1 within give_up_radius_m of one given up
  std::uint32_t given_up_groups_ = 0;
  std::uint32_t unreachable_groups_ = 0;
  std::uint32_t generation_ = 0;
  std::uint32_t target_ = kNoGroup;
  ExplorationStatus status_ = ExplorationStatus::kComplete;
};

}  // namespace grip
