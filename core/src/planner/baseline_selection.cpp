#include "grip/planner/baseline_selection.hpp"

#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip {

template <VehicleModel V>
Result<BaselineSelection<V>> BaselineSelection<V>::create(const PlannerConfig& config,
                                                          const OccupancyGrid& grid) {
  std::optional<NearestSourceField> tree_cells;
  if (config.selection == Selection::kRrt || config.selection == Selection::kRrtBias) {
    auto voronoi = NearestSourceField::create(grid.width(), grid.height());
    if (!voronoi) return voronoi.error();
    tree_cells.emplace(std::move(voronoi).value());
  }
  return BaselineSelection(config, grid, std::move(tree_cells));
}

template <VehicleModel V>
BaselineSelection<V>::BaselineSelection(const PlannerConfig& config, const OccupancyGrid& grid,
                                        std::optional<NearestSourceField> tree_cells)
    : selection_(config.selection),
      rrt_goal_bias_(config.rrt_goal_bias),
      grid_(&grid),
      live_edges_(config.selection == Selection::kRandom ? config.max_edges : 0),
      free_cells_(tree_cells ? grid.cell_count() : 0),
      cell_state_(free_cells_.capacity()),
      tree_cells_(std::move(tree_cells)) {}

template <VehicleModel V>
void BaselineSelection<V>::restart(const DistanceField& rho) noexcept {
  live_edges_.clear();
  free_cells_.clear();
  if (!tree_cells_) return;
  for (std::uint32_t c = 0; c < grid_->cell_count(); ++c) {
    if (rho.reachable(c)) GRIP_ASSERT(free_cells_.push_back(c));
  }
  tree_cells_->reset();
  cell_state_.clear();
  for (std::uint32_t c = 0; c < cell_state_.capacity(); ++c) {
    GRIP_ASSERT(cell_state_.push_back(TreeState{}));
  }
}

template <VehicleModel V>
void BaselineSelection<V>::register_edge(const Tree<State>& tree, EdgeHandle e,
                                         const DistanceField& rho) noexcept {
  switch (selection_) {
    case Selection::kGrip:
      break;  // GRIP's heap is the planner's
    case Selection::kRandom:
      GRIP_ASSERT(live_edges_.push_back(e));  // sized to the edge pool
      break;
    case Selection::kRrt:
    case Selection::kRrtBias: {
      const Edge& edge = tree.edge(e);
      for (int k = edge.first; k <= edge.last; ++k) {
        const State& q = tree.state(edge.trajectory, static_cast<std::uint32_t>(k));
        int cx = 0;
        int cy = 0;
        if (!grid_->to_cell(state_x(q), state_y(q), cx, cy)) continue;
        const std::uint32_t cell = grid_->index(cx, cy);
        if (cell_state_[cell].edge != kNoHandle) continue;
        cell_state_[cell] = TreeState{e, static_cast<std::uint16_t>(k)};
        tree_cells_->add_source(rho, cell);
      }
      break;
    }
  }
}

template <VehicleModel V>
TreeState BaselineSelection<V>::select(const Tree<State>& tree,
                                       std::span<const std::uint32_t> goal_cells,
                                       Random& rng) noexcept {
  if (selection_ == Selection::kRandom) {
    return random_state_along(
        tree, live_edges_[rng.below(static_cast<std::uint32_t>(live_edges_.size()))], rng);
  }
  return select_rrt(tree, goal_cells, rng);
}

template <VehicleModel V>
TreeState BaselineSelection<V>::select_rrt(const Tree<State>& tree,
                                           std::span<const std::uint32_t> goal_cells,
                                           Random& rng) noexcept {
  // RRT-EXTEND: a random free point, and the tree state nearest to it under rho_A*: the
  // geodesic Voronoi field of the tree's cells answers in O(1).
  std::uint32_t sample = 0;
  if (selection_ == Selection::kRrtBias && rng.uniform01() < rrt_goal_bias_) {
    sample = goal_cells[rng.below(static_cast<std::uint32_t>(goal_cells.size()))];
  } else {
    sample = free_cells_[rng.below(static_cast<std::uint32_t>(free_cells_.size()))];
  }
  const std::uint32_t cell = tree_cells_->nearest_source(sample);
  if (cell == NearestSourceField::kNoCell) return TreeState{tree.root(), 0};
  return resolve(tree, cell_state_[cell]);
}

template class BaselineSelection<DdVelocity>;
template class BaselineSelection<DdAcceleration>;
template class BaselineSelection<Car>;

}  // namespace grip
