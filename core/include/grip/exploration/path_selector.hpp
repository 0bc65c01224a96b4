#pragma once
// Path selection for exploration (the paper's Sec. IV): every root-to-state trajectory tr of the
// planner's tree is a candidate; with d_max the sensing radius and c the target cells,
//   d(tr, c) = rho_A*(q, c) for the state q of tr nearest to c among those that see c, else
//              d_max + rho(end of tr, F)
//   d(tr)    = sum over c of d(tr, c)
//   w(tr)    = d(tr) * exp(lambda * l(tr)),  l(tr) the length of tr,
// and the selector returns the minimum-weight state at least T (min_step) from the root. The
// paper has d_max alone for an unseen cell; then a trajectory that sees a few cells loses to
// one that barely moves (its length costs more than the cells gain), and the robot stalls where
// the frontier is just in sight. Adding rho from the trajectory's end rewards each step toward
// the cells it does not see yet; a seen cell still counts less than any unseen one. When no
// state of the tree sees any target cell, d(tr) is instead rho at the end of tr: the planner's
// rho to its target set F (Planner::rho_m: rho_A*, and for a car the turn it needs to head
// along its path), in exploration the target group's approach cells within approach range of
// the frontier (exploration/frontier.hpp), and only trajectories that
// end closer to F than the root are candidates. Without that rule a car facing a dead end, whose
// way out begins by backing away from F, would choose the shortest trajectory of at least T
// cycle after cycle: it creeps, and every re-rooting throws away the tree's attempts at a way
// out. With it there is no choice, the vehicle stops, and the tree, kept at the resting root
// (ReplanningCycle), grows on until it holds a way out.
//
// The bounded approximation, and why:
//  - c ranges over at most kMaxTargetCells cells of the group, evenly spread along it: a
//    frontier group can hold hundreds of cells, and one bit per cell keeps "which of them does
//    this grid cell see" a 32-bit word.
//  - Seeing is decided per sight cell, once per set_target(): rays are cast from each target's
//    sight cell to the border of the square of half-side d_max around it and walk
//    (detail::trace_cells) until they leave the sensing disk or meet a cell that blocks the view;
//    every cell they cross is marked as seeing that target. Sight along a segment is symmetric,
//    so this is "the state's cell sees c" at the sight grid's resolution, with rays to the
//    border cells standing for the segments to each cell (rays one border cell apart are less
//    than a cell apart everywhere inside). Cost: O(kMaxTargetCells x 8 r^2) per call, r = d_max
//    in sight cells, independent of the tree.
//  - The sight grid is the map's grid while d_max spans at most kMaxSightRadius of its cells,
//    else blocks of k x k map cells with k the smallest that brings d_max within it: the cost
//    of a call is bounded however fine the map is. A block blocks the view when one of its
//    cells is an obstacle or none is free: a wall stops sight at the block it touches, up to a
//    block early, and a frontier's own block, part unknown, is seen through. The target's own
//    block is always in sight.
//  - Where q sees c, rho_A*(q, c) is the straight distance: the segment between them is free,
//    so it is the shortest path.
//  - d and l are taken over the states sampled every sample_step_s along each edge (and its
//    last state), the way Eq. 1 samples rho; l sums the chords between them. One pass over the
//    tree in pre-order computes every edge's d(tr, c) vector from its parent's (elementwise
//    minimum), so each sampled state costs O(1) when it sees nothing and O(targets) when it
//    does. The pass runs when the plan is chosen rather than while the tree grows: the planner
//    splits, re-roots and prunes edges, and values kept in step with that would have to live
//    inside it. The pass is linear in the sampled states, a few milliseconds for a tree of
//    thousands of edges; it runs after growth, so the cycle's safety margin (or an earlier stop
//    of growth) must cover it.
//
// Memory is reserved by create() (a 32-bit mask and, with blocks, a 32-bit stamp per sight
// cell; targets x floats per edge);
// set_target() and select() never allocate and never throw.

#include <cstdint>
#include <limits>
#include <span>

#include "grip/common/result.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/planner/planner.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

struct PathSelectionConfig {
  double sensing_radius_m = 3.0;      // d_max: the sensor's range (one tenth of the scene)
  double length_weight_per_m = 0.05;  // lambda: a trajectory 14 m longer weighs twice as much
  double sample_step_s = 0.2;         // states sampled along each edge this far apart in time

