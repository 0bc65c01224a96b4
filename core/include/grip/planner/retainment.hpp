#pragma once
// Tree retainment (the paper's Sec. III-A, the start of every cycle of Algorithm 1): re-root the
// planner's tree at the state the vehicle will be in, prune what the new map or the safety
// horizon invalidates and, once a path reaches F, every path that does not; then priorities,
// rho and the heap afresh. A part of the Planner, kept in its own unit with its own buffers
// (sized at construction, never allocating afterwards); it works on the planner's tree.

#include <cstdint>

#include "grip/memory/fixed_vector.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/planner/tree_state.hpp"
#include "grip/vehicles/vehicle.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

template <VehicleModel V>
class Planner;

// What one retainment kept and pruned (edge counts).
struct RetainStats {
  std::uint32_t edges_before = 0;
  std::uint32_t cut_by_map = 0;       // edges cut where their trajectory now collides
  std::uint32_t cut_unsafe = 0;       // edges cut where the state at T cannot brake safely
  std::uint32_t pruned_off_goal = 0;  // not leading to the goal once a path does
  std::uint32_t pruned_for_room = 0;  // the worst subtrees, when the pool was filling up
  std::uint32_t released = 0;         // returned to the pool: above the new root, cut or pruned
  std::uint32_t edges_kept = 0;       // the tree carried over into the cycle
};

template <VehicleModel V>
class Retainment {
 public:
  explicit Retainment(const PlannerConfig& config);

  // Re-roots the planner's tree at `new_root` (resolved, in the tree), checks what is kept
  // against the grid when `map_changed` (only near `newly_blocked` when given) and the
  // braking contingency at the planner's horizon, releases the rest to the pools, and rebuilds
  // priorities, the heap, the best state and the solution. The planner's F, rho and horizon
  // are already those of the new cycle.
  void run(Planner<V>& p, TreeState new_root, bool map_changed,
           const CellBox* newly_blocked) noexcept;
  // The pools ran out during a solve: the worst subtrees go back to them (as between cycles,
  // without re-rooting or checking anything again), priorities and the heap afresh.
  void recycle(Planner<V>& p) noexcept;
  const RetainStats& last() const noexcept { return stats_; }

 private:
  void walk_from(const Tree<typename V::State>& tree, EdgeHandle root) noexcept;  // order_
  void prune_and_order(Planner<V>& p, EdgeHandle root, std::uint32_t shift, bool map_changed,
                       const CellBox* newly_blocked, TreeState known_solution) noexcept;
  void make_room(const Planner<V>& p, EdgeHandle root, double pool_use) noexcept;
  void release_unkept(Planner<V>& p, EdgeHandle root) noexcept;
  TreeState kept_goal_state(const Planner<V>& p, TreeState s) const noexcept;
  void rescore_tree(Planner<V>& p, TreeState known_solution) noexcept;

  std::uint32_t rescore_stride_;        // rho is sampled every this many records (Eq. 1)
  BoundedVector<EdgeHandle> order_;     // the kept tree in pre-order
  BoundedVector<EdgeHandle> stack_;     // depth-first walk
  BoundedVector<std::uint8_t> keep_;    // per edge handle, see prune_and_order
  BoundedVector<double> subtree_cost_;  // best estimated arrival below an edge
  RetainStats stats_;
};

}  // namespace grip
