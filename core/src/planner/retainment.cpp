#include "grip/planner/retainment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "grip/planner/planner.hpp"

namespace grip {

template <VehicleModel V>
Retainment<V>::Retainment(const PlannerConfig& config)
    // rho is sampled every 0.2 s of trajectory: Eq. 1 takes states "sampled along e", and a
    // full scan of every state of a big tree would not fit a cycle.
    : rescore_stride_(std::max<std::uint32_t>(
          1U, static_cast<std::uint32_t>(std::lround(0.2 / config.record_step_s())))),
      order_(config.max_edges),
      stack_(config.max_edges),
      keep_(config.max_edges),
      subtree_cost_(config.max_edges) {
  for (std::uint32_t e = 0; e < config.max_edges; ++e) {
    GRIP_ASSERT(subtree_cost_.push_back(std::numeric_limits<double>::infinity()));
  }
}

template <VehicleModel V>
void Retainment<V>::run(Planner<V>& p, TreeState new_root, bool map_changed,
                        const CellBox* newly_blocked) noexcept {
  auto& tree = p.tree_;
  stats_ = RetainStats{};
  stats_.edges_before = tree.edge_count();
  // The earliest goal state found so far: rho and F are sampled along edges, and a path that
  // crosses F between two samples must not be lost to one that lingers there.
  const TreeState known_solution = p.solution_;

  // Re-root: the part of the edge up to the new root becomes the root (reduced to its last
  // state); the rest of the tree above is unreachable, since no vehicle drives back in time.
  const std::uint32_t shift = tree.step_of(new_root.edge, new_root.index);
  EdgeHandle root = new_root.edge;
  if (new_root.index < tree.edge(root).last) root = tree.split(root, new_root.index);
  tree.unlink(root);
  tree.make_root(root);
  prune_and_order(p, root, shift, map_changed, newly_blocked, known_solution);
  std::uint32_t kept = 0;
  for (const EdgeHandle e : order_) kept += keep_[e] != 0 ? 1U : 0U;
  // Between cycles the edge pool decides: trajectories are reused by the splits of re-rooting.
  make_room(p, root, static_cast<double>(kept) / tree.edge_capacity());
  release_unkept(p, root);
  rescore_tree(p, known_solution);
  stats_.edges_kept = tree.edge_count();
}

template <VehicleModel V>
void Retainment<V>::recycle(Planner<V>& p) noexcept {
  auto& tree = p.tree_;
  stats_ = RetainStats{};
  stats_.edges_before = tree.edge_count();
  const TreeState known_solution = p.solution_;
  const EdgeHandle root = tree.root();
  walk_from(tree, root);
  for (const EdgeHandle e : order_) keep_[e] = 1;
  // Whichever pool is fuller decides, trajectories included: the solve stopped on either.
  const double edge_use = static_cast<double>(tree.edge_count()) / tree.edge_capacity();
  const double trajectory_use =
      static_cast<double>(tree.trajectory_count()) / tree.trajectory_capacity();
  make_room(p, root, std::max(edge_use, trajectory_use));
  release_unkept(p, root);
  rescore_tree(p, known_solution);
  stats_.edges_kept = tree.edge_count();
}

template <VehicleModel V>
void Retainment<V>::walk_from(const Tree<typename V::State>& tree, EdgeHandle root) noexcept {
  keep_.clear();
  for (std::uint32_t e = 0; e < tree.edge_capacity(); ++e) GRIP_ASSERT(keep_.push_back(0));
  order_.clear();
  stack_.clear();
  GRIP_ASSERT(stack_.push_back(root));
  while (!stack_.empty()) {
    const EdgeHandle e = stack_.back();
    stack_.pop_back();
    GRIP_ASSERT(order_.push_back(e));
    for (EdgeHandle c = tree.edge(e).first_child; c != kNoHandle; c = tree.edge(c).next_sibling) {
      GRIP_ASSERT(stack_.push_back(c));
    }
  }
}

template <VehicleModel V>
void Retainment<V>::prune_and_order(Planner<V>& p, EdgeHandle root, std::uint32_t shift,
                                    bool map_changed, const CellBox* newly_blocked,
                                    TreeState known_solution) noexcept {
  auto& tree = p.tree_;
  // keep_[e]: 0 released, 1 kept, 2 kept but its children released (it was cut short);
  // kInGoal marks edges with a sampled state in F, then those with one below them.
  constexpr std::uint8_t kInGoal = 4;
  walk_from(tree, root);

  // Which states the new map can have invalidated: none when it did not change; those within
  // the chassis' reach of the newly blocked cells when the caller says where; else all.
  const bool check_all = map_changed && newly_blocked == nullptr;
  const bool check_some = map_changed && newly_blocked != nullptr && !newly_blocked->empty();
  double box_x0 = 0.0, box_y0 = 0.0, box_x1 = 0.0, box_y1 = 0.0;
  if (check_some) {
    const double reach =
        p.checker_.checked_footprint().circumscribed_radius() + p.grid_->resolution();
    box_x0 = p.grid_->origin_x() + newly_blocked->x0 * p.grid_->resolution() - reach;
    box_y0 = p.grid_->origin_y() + newly_blocked->y0 * p.grid_->resolution() - reach;
    box_x1 = p.grid_->origin_x() + (newly_blocked->x1 + 1) * p.grid_->resolution() + reach;
    box_y1 = p.grid_->origin_y() + (newly_blocked->y1 + 1) * p.grid_->resolution() + reach;
  }

  // Pre-order: every parent comes before its children, so one pass re-times the edges,
  // checks them against the new map and T, and propagates removals downwards.
  for (const EdgeHandle e : order_) {
    Edge& edge = tree.edge(e);
    if (e == root) {
      edge.start_step = 0;
      keep_[e] = 1;
      continue;
    }
    if (keep_[edge.parent] != 1) continue;  // below a removed or shortened edge
    edge.start_step -= shift;               // times are from the new root
    std::uint16_t last = edge.last;
    bool unsafe = false;
    if (check_all || check_some) {
      for (std::uint16_t k = static_cast<std::uint16_t>(edge.first + 1); k <= edge.last; ++k) {
        const typename V::State& qk = tree.state(edge.trajectory, k);
        const double x = state_x(qk);
        const double y = state_y(qk);
        const bool near = check_all || (x >= box_x0 && x <= box_x1 && y >= box_y0 && y <= box_y1);
        if (near && !p.is_free(qk)) {
          last = static_cast<std::uint16_t>(k - 1);
          break;
        }
      }
    }
    // The state reached at T, if this edge holds it, must be able to brake (one state, found
    // by its time, not by a scan).
    const std::uint32_t t_offset = p.horizon_step_ - std::min(p.horizon_step_, edge.start_step);
    if (p.config_.safety == SafetyCheck::kAtHorizon && edge.start_step < p.horizon_step_ &&
        t_offset <= static_cast<std::uint32_t>(last - edge.first)) {
      const auto k = static_cast<std::uint16_t>(edge.first + t_offset);
      if (!p.contingency_safe(tree.state(edge.trajectory, k))) {
        last = static_cast<std::uint16_t>(k - 1);
        unsafe = true;
      }
    }
    if (last == edge.last) {
      keep_[e] = 1;
      continue;
    }
    ++(unsafe ? stats_.cut_unsafe : stats_.cut_by_map);
    if (last > edge.first) {
      edge.last = last;
      keep_[e] = 2;
    }
  }

  // Rho against the new target (Eq. 1 over states sampled along each edge) and membership of
  // F, in one pass; reverse pre-order then carries "leads to F" up to the root.
  bool reaches_goal = false;
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0) continue;
    Edge& edge = tree.edge(e);
    bool in_goal = false;
    edge.rho_m = e == root ? p.rho_m(tree.edge_state(e, edge.last))
                           : p.sampled_rho(e, rescore_stride_, &in_goal);
    if (in_goal) {
      keep_[e] = static_cast<std::uint8_t>(keep_[e] | kInGoal);
      reaches_goal = true;
    }
  }
  if (const TreeState s = kept_goal_state(p, known_solution); s.edge != kNoHandle) {
    keep_[s.edge] = static_cast<std::uint8_t>(keep_[s.edge] | kInGoal);
    reaches_goal = true;
  }
  // Once a path reaches F, every path that does not is pruned, so that the cycle improves
  // the solution (Algorithm 1).
  if (reaches_goal) {
    for (auto it = order_.end(); it != order_.begin();) {
      const EdgeHandle e = *--it;
      if (keep_[e] == 0 || e == root || (keep_[e] & kInGoal) == 0) continue;
      const EdgeHandle parent = tree.edge(e).parent;
      keep_[parent] = static_cast<std::uint8_t>(keep_[parent] | kInGoal);
    }
    for (const EdgeHandle e : order_) {
      if (keep_[e] == 0 || e == root) continue;
      if ((keep_[e] & kInGoal) == 0) {
        keep_[e] = 0;
        ++stats_.pruned_off_goal;
      }
    }
  }
  for (const EdgeHandle e : order_) keep_[e] = static_cast<std::uint8_t>(keep_[e] & ~kInGoal);
  keep_[root] = 1;
}

