// Path selection by the visibility/length weight of the paper's Sec. IV, on a real planner tree:
// the selector's choice is the brute-force minimum over every root-to-state trajectory, the
// trajectory that sees the frontier beats shorter ones that see nothing, and T is honoured.

#include "grip/exploration/path_selector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "grip/exploration/frontier.hpp"

namespace grip {
namespace {

// A room of 8 m x 6 m; a wall from the bottom up to y = 2.5 at x = 5; an unknown pocket in the
// bottom-right corner, out of sight from the robot's side below the wall's end.
OccupancyGrid pocket_room() {
  OccupancyGrid grid = OccupancyGrid::create(80, 60, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.3, 0.3, 7.7, 5.7, Cell::kFree);
  grid.fill_rect(4.85, 0.0, 5.15, 2.5, Cell::kObstacle);
  grid.fill_rect(6.01, 0.31, 7.69, 1.49, Cell::kUnknown);
  return grid;
}

struct Reference {
  double weight = std::numeric_limits<double>::infinity();
  double length_m = 0.0;
  double d_m = 0.0;
};

class PathSelectorTest : public ::testing::Test {
 protected:
  OccupancyGrid grid = pocket_room();
  // Uniform speeds: the small trees of these tests stay near their root.
  DdVelocity robot = DdVelocity::create([] {
                       DdVelocityParams p;
                       p.top_speed_share = 0.0;
                       return p;
                     }())
                         .value();
  std::optional<DdVelocityPlanner> planner;
  std::optional<FrontierMap> frontiers;
  std::optional<PathSelector> selector;
  PathSelectionConfig config;

