#pragma once
// A state reached in the planner's tree, by the edge that records it and its index along the
// edge's trajectory, and the two operations every part of the planner needs on one: where it
// lies after splits (resolve) and a random one along an edge (random_state_along).

#include <cstdint>

#include "grip/common/random.hpp"
#include "grip/planner/tree.hpp"

namespace grip {

// A state reached in the tree: recorded state k of edge e.
struct TreeState {
  EdgeHandle edge = kNoHandle;
  std::uint16_t index = 0;
};

// s where the tree holds it now. Splitting keeps the tail under the old handle; states before
// its first index belong to the heads above it, and an edge's first state to its parent. An
// empty TreeState when s lies before the root (not in the tree).
template <typename State>
TreeState resolve(const Tree<State>& tree, TreeState s) noexcept {
  if (s.edge == kNoHandle) return s;
  while (s.index < tree.edge(s.edge).first) {
    s.edge = tree.edge(s.edge).parent;
    if (s.edge == kNoHandle) return TreeState{};
  }
  const Edge& edge = tree.edge(s.edge);
  if (s.index == edge.first && edge.parent != kNoHandle) {
    return TreeState{edge.parent, tree.edge(edge.parent).last};
  }
  return s;
}

// A random recorded state of e other than its first, which belongs to the parent (the root
// edge holds a single state). Draws one number from rng unless e holds a single state.
template <typename State>
TreeState random_state_along(const Tree<State>& tree, EdgeHandle e, Random& rng) noexcept {
  const Edge& edge = tree.edge(e);
  if (edge.first == edge.last) return TreeState{e, edge.last};
  return TreeState{e,
                   static_cast<std::uint16_t>(edge.first + 1 + rng.below(edge.last - edge.first))};
}

}  // namespace grip