template <VehicleModel V>
void Retainment<V>::release_unkept(Planner<V>& p, EdgeHandle root) noexcept {
  auto& tree = p.tree_;
  GRIP_ASSERT(keep_[root] != 0);
  // Repair the links of what stays: drop released children from the child lists.
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0) continue;
    Edge& edge = tree.edge(e);
    EdgeHandle previous = kNoHandle;
    EdgeHandle first = kNoHandle;
    for (EdgeHandle c = edge.first_child; c != kNoHandle; c = tree.edge(c).next_sibling) {
      if (keep_[e] != 1 || keep_[c] == 0) continue;
      tree.edge(c).prev_sibling = previous;
      if (previous == kNoHandle) {
        first = c;
      } else {
        tree.edge(previous).next_sibling = c;
      }
      previous = c;
    }
    if (previous != kNoHandle) tree.edge(previous).next_sibling = kNoHandle;
    edge.first_child = first;
  }
  // Everything not kept goes back to the pools.
  const std::uint32_t before_release = tree.edge_count();
  for (EdgeHandle e = 0; e < tree.edge_capacity(); ++e) {
    if (tree.contains(e) && keep_[e] == 0) tree.release_edge(e);
  }
  stats_.released = before_release - tree.edge_count();
}

template <VehicleModel V>
void Retainment<V>::make_room(const Planner<V>& p, EdgeHandle root, double pool_use) noexcept {
  auto& tree = p.tree_;
  // Memory is fixed and a replanning tree only loses what falls behind the root, so a long run
  // would fill the pools and stop growing. Past 60% of the pool (`pool_use`, the kept share),
  // the subtrees whose best estimated arrival (rho + time at a quarter of top speed) is worst
  // are released until about 40% remain. A subtree's best is never better than its parent's,
  // so what stays is a tree.
  if (pool_use <= 0.6) return;
  std::uint32_t kept = 0;
  for (const EdgeHandle e : order_) kept += keep_[e] != 0 ? 1U : 0U;
  const auto target = static_cast<std::uint32_t>(kept * (0.4 / pool_use));
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  for (auto it = order_.end(); it != order_.begin();) {
    const EdgeHandle e = *--it;
    if (keep_[e] == 0) continue;
    const Edge& edge = tree.edge(e);
    const double own = edge.rho_m + p.cost_speed_ * p.step_time(tree.end_step(e));
    subtree_cost_[e] = std::min(subtree_cost_[e], own);  // children came first: min over them
    if (e != root)
      subtree_cost_[edge.parent] = std::min(subtree_cost_[edge.parent], subtree_cost_[e]);
    if (std::isfinite(subtree_cost_[e])) {
      low = std::min(low, subtree_cost_[e]);
      high = std::max(high, subtree_cost_[e]);
    }
  }
  // The threshold that keeps about `target` edges, by bisection over the costs.
  for (int i = 0; i < 40 && low < high; ++i) {
    const double middle = 0.5 * (low + high);
    std::uint32_t below = 0;
    for (const EdgeHandle e : order_)
      below += keep_[e] != 0 && subtree_cost_[e] <= middle ? 1U : 0U;
    (below > target ? high : low) = middle;
  }
  for (const EdgeHandle e : order_) {
    if (keep_[e] != 0 && e != root && !(subtree_cost_[e] <= high)) {
      keep_[e] = 0;
      ++stats_.pruned_for_room;
    }
    subtree_cost_[e] = std::numeric_limits<double>::infinity();  // ready for the next cycle
  }
}