  void SetUp() override {
    PlannerConfig pc;
    pc.max_edges = 4000;
    pc.max_trajectories = 2000;
    pc.stop_at_goal = false;
    planner.emplace(DdVelocityPlanner::create(robot, grid, pc).value());
    frontiers.emplace(FrontierMap::create(80, 60, 0.1, FrontierConfig{}).value());
    // Every recorded state is sampled, so that the brute force below sees the same states.
    config.sample_step_s = pc.record_step_s();
    selector.emplace(PathSelector::create(80, 60, 0.1, pc.max_edges, config).value());
  }
  void grow(double x, double y, std::uint64_t edges) {
    ASSERT_EQ(frontiers->update(grid, planner->checker().clearance(), x, y),
              ExplorationStatus::kTarget);
    ASSERT_TRUE(planner->set_problem(robot.rest_state(x, y, 0.0),
                                     Goal::cells(frontiers->approach_cells())));
    (void)planner->solve([&] { return planner->stats().edges_added >= edges; });
    selector->set_target(grid, frontiers->target_cells());
  }
  std::uint32_t seen_at(double x, double y) const {
    int cx = 0;
    int cy = 0;
    return grid.to_cell(x, y, cx, cy) ? selector->seen_from(grid.index(cx, cy)) : 0U;
  }
  // Section 3's weight of the trajectory to s, computed from scratch over its recorded states.
  Reference reference(TreeState s, bool by_sight) const {
    const std::span<const std::uint32_t> targets = selector->target_cells();
    std::vector<double> d(targets.size(), config.sensing_radius_m);
    Reference r;
    bool first = true;
    double px = 0.0;
    double py = 0.0;
    planner->visit_path(s, [&](const DdVelocity::State& q) {
      if (!first) r.length_m += std::hypot(q[0] - px, q[1] - py);
      first = false;
      px = q[0];
      py = q[1];
      const std::uint32_t mask = seen_at(q[0], q[1]);
      for (std::size_t i = 0; i < targets.size(); ++i) {
        if (((mask >> i) & 1U) == 0) continue;
        const double cx = grid.cell_center_x(grid.cell_x(targets[i]));
        const double cy = grid.cell_center_y(grid.cell_y(targets[i]));
        d[i] = std::min(d[i], std::hypot(q[0] - cx, q[1] - cy));
      }
    });
    // A cell the trajectory does not see: d_max beyond rho from its end.
    const double rho_end = planner->rho_field().distance_m(px, py);
    r.d_m = 0.0;
    for (const double v : d) r.d_m += v < config.sensing_radius_m ? v : v + rho_end;
    if (!by_sight) r.d_m = rho_end;
    r.weight = r.d_m * std::exp(config.length_weight_per_m * r.length_m);
    return r;
  }
  // Every state of the tree (TreeState) with its step from the root.
  template <typename F>
  void for_each_state(F&& f) const {
    planner->visit_edges([&](EdgeHandle e, const Edge& edge) {
      const int first = edge.parent == kNoHandle ? edge.last : edge.first + 1;
      for (int k = first; k <= edge.last; ++k) {
        const auto index = static_cast<std::uint16_t>(k);
        f(TreeState{e, index}, planner->tree().step_of(e, index));
      }
    });
  }
  bool tree_sees_target() const {
    bool seen = false;
    for_each_state([&](TreeState s, std::uint32_t) {
      const auto& q = planner->tree().edge_state(s.edge, s.index);
      seen = seen || seen_at(q[0], q[1]) != 0;
    });
    return seen;
  }
};

TEST_F(PathSelectorTest, CellsSeeATargetOnlyInRangeAndInSight) {
  const std::uint32_t target = grid.index(60, 16);  // the pocket's top frontier, x = 6.05
  ASSERT_EQ(grid.at(target), Cell::kFree);
  const std::uint32_t cells[] = {target};
  selector->set_target(grid, cells);
  ASSERT_EQ(selector->target_cells().size(), 1U);
  EXPECT_EQ(seen_at(6.05, 3.0), 1U);  // open space above, 1.4 m
  EXPECT_EQ(seen_at(4.5, 3.5), 1U);   // over the wall's end, 2.5 m
  EXPECT_EQ(seen_at(4.0, 1.6), 0U);   // behind the wall, 2 m
  EXPECT_EQ(seen_at(6.05, 5.5), 0U);  // in sight but 3.9 m away: beyond d_max
  EXPECT_EQ(seen_at(6.5, 1.0), 0U);   // inside the unknown pocket
  // A new target forgets the old one.
  const std::uint32_t other[] = {grid.index(10, 50)};
  selector->set_target(grid, other);
  EXPECT_EQ(seen_at(6.05, 3.0), 0U);
  EXPECT_EQ(seen_at(1.0, 5.0), 1U);
}

TEST_F(PathSelectorTest, LongFrontiersAreSubsampledEvenly) {
  std::vector<std::uint32_t> cells;
  for (int x = 3; x < 77; ++x) cells.push_back(grid.index(x, 56));
  selector->set_target(grid, cells);
  const auto targets = selector->target_cells();
  ASSERT_EQ(targets.size(), PathSelector::kMaxTargetCells);
  EXPECT_LT(grid.cell_x(targets.front()), 6);
  EXPECT_GT(grid.cell_x(targets.back()), 73);
  for (std::size_t i = 1; i < targets.size(); ++i) {
    EXPECT_GT(grid.cell_x(targets[i]), grid.cell_x(targets[i - 1]));
  }
}

TEST_F(PathSelectorTest, TheChoiceIsTheMinimumWeightTrajectoryOfAtLeastT) {
  grow(2.0, 1.0, 1500);
  ASSERT_TRUE(tree_sees_target());
  const std::uint32_t min_step = 20;  // 1 s
  const PathChoice choice = selector->select(*planner, min_step);
  ASSERT_NE(choice.state.edge, kNoHandle);
  EXPECT_TRUE(choice.sees_target);
  EXPECT_GE(planner->tree().step_of(choice.state.edge, choice.state.index), min_step);

  double best = std::numeric_limits<double>::infinity();
  for_each_state([&](TreeState s, std::uint32_t step) {
    if (step >= min_step) best = std::min(best, reference(s, true).weight);
  });
  const Reference chosen = reference(choice.state, true);
  EXPECT_NEAR(choice.weight, best, 1e-5 * best);
  EXPECT_NEAR(chosen.weight, best, 1e-5 * best);
  EXPECT_NEAR(choice.d_m, chosen.d_m, 1e-4);
  EXPECT_NEAR(choice.length_m, chosen.length_m, 1e-4);
}

TEST_F(PathSelectorTest, ATrajectoryThatSeesTheFrontierBeatsShorterOnesThatSeeNothing) {
  grow(2.0, 1.0, 1500);
  const PathChoice choice = selector->select(*planner, 20);
  const double nothing_seen =
      config.sensing_radius_m * static_cast<double>(selector->target_cells().size());
  ASSERT_LT(choice.d_m, nothing_seen);
  // Its trajectory passes a state that sees the frontier.
  bool sees = false;
  planner->visit_path(choice.state,
                      [&](const DdVelocity::State& q) { sees = sees || seen_at(q[0], q[1]) != 0; });
  EXPECT_TRUE(sees);
  // And shorter trajectories of at least T that see nothing exist, and lost.
  int shorter_blind = 0;
  for_each_state([&](TreeState s, std::uint32_t step) {
    if (step < 20) return;
    const Reference r = reference(s, true);
    if (r.length_m < choice.length_m && r.d_m >= nothing_seen - 1e-9) ++shorter_blind;
  });
  EXPECT_GT(shorter_blind, 0);
}

TEST_F(PathSelectorTest, WhenNoStateSeesTheFrontierRhoAtTheEndDecides) {
  grow(1.0, 1.0, 4);  // a small tree near the start, far from the pocket
  ASSERT_FALSE(tree_sees_target());
  const PathChoice choice = selector->select(*planner, 10);
  ASSERT_NE(choice.state.edge, kNoHandle);
  EXPECT_FALSE(choice.sees_target);
  // The least weight among the trajectories that end closer to F than the root.
  const double root_rho = planner->rho_field().distance_m(1.0, 1.0);
  double best = std::numeric_limits<double>::infinity();
  for_each_state([&](TreeState s, std::uint32_t step) {
    const Reference r = reference(s, false);
    if (step >= 10 && r.d_m < root_rho) best = std::min(best, r.weight);
  });
  EXPECT_NEAR(choice.weight, best, 1e-9 * best);
  EXPECT_NEAR(choice.d_m, reference(choice.state, false).d_m, 1e-9);
  EXPECT_LT(choice.d_m, root_rho);
}

TEST_F(PathSelectorTest, WhenNoTrajectoryGetsCloserToTheTargetThereIsNoChoice) {
  // GIVEN a tree none of whose trajectories sees the frontier or ends closer to F than the
  // root: F is the root's own cell (rho 0 there)
  ASSERT_EQ(frontiers->update(grid, planner->checker().clearance(), 1.0, 1.0),
            ExplorationStatus::kTarget);
  int cx = 0;
  int cy = 0;
  ASSERT_TRUE(grid.to_cell(1.0, 1.0, cx, cy));
  const std::uint32_t here[] = {grid.index(cx, cy)};
  ASSERT_TRUE(planner->set_problem(robot.rest_state(1.0, 1.0, 0.0), Goal::cells(here)));
  (void)planner->solve([&] { return planner->stats().edges_added >= 4; });
  selector->set_target(grid, frontiers->target_cells());
  ASSERT_FALSE(tree_sees_target());
  std::uint32_t deepest = 0;
  for_each_state([&](TreeState, std::uint32_t step) { deepest = std::max(deepest, step); });
  ASSERT_GT(deepest, 10U);
  // WHEN a trajectory is chosen THEN there is none: creeping along the shortest one would be
  // the choice otherwise, and the vehicle is to stop and let the tree grow instead
  EXPECT_EQ(selector->select(*planner, 10).state.edge, kNoHandle);
}

TEST_F(PathSelectorTest, NoTrajectoryLastingTMeansNoChoice) {
  grow(2.0, 1.0, 200);
  std::uint32_t deepest = 0;
  for_each_state([&](TreeState, std::uint32_t step) { deepest = std::max(deepest, step); });
  EXPECT_NE(selector->select(*planner, deepest).state.edge, kNoHandle);
  EXPECT_EQ(selector->select(*planner, deepest + 1).state.edge, kNoHandle);
}

// A corridor 16 m long whose far end is unknown: a tree that has just come within sensing range
// of the frontier sees only the few cells straight ahead, at the edge of the range. Standing
// still must not be the best choice then (with d_max alone for an unseen cell it was: the
// trajectory's length cost more than the few cells gained, and the robot stalled).
TEST(PathSelectorFromAfar, SeeingAFewFrontierCellsStillMovesTowardThem) {
  OccupancyGrid grid = OccupancyGrid::create(160, 30, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.3, 0.3, 15.7, 2.7, Cell::kFree);
  grid.fill_rect(14.0, 0.3, 15.7, 2.7, Cell::kUnknown);
  const DdVelocity robot = DdVelocity::create({}).value();
  PlannerConfig pc;
  pc.max_edges = 4000;
  pc.max_trajectories = 2000;
  pc.stop_at_goal = false;
  auto planner = DdVelocityPlanner::create(robot, grid, pc).value();
  auto frontiers = FrontierMap::create(160, 30, 0.1, FrontierConfig{}).value();
  PathSelectionConfig config;
  auto selector = PathSelector::create(160, 30, 0.1, pc.max_edges, config).value();
  ASSERT_EQ(frontiers.update(grid, planner.checker().clearance(), 1.0, 1.5),
            ExplorationStatus::kTarget);
  ASSERT_TRUE(planner.set_problem(robot.rest_state(1.0, 1.5, 0.0),
                                  Goal::cells(frontiers.approach_cells())));
  selector.set_target(grid, frontiers.target_cells());
  // Grow until the first tree state sees a target cell.
  PathChoice choice;
  for (std::uint64_t edges = 20; edges <= 4000 && !choice.sees_target; edges += 20) {
    (void)planner.solve([&] { return planner.stats().edges_added >= edges; });
    choice = selector.select(planner, 20);
  }
  ASSERT_TRUE(choice.sees_target) << "the tree never came within sight of the frontier";
  const auto& end = planner.tree().edge_state(choice.state.edge, choice.state.index);
  EXPECT_GT(end[0], 8.0) << "chose a trajectory of " << choice.length_m << " m ending at ("
                         << end[0] << ", " << end[1] << ")";
}

// A map finer than d_max / kMaxSightRadius: sight is decided on blocks of map cells. 12 m x 6 m
// at 2 cm, d_max 4 m (200 cells: blocks of 4), a wall at x = 6 m from the bottom to y = 4 m,
// the target at (7, 1) right of it. Open space in range on the target's side is seen, the
// wall's shadow is not, nor is anything beyond d_max.
TEST(PathSelectorOnAFineMap, SightOnBlocksStopsAtWallsAndAtTheRange) {
  const double res = 0.02;
  OccupancyGrid grid = OccupancyGrid::create(600, 300, res, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.1, 0.1, 11.9, 5.9, Cell::kFree);
  grid.fill_rect(5.95, 0.0, 6.05, 4.0, Cell::kObstacle);
  PathSelectionConfig config;
  config.sensing_radius_m = 4.0;
  auto selector = PathSelector::create(600, 300, res, 100, config).value();
  EXPECT_EQ(selector.sight_block(), 4);
  int tx = 0;
  int ty = 0;
  ASSERT_TRUE(grid.to_cell(7.0, 1.0, tx, ty));
  const std::uint32_t target[] = {grid.index(tx, ty)};
  selector.set_target(grid, target);
  int seen_open = 0;
  int shadow = 0;
  int beyond = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const double cx = grid.cell_center_x(x);
      const double cy = grid.cell_center_y(y);
      const double d = std::hypot(cx - 7.0, cy - 1.0);
      const bool seen = selector.seen_from(grid.index(x, y)) != 0;
      if (cx > 6.4 && cx < 11.6 && cy > 0.4 && cy < 5.6 && d < 3.8) {
        EXPECT_TRUE(seen) << "open cell (" << cx << ", " << cy << ") not seen";
        seen_open += seen ? 1 : 0;
      } else if (cx < 5.7 && cy < 3.5) {
        EXPECT_FALSE(seen) << "cell (" << cx << ", " << cy << ") behind the wall seen";
        ++shadow;
      } else if (d > 4.2) {
        EXPECT_FALSE(seen) << "cell (" << cx << ", " << cy << ") beyond d_max seen";
        ++beyond;
      }
    }
  }
  EXPECT_GT(seen_open, 10'000);
  EXPECT_GT(shadow, 10'000);
  EXPECT_GT(beyond, 1'000);
}

TEST(PathSelectionConfigTest, BadValuesAreRefusedByName) {
  PathSelectionConfig config;
  config.sensing_radius_m = 0.0;
  const auto made = PathSelector::create(10, 10, 0.1, 100, config);
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.error().message.find("sensing_radius_m"), std::string::npos);
  config = PathSelectionConfig{};
  config.length_weight_per_m = -0.1;
  EXPECT_FALSE(PathSelector::create(10, 10, 0.1, 100, config).ok());
  EXPECT_FALSE(PathSelector::create(10, 10, 0.1, 0, PathSelectionConfig{}).ok());
}

}  // namespace
}  // namespace grip
