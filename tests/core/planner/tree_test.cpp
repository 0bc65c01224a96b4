#include "grip/planner/tree.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

namespace grip {
namespace {

using State = Eigen::Matrix<double, 3, 1>;

class TreeTest : public ::testing::Test {
 protected:
  // 8 edges, 4 trajectories of up to 6 states, 5 integration steps per recorded state.
  Tree<State> tree{8, 4, 6, 5};

  TrajectoryHandle straight_trajectory(const State& from, std::uint16_t states) {
    const TrajectoryHandle t = tree.acquire_trajectory();
    for (std::uint16_t k = 0; k < states; ++k) tree.state(t, k) = from + State(k, 0, 0);
    tree.trajectory(t).state_count = states;
    return t;
  }
};

TEST_F(TreeTest, ResetMakesARootEdgeHoldingOnlyTheStartState) {
  const EdgeHandle root = tree.reset(State(1, 2, 0));
  EXPECT_EQ(tree.edge_count(), 1U);
  EXPECT_EQ(tree.trajectory_count(), 1U);
  EXPECT_EQ(tree.edge(root).first, tree.edge(root).last);
  EXPECT_EQ(tree.edge(root).parent, kNoHandle);
  EXPECT_EQ(tree.edge_state(root, 0), State(1, 2, 0));
  EXPECT_EQ(tree.end_step(root), 0U);
}

TEST_F(TreeTest, AddedChildStartsWhereItsParentEndsInTime) {
  const EdgeHandle root = tree.reset(State(0, 0, 0));
  const TrajectoryHandle t = straight_trajectory(State(0, 0, 0), 5);
  const EdgeHandle child = tree.add_child(root, t, 4);
  EXPECT_EQ(tree.edge(child).parent, root);
  EXPECT_EQ(tree.edge(root).first_child, child);
  EXPECT_EQ(tree.edge(child).start_step, 0U);
  EXPECT_EQ(tree.end_step(child), 20U);  // 4 records x 5 steps
  EXPECT_EQ(tree.trajectory(t).edge_refs, 1U);
}

TEST_F(TreeTest, SplittingKeepsTheTailsHandleChildrenAndSharesTheTrajectory) {
  // GIVEN root -> a (states 0..4) -> b, and a sibling c of a
  const EdgeHandle root = tree.reset(State(0, 0, 0));
  const TrajectoryHandle ta = straight_trajectory(State(0, 0, 0), 5);
  const EdgeHandle a = tree.add_child(root, ta, 4);
  const TrajectoryHandle tc = straight_trajectory(State(0, 0, 0), 3);
  const EdgeHandle c = tree.add_child(root, tc, 2);
  const TrajectoryHandle tb = straight_trajectory(State(4, 0, 0), 3);
  const EdgeHandle b = tree.add_child(a, tb, 2);
  const std::uint32_t b_start = tree.edge(b).start_step;

  // WHEN a is split at its recorded state 2
  const EdgeHandle head = tree.split(a, 2);

  // THEN the head [0, 2] takes a's place under the root and a keeps the tail [2, 4] and b
  EXPECT_EQ(tree.edge(head).parent, root);
  EXPECT_EQ(tree.edge(head).first, 0);
  EXPECT_EQ(tree.edge(head).last, 2);
  EXPECT_EQ(tree.edge(a).parent, head);
  EXPECT_EQ(tree.edge(a).first, 2);
  EXPECT_EQ(tree.edge(a).last, 4);
  EXPECT_EQ(tree.edge(a).start_step, 10U);
  EXPECT_EQ(tree.edge(head).first_child, a);
  EXPECT_EQ(tree.edge(b).parent, a);
  EXPECT_EQ(tree.edge(b).start_step, b_start);  // times below the split do not change
  EXPECT_EQ(tree.end_step(a), tree.edge(b).start_step);
  // c is still a sibling of the edge that now starts at the root
  EXPECT_EQ(tree.edge(root).first_child, c);
  EXPECT_EQ(tree.edge(c).next_sibling, head);
  EXPECT_EQ(tree.edge(head).prev_sibling, c);
  EXPECT_EQ(tree.trajectory(ta).edge_refs, 2U);
  EXPECT_EQ(tree.edge_count(), 5U);
  EXPECT_EQ(tree.trajectory_count(), 4U);  // no state was copied
}

TEST_F(TreeTest, RoomForAPropagationNeedsATrajectoryAndTwoEdgeRecords) {
  const EdgeHandle root = tree.reset(State(0, 0, 0));
  EXPECT_TRUE(tree.has_room_for_propagation());
  for (int i = 0; i < 3; ++i) tree.add_child(root, straight_trajectory(State(0, 0, 0), 2), 1);
  // 4 trajectories used of 4: no room although edge records remain
  EXPECT_EQ(tree.trajectory_count(), 4U);
  EXPECT_FALSE(tree.has_room_for_propagation());
  EXPECT_EQ(tree.acquire_trajectory(), kNoHandle);
}

TEST_F(TreeTest, ReleasedTrajectoryReturnsToThePool) {
  tree.reset(State(0, 0, 0));
  const TrajectoryHandle t = tree.acquire_trajectory();
  ASSERT_NE(t, kNoHandle);
  EXPECT_EQ(tree.trajectory_count(), 2U);
  tree.release_trajectory(t);
  EXPECT_EQ(tree.trajectory_count(), 1U);
}

}  // namespace
}  // namespace grip
