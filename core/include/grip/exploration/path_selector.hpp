#pragma once
// Path selection for exploration (the paper's Sec. IV): every root-to-state trajectory tr of the
// planner's tree is a candidate; with d_max the sensing radius and c the target cells,
//   d(tr, c) = rho_A*(q, c) for the state q of tr nearest to c among those that see c, else
//              d_max + rho(end of tr, F)
//   d(tr)    = sum over c of d(tr, c)
//   w(tr)    = d(tr) * exp(lambda * l(tr)),  l(tr) the length of tr (or its duration at a
//              reference speed: PathSelectionConfig::reference_speed_m_s),
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
// (ReplanningCycle), grows on until it holds a way out. Without sight the weight is
//   w(tr) = rho + min(rho, d_max) * (exp(lambda * l(tr)) - 1),  rho = rho(end of tr, F),
// d exp(lambda l) with d = rho where F lies within d_max (a target just behind an obstacle),
// and beyond it length weighed as at d_max: the product would make every metre cost lambda
// times the whole remaining way, and beyond 1 / lambda (20 m) of it no trajectory heading for F
// could beat the shortest one that ends any closer. The vehicle would creep toward a far target
// cycle after cycle at whatever it was doing (a car at full lock loops).
//
// The bounded approximation, and why:
//  - c ranges over at most TargetSight::kMaxTargetCells cells of the group, and "q sees c" is
//    decided on a sight grid, once per target (TargetSight: its file comment says how).
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
// Memory is reserved by create() (targets x floats per edge); select() never allocates and
// never throws.

#include <cstdint>
#include <limits>
#include <span>

#include "grip/common/result.hpp"
#include "grip/exploration/path_selection_config.hpp"
#include "grip/exploration/target_sight.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/planner/planner.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

// The chosen trajectory, ending at `state`.
struct PathChoice {
  TreeState state;  // empty when no state of the tree is min_step or more from the root, or
                    // none sees the target and none ends closer to F than the root
  double d_m = std::numeric_limits<double>::infinity();  // d(tr) (or rho at its end)
  double length_m = 0.0;  // l(tr) over the sampled states (or reference speed x duration)
  double weight = std::numeric_limits<double>::infinity();
  bool sees_target = false;  // some tree state sees a target cell: d is the visibility sum
  double root_rho_m = std::numeric_limits<double>::infinity();  // rho at the root, to F
};

class PathSelector {
 public:
  static constexpr std::uint32_t kMaxTargetCells = TargetSight::kMaxTargetCells;

  // For grids of this size and resolution and trees of up to max_edges edges (the planner's
  // PlannerConfig::max_edges). Errors as for OccupancyGrid::create and validate(), and for
  // max_edges == 0.
  static Result<PathSelector> create(int width_cells, int height_cells, double resolution_m,
                                     std::uint32_t max_edges, const PathSelectionConfig& config);
  // A sight of the target for this selector (its grid and d_max).
  Result<TargetSight> create_sight() const;

  // The minimum-weight trajectory whose end is at least min_step integration steps from the
  // root (duration >= T), the target cells c and what sees them from `sight` (one of
  // create_sight()'s). `course`: the end of the plan committed last (ReplanningCycle::
  // committed), or empty; trajectories that branch off the path to it weigh as if
  // course_change_m longer. The planner must plan on a grid of this selector's size with at
  // most max_edges edges (asserted).
  template <VehicleModel V>
  PathChoice select(const Planner<V>& planner, const TargetSight& sight, std::uint32_t min_step,
                    TreeState course = {}) noexcept;

  const PathSelectionConfig& config() const noexcept { return config_; }

 private:
  PathSelector(int width_cells, int height_cells, double resolution_m, std::uint32_t max_edges,
               const PathSelectionConfig& config);

  int width_;
  int height_;
  double resolution_;
  std::uint32_t max_edges_;
  PathSelectionConfig config_;
  BoundedVector<float> d_;           // per edge: d(tr, c) at its last sampled state
  BoundedVector<double> length_;     // per edge: l(tr) at its last state
  BoundedVector<EdgeHandle> stack_;  // the pre-order walk
  // Per edge, within select(): on the path to the last plan's end, below it, or neither.
  static constexpr std::uint8_t kOffCourse = 0;
  static constexpr std::uint8_t kOnCourse = 1;
  static constexpr std::uint8_t kBelowCourse = 2;
  BoundedVector<std::uint8_t> course_;
};

}  // namespace grip
