// Tree retainment (Algorithm 1, first half): re-rooting, pruning by the map, safety at the new
// T, pruning paths not leading to F, priority reset, heap rebuild and pool accounting.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <vector>

#include "grip/planner/contingency.hpp"
#include "grip/planner/planner.hpp"
#include "test_support.hpp"

namespace grip {
namespace {

class RetainmentTest : public ::testing::Test {
 protected:
  OccupancyGrid grid = test::walled_room(14.0);
  // Uniform controls: the tree sizes below are chosen so that it has not reached the goal yet
  // (controls aimed at a velocity get there within 60 edges), since retainment prunes paths
  // off the goal once one reaches it.
  DdAcceleration robot = DdAcceleration::create({.velocity_target_share = 0.0}).value();
  PlannerConfig config;
  std::optional<Planner<DdAcceleration>> planner;
  Goal goal = Goal::disk(11.5, 11.5, 1.0);

  void SetUp() override {
    config.steps_per_record = 1;  // the replanning configuration
    config.stop_at_goal = false;
    config.max_edges = 20'000;
    config.max_trajectories = 10'000;
    config.seed = 4;
    planner.emplace(Planner<DdAcceleration>::create(robot, grid, config).value());
    ASSERT_TRUE(planner->set_problem(robot.rest_state(2, 2, 0.7), goal));
  }
  // Adds `edges` edges, or gives up after 50 iterations per edge (a cornered tree).
  void grow(std::uint64_t edges) {
    const std::uint64_t target = planner->stats().edges_added + edges;
    const std::uint64_t give_up = planner->stats().iterations + 50 * edges;
    (void)planner->solve([&] {
      return planner->stats().edges_added >= target || planner->stats().iterations >= give_up;
    });
  }
  // Edges in the subtree below (and including) e, by a walk of the child lists.
  std::uint32_t subtree_size(EdgeHandle e) const {
    std::uint32_t n = 1;
    for (EdgeHandle c = planner->tree().edge(e).first_child; c != kNoHandle;
         c = planner->tree().edge(c).next_sibling) {
      n += subtree_size(c);
    }
    return n;
  }
  // Every in-use edge is reachable from the root and every trajectory in use is referenced.
  void expect_pools_consistent() const {
    const auto& tree = planner->tree();
    EXPECT_EQ(subtree_size(tree.root()), tree.edge_count());
    std::set<TrajectoryHandle> referenced;
    planner->visit_edges([&](EdgeHandle, const Edge& e) { referenced.insert(e.trajectory); });
    EXPECT_EQ(referenced.size(), tree.trajectory_count());
    EXPECT_EQ(planner->heap_size(), tree.edge_count());
  }
  TreeState state_along_best(std::uint32_t step) const {
    return planner->state_at_step(planner->best_state(), step);
  }
};

TEST_F(RetainmentTest, ReRootingKeepsExactlyTheSubtreeBelowTheNewRootAndShiftsItsTimes) {
  grow(60);
  ASSERT_FALSE(planner->solved());  // else retainment would also prune paths off the goal
  // The deepest state of the tree, and the state 20 steps along the path to it.
  TreeState best;
  std::uint32_t best_step = 0;
  planner->visit_edges([&](EdgeHandle h, const Edge& edge) {
    if (planner->tree().end_step(h) > best_step) {
      best_step = planner->tree().end_step(h);
      best = TreeState{h, edge.last};
    }
  });
  ASSERT_GT(best_step, 40U);
  const TreeState new_root = planner->state_at_step(best, 20);
  ASSERT_NE(new_root.edge, kNoHandle);
  const auto root_state = planner->tree().edge_state(new_root.edge, new_root.index);
  // The subtree below the new root: the rest of its edge, plus the edge's children.
  const Edge& e = planner->tree().edge(new_root.edge);
  const std::uint32_t expected = subtree_size(new_root.edge) + (new_root.index == e.last ? 0 : 1);
  const auto best_state = planner->tree().edge_state(best.edge, best.index);

  const RetainStatus status = planner->retain(new_root, goal, 100.0);  // T beyond every path
  ASSERT_EQ(status, RetainStatus::kOk) << retain_status_name(status);

  const TreeState root = planner->root_state();
  EXPECT_EQ(planner->tree().edge_state(root.edge, root.index), root_state);
  EXPECT_EQ(planner->tree().edge_count(), expected);
  EXPECT_EQ(planner->last_retain().edges_kept, expected);
  // The deepest state is still in the tree, 20 steps closer in time.
  bool found = false;
  planner->visit_edges([&](EdgeHandle h, const Edge& edge) {
    if (planner->tree().edge_state(h, edge.last) == best_state) {
      found = true;
      EXPECT_EQ(planner->tree().end_step(h), best_step - 20);
    }
  });
  EXPECT_TRUE(found);
  expect_pools_consistent();
}

TEST_F(RetainmentTest, EdgesTheNewMapInvalidatesAreCutAndWhatStaysIsCollisionFree) {
  grow(1500);
  // A newly sensed obstacle across the middle of the room.
  grid.fill_rect(4.0, 0.3, 5.0, 9.0, Cell::kObstacle);
  ASSERT_EQ(planner->retain(planner->root_state(), goal, 100.0), RetainStatus::kOk);
  EXPECT_GT(planner->last_retain().cut_by_map, 0U);
  std::size_t states = 0;
  planner->visit_edges([&](EdgeHandle, const Edge& edge) {
    for (int k = edge.first; k <= edge.last; ++k) {
      const auto& q = planner->tree().state(edge.trajectory, static_cast<std::uint32_t>(k));
      EXPECT_TRUE(planner->chassis_free(q));
      ++states;
    }
  });
  EXPECT_GT(states, 100U);
  expect_pools_consistent();
}

TEST_F(RetainmentTest, EveryStateReachedAtTheNewTCanBrakeSafely) {
  grow(2000);
  grid.fill_rect(6.0, 6.0, 7.0, 13.7, Cell::kObstacle);
  const double horizon_s = 3.0;
  ASSERT_EQ(planner->retain(planner->root_state(), goal, horizon_s), RetainStatus::kOk);
  const auto horizon =
      static_cast<std::uint32_t>(std::lround(horizon_s / config.integration_step_s));
  std::size_t crossing = 0;
  planner->visit_edges([&](EdgeHandle h, const Edge& edge) {
    if (h == planner->tree().root()) return;
    for (int k = edge.first + 1; k <= edge.last; ++k) {
      if (planner->tree().step_of(h, static_cast<std::uint16_t>(k)) != horizon) continue;
      ++crossing;
      std::uint64_t checks = 0;
      EXPECT_TRUE(contingency_is_collision_free(
          robot, planner->checker(),
          planner->tree().state(edge.trajectory, static_cast<std::uint32_t>(k)),
          config.integration_step_s, checks));
    }
  });
  EXPECT_GT(crossing, 0U);
}

TEST_F(RetainmentTest, OnceAPathReachesTheGoalOnlyPathsToTheGoalAreKept) {
  (void)planner->solve([&] { return planner->solved() || planner->stats().edges_added > 15'000; });
  ASSERT_TRUE(planner->solved());
  grow(300);
  ASSERT_EQ(planner->retain(planner->root_state(), goal, 100.0), RetainStatus::kOk);
  EXPECT_GT(planner->last_retain().pruned_off_goal, 0U);
  ASSERT_TRUE(planner->solved());
  // Every leaf ends a path that passes through the goal region.
  std::size_t leaves = 0;
  planner->visit_edges([&](EdgeHandle h, const Edge& edge) {
    if (edge.first_child != kNoHandle) return;
    ++leaves;
    bool through_goal = false;
    planner->visit_path(TreeState{h, edge.last}, [&](const auto& q) {
      through_goal = through_goal || goal.contains(q[0], q[1]);
    });
    EXPECT_TRUE(through_goal);
  });
  EXPECT_GT(leaves, 0U);
  expect_pools_consistent();
}

TEST_F(RetainmentTest, PrioritiesAreResetByEq2AndScoresUseTheNewTarget) {
  grow(800);
  const Goal new_goal = Goal::disk(2.0, 11.5, 1.0);
  ASSERT_EQ(planner->retain(planner->root_state(), new_goal, 100.0), RetainStatus::kOk);
  const auto& tree = planner->tree();
  const EdgeHandle root = tree.root();
  planner->visit_edges([&](EdgeHandle h, const Edge& edge) {
    if (h == root) return;
    const double expected = edge.parent == root ? 1.0 : 2.0 * tree.edge(edge.parent).priority + 1.0;
    EXPECT_EQ(edge.priority, expected);
    // Eq. 1 over states sampled every 0.2 s back from the edge's end (4 records of 0.05 s).
    double rho = INFINITY;
    for (int k = edge.last; k >= edge.first + 1; k -= 4) {
      const auto& q = tree.state(edge.trajectory, static_cast<std::uint32_t>(k));
      rho = std::min(rho, planner->rho_field().distance_m(q[0], q[1]));
    }
    EXPECT_DOUBLE_EQ(edge.rho_m, rho);
  });
  // The heap was rebuilt: its minimum is the minimum score over the tree.
  const double top = planner->log_score(planner->peek_selection());
  planner->visit_edges([&](EdgeHandle h, const Edge&) { EXPECT_GE(planner->log_score(h), top); });
  EXPECT_EQ(planner->heap_size(), tree.edge_count());
}

TEST_F(RetainmentTest, RestartingInTheSameStateDrawsNewSamplesAndKeepsRhoOnRequest) {
  // A vehicle restarted where it stands, cycle after cycle, must not replay the samples that
  // failed there: the random stream goes on, and so do the work counters.
  const auto first_control = [&] {
    const auto& tree = planner->tree();
    const EdgeHandle child = tree.edge(tree.root()).first_child;
    EXPECT_NE(child, kNoHandle);
    return child == kNoHandle ? std::array<double, 2>{}
                              : tree.trajectory(tree.edge(child).trajectory).control;
  };
  const DdAcceleration::State start = robot.rest_state(2, 2, 0.7);
  grow(1);
  const std::array<double, 2> before = first_control();
  const std::uint64_t edges = planner->stats().edges_added;
  ASSERT_EQ(planner->restart(start, goal, 1.0, RhoUpdate::kKeep), RetainStatus::kOk);
  EXPECT_EQ(planner->tree().edge_count(), 1U);
  grow(1);
  EXPECT_NE(first_control(), before);
  EXPECT_EQ(planner->stats().edges_added, edges + 1);
  // kKeep leaves rho toward the old goal; kRecompute turns it toward the new one.
  const Goal other = Goal::disk(2.0, 11.5, 1.0);
  const double rho_here = planner->rho_field().distance_m(2.0, 11.5);
  ASSERT_EQ(planner->restart(start, other, 1.0, RhoUpdate::kKeep), RetainStatus::kOk);
  EXPECT_DOUBLE_EQ(planner->rho_field().distance_m(2.0, 11.5), rho_here);
  ASSERT_EQ(planner->restart(start, other, 1.0), RetainStatus::kOk);
  EXPECT_LT(planner->rho_field().distance_m(2.0, 11.5), 0.2);
  // A new problem replays the seed: the first sample is the first run's again.
  ASSERT_TRUE(planner->set_problem(start, goal));
  EXPECT_EQ(planner->stats().edges_added, 0U);
  grow(1);
  EXPECT_EQ(first_control(), before);
}

TEST_F(RetainmentTest, AGoalAdoptedWithItsRhoPlansAsOneWhoseRhoThePlannerComputed) {
  // GIVEN rho toward a set of cells computed outside the planner, as the target thread does
  grow(300);
  std::vector<std::uint32_t> cells;
  for (int x = 100; x < 110; ++x) cells.push_back(grid.index(x, 20));  // near (10.5, 2.05)
  DistanceField field =
      DistanceField::create(grid.width(), grid.height(), grid.resolution()).value();
  const ClearanceMap clearance = ClearanceMap::create_for(grid).value();
  field.compute(grid, clearance, cells, config.rho_clearance_m);
  Planner<DdAcceleration> computed = Planner<DdAcceleration>::create(robot, grid, config).value();
  ASSERT_TRUE(computed.set_problem(robot.rest_state(2, 2, 0.7), Goal::cells(cells)));

  // WHEN the planner adopts it with the cells and retains without recomputing
  ASSERT_EQ(planner->adopt_goal(Goal::cells(cells), field), RetainStatus::kOk);
  ASSERT_EQ(
      planner->retain(planner->root_state(), Goal::cells(cells), 1.0, nullptr, RhoUpdate::kKeep),
      RetainStatus::kOk);

  // THEN its rho is the one a planner computes itself toward those cells
  for (std::uint32_t c = 0; c < grid.cell_count(); c += 37) {
    const double x = grid.cell_center_x(grid.cell_x(c));
    const double y = grid.cell_center_y(grid.cell_y(c));
    ASSERT_DOUBLE_EQ(planner->rho_field().distance_m(x, y), computed.rho_field().distance_m(x, y))
        << x << ", " << y;
  }
  expect_pools_consistent();

  // WHEN the adopted F holds the root's own cell THEN the tree is solved at once: F is the
  // adopted cells
  EXPECT_FALSE(planner->solved());
  const auto& root =
      planner->tree().edge_state(planner->root_state().edge, planner->root_state().index);
  int rx = 0;
  int ry = 0;
  ASSERT_TRUE(grid.to_cell(root[0], root[1], rx, ry));
  const std::uint32_t here[] = {grid.index(rx, ry)};
  field.compute(grid, clearance, here, config.rho_clearance_m);
  ASSERT_EQ(planner->adopt_goal(Goal::cells(here), field), RetainStatus::kOk);
  ASSERT_EQ(
      planner->retain(planner->root_state(), Goal::cells(here), 1.0, nullptr, RhoUpdate::kKeep),
      RetainStatus::kOk);
  EXPECT_TRUE(planner->solved());

  // AND a goal without a free cell is refused, leaving F and rho as they were
  const double rho_before = planner->rho_field().distance_m(5.0, 5.0);
  grid.set(3, 3, Cell::kObstacle);
  const std::uint32_t blocked[] = {grid.index(3, 3)};
  EXPECT_EQ(planner->adopt_goal(Goal::cells(blocked), field), RetainStatus::kGoalWithoutFreeCell);
  EXPECT_DOUBLE_EQ(planner->rho_field().distance_m(5.0, 5.0), rho_before);
  // AND so is a disk: rho toward a disk is the planner's own to compute
  EXPECT_EQ(planner->adopt_goal(Goal::disk(5.0, 5.0, 1.0), field), RetainStatus::kGoalNotCells);
  EXPECT_DOUBLE_EQ(planner->rho_field().distance_m(5.0, 5.0), rho_before);
  ASSERT_EQ(
      planner->retain(planner->root_state(), Goal::cells(here), 1.0, nullptr, RhoUpdate::kKeep),
      RetainStatus::kOk);
  EXPECT_TRUE(planner->solved());
}

TEST_F(RetainmentTest, ThousandsOfCyclesLeakNothing) {
  for (int cycle = 0; cycle < 2000; ++cycle) {
    grow(40);
    TreeState next = state_along_best(1);
    if (next.edge == kNoHandle) next = planner->root_state();
    ASSERT_EQ(planner->retain(next, goal, 1.0), RetainStatus::kOk) << "cycle " << cycle;
    ASSERT_EQ(subtree_size(planner->tree().root()), planner->tree().edge_count());
  }
  expect_pools_consistent();
}

TEST_F(RetainmentTest, OnAStaticMapTheTimeToTheGoalNeverGrowsAcrossCycles) {
  (void)planner->solve([&] { return planner->solved() || planner->stats().edges_added > 15'000; });
  ASSERT_TRUE(planner->solved());
  double previous_arrival = INFINITY;
  std::uint32_t elapsed = 0;  // the root advances one step per cycle along the solution
  for (int cycle = 0; cycle < 30; ++cycle) {
    const TreeState s = planner->best_state();
    const double arrival = elapsed + planner->tree().step_of(s.edge, s.index);
    EXPECT_LE(arrival, previous_arrival) << "cycle " << cycle;
    previous_arrival = arrival;
    const TreeState next = planner->state_at_step(s, 1);
    ASSERT_NE(next.edge, kNoHandle);
    ASSERT_EQ(planner->retain(next, goal, 1.0), RetainStatus::kOk);
    ++elapsed;
    grow(100);
  }
}

TEST_F(RetainmentTest, RefusedRetainmentsLeaveTheTreeAsItWas) {
  grow(300);
  const std::uint32_t edges = planner->tree().edge_count();
  EXPECT_EQ(planner->retain(TreeState{}, goal, 1.0), RetainStatus::kRootNotInTree);
  ASSERT_EQ(planner->retain(planner->root_state(), goal, 1.0), RetainStatus::kOk);
  const std::uint32_t kept = planner->tree().edge_count();
  // Index 0 of the root's trajectory lies before the root once the tree was re-rooted.
  EXPECT_EQ(planner->retain(TreeState{planner->tree().root(), 0}, goal, 1.0),
            planner->tree().edge(planner->tree().root()).last == 0 ? RetainStatus::kOk
                                                                   : RetainStatus::kRootNotInTree);
  EXPECT_EQ(planner->retain(planner->root_state(), Goal::disk(40, 4, 1), 1.0),
            RetainStatus::kGoalOutsideGrid);
  const TreeState root = planner->root_state();
  const auto& q = planner->tree().edge_state(root.edge, root.index);
  grid.fill_rect(q[0] - 0.2, q[1] - 0.2, q[0] + 0.2, q[1] + 0.2, Cell::kObstacle);
  EXPECT_EQ(planner->retain(planner->root_state(), goal, 1.0), RetainStatus::kRootInCollision);
  EXPECT_EQ(planner->tree().edge_count(), kept);
  EXPECT_LE(kept, edges);
}

TEST(RetainmentSelection, BaselinesDoNotRetain) {
  const OccupancyGrid grid = test::walled_room(8.0);
  const auto robot = DdVelocity::create({}).value();
  PlannerConfig config;
  config.selection = Selection::kRrt;
  config.steps_per_record = 1;
  auto planner = Planner<DdVelocity>::create(robot, grid, config).value();
  const Goal goal = Goal::disk(6, 6, 0.5);
  ASSERT_TRUE(planner.set_problem(robot.rest_state(2, 2, 0), goal));
  EXPECT_EQ(planner.retain(planner.root_state(), goal, 1.0), RetainStatus::kUnsupportedSelection);
}

}  // namespace
}  // namespace grip
