#pragma once
// The planner's tree (the paper's Sec. III): edges are trajectory segments, not points. A
// propagation produces one trajectory (its control and the states recorded along it); splitting an
// edge at a state makes two edges that share that trajectory, so no state is copied.
//
// All storage is reserved at construction; operations never allocate. Handles are 32-bit pool
// indices. The tree is generic over the state type only.

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>

#include "grip/common/assert.hpp"
#include "grip/memory/object_pool.hpp"

namespace grip {

using EdgeHandle = std::uint32_t;
using TrajectoryHandle = std::uint32_t;
inline constexpr std::uint32_t kNoHandle = 0xFFFF'FFFF;

struct Edge {
  TrajectoryHandle trajectory = kNoHandle;
  std::uint16_t first = 0;  // recorded states [first, last] of the trajectory
  std::uint16_t last = 0;
  EdgeHandle parent = kNoHandle;  // the edge ending where this one starts
  EdgeHandle first_child = kNoHandle;
  EdgeHandle next_sibling = kNoHandle;
  EdgeHandle prev_sibling = kNoHandle;
  std::uint32_t start_step = 0;  // integration steps from the root to state `first`
  double priority = 1.0;         // p(e), Eq. 2
  double rho_m = 0.0;            // rho(e, F), Eq. 1
};

struct Trajectory {
  std::array<double, 2> control{};  // held constant along the trajectory
  std::uint16_t state_count = 0;
  std::uint16_t edge_refs = 0;  // edges sharing this trajectory
};

template <typename State>
class Tree {
 public:
  Tree(std::uint32_t max_edges, std::uint32_t max_trajectories, std::uint32_t states_per_trajectory,
       std::uint32_t steps_per_record)
      : edges_(max_edges),
        trajectories_(max_trajectories),
        states_per_trajectory_(states_per_trajectory),
        steps_per_record_(steps_per_record),
        states_(new State[static_cast<std::size_t>(max_trajectories) * states_per_trajectory]) {
    // Every page is written here, at start-up, not in the planning loop: value-initialisation
    // alone would not do it for a state type with its own default constructor (Eigen's leaves
    // its coefficients unset), and the first propagations would take the page faults.
    static_assert(std::is_trivially_destructible_v<State>);
    std::memset(static_cast<void*>(states_.get()), 0,
                sizeof(State) * max_trajectories * states_per_trajectory);
  }

  // Clears the tree and makes a root edge holding the single state q (zero duration).
  EdgeHandle reset(const State& q) noexcept {
    edges_.clear();
    trajectories_.clear();
    const TrajectoryHandle t = trajectories_.acquire();
    GRIP_ASSERT(t != kNoHandle);
    trajectories_[t] = Trajectory{};
    trajectories_[t].state_count = 1;
    trajectories_[t].edge_refs = 1;
    state(t, 0) = q;
    root_ = edges_.acquire();
    GRIP_ASSERT(root_ != kNoHandle);
    edges_[root_] = Edge{};
    edges_[root_].trajectory = t;
    return root_;
  }

  // Room for one more propagation: a trajectory and two edge records, keeping one record in
  // reserve so that re-rooting (tree retainment) can always split an edge.
  bool has_room_for_propagation() const noexcept {
    return edges_.used() + 3 <= edges_.capacity() &&
           trajectories_.used() + 1 <= trajectories_.capacity();
  }

  TrajectoryHandle acquire_trajectory() noexcept {
    const TrajectoryHandle t = trajectories_.acquire();
    if (t != kNoHandle) trajectories_[t] = Trajectory{};
    return t;
  }
  void release_trajectory(TrajectoryHandle t) noexcept {
    GRIP_ASSERT(trajectories_[t].edge_refs == 0);
    trajectories_.release(t);
  }

  // Splits e at recorded state k (first < k < last). The head [first, k] becomes a new edge
  // that takes e's place under its parent; e keeps the tail [k, last] and its children, so
  // handles held elsewhere (the heap, descendants) stay valid. Returns the head.
  EdgeHandle split(EdgeHandle e, std::uint16_t k) noexcept {
    Edge& tail = edges_[e];
    GRIP_ASSERT(tail.first < k && k < tail.last);
    const EdgeHandle h = edges_.acquire();
    GRIP_ASSERT(h != kNoHandle);
    Edge& head = edges_[h];
    head = tail;
    head.last = k;
    head.first_child = e;
    head.next_sibling = tail.next_sibling;
    head.prev_sibling = tail.prev_sibling;
    if (head.prev_sibling != kNoHandle) edges_[head.prev_sibling].next_sibling = h;
    if (head.next_sibling != kNoHandle) edges_[head.next_sibling].prev_sibling = h;
    if (head.parent != kNoHandle && edges_[head.parent].first_child == e) {
      edges_[head.parent].first_child = h;
    }
    tail.start_step += static_cast<std::uint32_t>(k - tail.first) * steps_per_record_;
    tail.first = k;
    tail.parent = h;
    tail.next_sibling = kNoHandle;
    tail.prev_sibling = kNoHandle;
    ++trajectories_[tail.trajectory].edge_refs;
    return h;
  }

