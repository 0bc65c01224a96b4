#pragma once
// How the baselines of the paper's Fig. 5/6 choose the state to propagate from, on GRIP's tree,
// propagation and rho (GRIP's own selection, the heap of scores, is the planner's):
//   kRandom   a random state along an edge chosen uniformly at random;
//   kRrt      RRT-EXTEND: the tree state nearest (by rho_A*) to a random free cell;
//   kRrtBias  the same, with a cell of F as the sample a fraction of the time.
// Everything is reserved by create(); the rest never allocates.

#include <cstdint>
#include <optional>
#include <span>

#include "grip/common/random.hpp"
#include "grip/common/result.hpp"
#include "grip/memory/fixed_vector.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/planner/tree.hpp"
#include "grip/planner/tree_state.hpp"
#include "grip/vehicles/vehicle.hpp"
#include "grip/world/distance_field.hpp"
#include "grip/world/nearest_source_field.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

template <VehicleModel V>
class BaselineSelection {
 public:
  using State = typename V::State;

  // Sized for `config`'s selection (nothing for kGrip) on `grid`, which must outlive it.
  static Result<BaselineSelection> create(const PlannerConfig& config, const OccupancyGrid& grid);

  // A fresh tree is about to grow: forgets the edges; RRT samples the cells rho_A* (`rho`)
  // reaches from F, so that every sample has a nearest tree state.
  void restart(const DistanceField& rho) noexcept;
  // Makes a new edge of `tree` selectable (RRT: its states' cells become sources of the
  // nearest-state field under `rho`).
  void register_edge(const Tree<State>& tree, EdgeHandle e, const DistanceField& rho) noexcept;
  // The state to propagate from. `goal_cells` are F's cells (RRT's bias); draws from `rng` in
  // a fixed order, so that a seed replays a run.
  TreeState select(const Tree<State>& tree, std::span<const std::uint32_t> goal_cells,
                   Random& rng) noexcept;

 private:
  BaselineSelection(const PlannerConfig& config, const OccupancyGrid& grid,
                    std::optional<NearestSourceField> tree_cells);
  TreeState select_rrt(const Tree<State>& tree, std::span<const std::uint32_t> goal_cells,
                       Random& rng) noexcept;

  Selection selection_;
  double rrt_goal_bias_;
  const OccupancyGrid* grid_;
  BoundedVector<EdgeHandle> live_edges_;          // random selection
  BoundedVector<std::uint32_t> free_cells_;       // RRT samples: cells rho_A* can reach
  BoundedVector<TreeState> cell_state_;           // RRT: a tree state in each grid cell
  std::optional<NearestSourceField> tree_cells_;  // RRT: nearest tree cell under rho_A*
};

}  // namespace grip