template <VehicleModel V>
TreeState Retainment<V>::kept_goal_state(const Planner<V>& p, TreeState s) const noexcept {
  auto& tree = p.tree_;
  // During retainment, after the walk: s if it is still in the kept tree below the root (not
  // cut off, not released) and in the current F.
  if (s.edge == kNoHandle || !tree.contains(s.edge)) return TreeState{};
  s = resolve(tree, s);
  if (s.edge == kNoHandle || s.edge == tree.root() || keep_[s.edge] == 0) return TreeState{};
  const Edge& edge = tree.edge(s.edge);
  if (s.index <= edge.first || s.index > edge.last) return TreeState{};
  if (!p.in_goal_region(tree.state(edge.trajectory, s.index))) return TreeState{};
  return s;
}

template <VehicleModel V>
void Retainment<V>::rescore_tree(Planner<V>& p, TreeState known_solution) noexcept {
  auto& tree = p.tree_;
  // Children of the root get priority 1, then Eq. 2 down the tree; the heap is rebuilt; the
  // best state and the solution are found again (over the same sampled states as rho).
  p.heap_.clear();
  p.solution_ = TreeState{};
  const EdgeHandle root = tree.root();
  p.best_ = TreeState{root, tree.edge(root).last};
  p.best_rho_ = tree.edge(root).rho_m;
  p.best_cost_m_ = std::numeric_limits<double>::infinity();
  EdgeHandle best_edge = root;
  double best_edge_cost = p.best_cost_m_;
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0) continue;
    Edge& edge = tree.edge(e);
    if (e == root) {
      edge.priority = 1.0;
    } else {
      edge.priority =
          edge.parent == root ? 1.0 : std::fma(2.0, tree.edge(edge.parent).priority, 1.0);
    }
    p.push_scored(e);
    // Estimated from the edge's rho and the time at its end; refined on the chosen edge below.
    const double cost = edge.rho_m + p.cost_speed_ * p.step_time(tree.end_step(e));
    if (tree.end_step(e) >= p.horizon_step_ && cost < best_edge_cost) {
      best_edge_cost = cost;
      best_edge = e;
    }
  }
  if (best_edge != root) {
    const Edge& edge = tree.edge(best_edge);
    for (int k = edge.first + 1; k <= edge.last; ++k) {
      const auto index = static_cast<std::uint16_t>(k);
      const double rho = p.rho_m(tree.state(edge.trajectory, index));
      const std::uint32_t step = tree.step_of(best_edge, index);
      const double cost = rho + p.cost_speed_ * p.step_time(step);
      if (step >= p.horizon_step_ && cost < p.best_cost_m_) {
        p.best_cost_m_ = cost;
        p.best_rho_ = rho;
        p.best_ = TreeState{best_edge, index};
      }
    }
  }
  // The solution: the earliest goal state among the edges kept (all lead to F when one does).
  for (const EdgeHandle e : order_) {
    if (keep_[e] == 0 || e == root) continue;
    const Edge& edge = tree.edge(e);
    for (int k = edge.first + 1; k <= edge.last; k += static_cast<int>(rescore_stride_)) {
      const typename V::State& qk = tree.state(edge.trajectory, static_cast<std::uint32_t>(k));
      if (!p.in_goal_region(qk)) continue;
      // Back to the first state of this edge in F, between the samples.
      while (k > edge.first + 1) {
        const typename V::State& earlier =
            tree.state(edge.trajectory, static_cast<std::uint32_t>(k - 1));
        if (!p.in_goal_region(earlier)) break;
        --k;
      }
      p.offer_solution(TreeState{e, static_cast<std::uint16_t>(k)});
      break;
    }
  }
  if (const TreeState s = kept_goal_state(p, known_solution); s.edge != kNoHandle) {
    p.offer_solution(s);
  }
}

template class Retainment<DdVelocity>;
template class Retainment<DdAcceleration>;
template class Retainment<Car>;

}  // namespace grip