  // Errors name the bad value: any value not finite or not > 0 (lambda may be 0).
  Status validate() const;
};

// The chosen trajectory, ending at `state`.
struct PathChoice {
  TreeState state;  // empty when no state of the tree is min_step or more from the root, or
                    // none sees the target and none ends closer to F than the root
  double d_m = std::numeric_limits<double>::infinity();  // d(tr) (or rho at its end)
  double length_m = 0.0;                                 // l(tr) over the sampled states
  double weight = std::numeric_limits<double>::infinity();
  bool sees_target = false;  // some tree state sees a target cell: d is the visibility sum
};

class PathSelector {
 public:
  static constexpr std::uint32_t kMaxTargetCells = 32;
  // [sight cells] d_max spans at most this many cells of the sight grid (see the file comment).
  static constexpr int kMaxSightRadius = 64;

  // For grids of this size and resolution and trees of up to max_edges edges (the planner's
  // PlannerConfig::max_edges). Errors as for OccupancyGrid::create and validate(), and for
  // max_edges == 0.
  static Result<PathSelector> create(int width_cells, int height_cells, double resolution_m,
                                     std::uint32_t max_edges, const PathSelectionConfig& config);

  // The cells c of d(tr) (e.g. FrontierMap::target_cells()): up to kMaxTargetCells of them,
  // evenly spread over the list, and which grid cells see each. Call it whenever the target or
  // the map changed (every cycle). Asserts the grid's size matches and every cell is in it.
  void set_target(const OccupancyGrid& grid, std::span<const std::uint32_t> cells) noexcept;

  // The minimum-weight trajectory whose end is at least min_step integration steps from the
  // root (duration >= T). The planner must plan on a grid of this selector's size with at most
  // max_edges edges (asserted).
  template <VehicleModel V>
  PathChoice select(const Planner<V>& planner, std::uint32_t min_step) noexcept;

  // The target cells used (after subsampling), and which of them (bit i: target_cells()[i])
  // the grid cell sees.
  std::span<const std::uint32_t> target_cells() const noexcept { return targets_.span(); }
  std::uint32_t seen_from(std::uint32_t cell) const noexcept;
  // Map cells per side of a sight cell (1: the map's own grid).
  int sight_block() const noexcept { return block_; }
  const PathSelectionConfig& config() const noexcept { return config_; }

 private:
  PathSelector(int width_cells, int height_cells, double resolution_m, std::uint32_t max_edges,
               const PathSelectionConfig& config);
  void cast_rays_from(const OccupancyGrid& grid, std::uint32_t target_bit) noexcept;
  bool blocks_sight(const OccupancyGrid& grid, int sx, int sy) noexcept;
  // The sight cell holding map cell (x, y).
  std::uint32_t sight_cell(std::uint32_t x, std::uint32_t y) const noexcept;
  // The index of sight cell (sx, sy), inside the sight grid.
  std::uint32_t sight_index(int sx, int sy) const noexcept;

  int width_;
  int height_;
  double resolution_;
  int block_;        // map cells per side of a sight cell
  int sight_width_;  // sight cells
  int sight_height_;
  std::uint32_t stamp_ = 0;  // of the current set_target(); blocked_ holds stamp_ << 1 | blocks
  double origin_x_m_ = 0.0;  // of the grid given to set_target()
  double origin_y_m_ = 0.0;
  std::uint32_t max_edges_;
  PathSelectionConfig config_;
  FixedVector<std::uint32_t, kMaxTargetCells> targets_;
  double target_x_m_[kMaxTargetCells] = {};  // cell centres
  double target_y_m_[kMaxTargetCells] = {};
  BoundedVector<std::uint32_t> seen_;       // per sight cell: bit i set = sees target i
  BoundedVector<std::uint32_t> seen_list_;  // sight cells with a bit set, to clear them
  BoundedVector<std::uint32_t> blocked_;    // per sight cell, with blocks: stamp_ when known
  BoundedVector<float> d_;                  // per edge: d(tr, c) at its last sampled state
  BoundedVector<double> length_;            // per edge: l(tr) at its last state
  BoundedVector<EdgeHandle> stack_;         // the pre-order walk
};

}  // namespace grip