  // Adds an edge covering states [0, last] of trajectory t as a child of `parent`.
  EdgeHandle add_child(EdgeHandle parent, TrajectoryHandle t, std::uint16_t last) noexcept {
    const EdgeHandle e = edges_.acquire();
    GRIP_ASSERT(e != kNoHandle);
    Edge& edge = edges_[e];
    edge = Edge{};
    edge.trajectory = t;
    edge.first = 0;
    edge.last = last;
    edge.parent = parent;
    edge.start_step = end_step(parent);
    edge.next_sibling = edges_[parent].first_child;
    if (edge.next_sibling != kNoHandle) edges_[edge.next_sibling].prev_sibling = e;
    edges_[parent].first_child = e;
    ++trajectories_[t].edge_refs;
    return e;
  }

  // Removes e from its parent's list of children (its own subtree stays attached to it).
  void unlink(EdgeHandle e) noexcept {
    Edge& edge = edges_[e];
    if (edge.prev_sibling != kNoHandle) {
      edges_[edge.prev_sibling].next_sibling = edge.next_sibling;
    } else if (edge.parent != kNoHandle) {
      edges_[edge.parent].first_child = edge.next_sibling;
    }
    if (edge.next_sibling != kNoHandle) edges_[edge.next_sibling].prev_sibling = edge.prev_sibling;
    edge.parent = kNoHandle;
    edge.next_sibling = kNoHandle;
    edge.prev_sibling = kNoHandle;
  }

  // Returns e to the pool, and its trajectory once no edge shares it. Links are not repaired:
  // the caller releases whole subtrees or unlinks first.
  void release_edge(EdgeHandle e) noexcept {
    const TrajectoryHandle t = edges_[e].trajectory;
    GRIP_ASSERT(trajectories_[t].edge_refs > 0);
    if (--trajectories_[t].edge_refs == 0) trajectories_.release(t);
    edges_.release(e);
  }

  // Makes the detached edge e, reduced to its last state, the root (tree retainment).
  void make_root(EdgeHandle e) noexcept {
    Edge& edge = edges_[e];
    GRIP_ASSERT(edge.parent == kNoHandle);
    edge.first = edge.last;
    edge.start_step = 0;
    root_ = e;
  }

  // Integration steps from the root to e's last state.
  std::uint32_t end_step(EdgeHandle e) const noexcept {
    const Edge& edge = edges_[e];
    return edge.start_step + static_cast<std::uint32_t>(edge.last - edge.first) * steps_per_record_;
  }
  std::uint32_t step_of(EdgeHandle e, std::uint16_t k) const noexcept {
    const Edge& edge = edges_[e];
    return edge.start_step + static_cast<std::uint32_t>(k - edge.first) * steps_per_record_;
  }

  State& state(TrajectoryHandle t, std::uint32_t k) noexcept {
    GRIP_ASSERT(k < states_per_trajectory_);
    return states_[static_cast<std::size_t>(t) * states_per_trajectory_ + k];
  }
  const State& state(TrajectoryHandle t, std::uint32_t k) const noexcept {
    GRIP_ASSERT(k < states_per_trajectory_);
    return states_[static_cast<std::size_t>(t) * states_per_trajectory_ + k];
  }
  const State& edge_state(EdgeHandle e, std::uint16_t k) const noexcept {
    return state(edges_[e].trajectory, k);
  }

  Edge& edge(EdgeHandle e) noexcept { return edges_[e]; }
  const Edge& edge(EdgeHandle e) const noexcept { return edges_[e]; }
  Trajectory& trajectory(TrajectoryHandle t) noexcept { return trajectories_[t]; }
  const Trajectory& trajectory(TrajectoryHandle t) const noexcept { return trajectories_[t]; }
  bool contains(EdgeHandle e) const noexcept { return e < edges_.capacity() && edges_.in_use(e); }

  EdgeHandle root() const noexcept { return root_; }
  std::uint32_t edge_count() const noexcept { return edges_.used(); }
  std::uint32_t edge_capacity() const noexcept { return edges_.capacity(); }
  std::uint32_t trajectory_count() const noexcept { return trajectories_.used(); }
  std::uint32_t trajectory_capacity() const noexcept { return trajectories_.capacity(); }
  std::uint32_t states_per_trajectory() const noexcept { return states_per_trajectory_; }

 private:
  ObjectPool<Edge> edges_;
  ObjectPool<Trajectory> trajectories_;
  std::uint32_t states_per_trajectory_;
  std::uint32_t steps_per_record_;
  std::unique_ptr<State[]> states_;
  EdgeHandle root_ = kNoHandle;
};

}  // namespace grip
