// Path selection by the visibility/length weight of the paper's Sec. IV, on a real planner tree:
// the selector's choice is the brute-force minimum over every root-to-state trajectory, the
// trajectory that sees the frontier beats shorter ones that see nothing, and T is honoured.
// What sees the target is TargetSight's (target_sight_test.cpp).

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
  std::optional<TargetSight> sight;
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
    sight.emplace(selector->create_sight().value());
  }
  void grow(double x, double y, std::uint64_t edges) {
    ASSERT_EQ(frontiers->update(grid, planner->checker().clearance(), x, y),
              ExplorationStatus::kTarget);
    ASSERT_TRUE(planner->set_problem(robot.rest_state(x, y, 0.0),
                                     Goal::cells(frontiers->approach_cells())));
    (void)planner->solve([&] { return planner->stats().edges_added >= edges; });
    sight->set_target(grid, frontiers->target_cells());
  }
  std::uint32_t seen_at(double x, double y) const {
    int cx = 0;
    int cy = 0;
    return grid.to_cell(x, y, cx, cy) ? sight->seen_from(grid.index(cx, cy)) : 0U;
  }
  // Section 3's weight of the trajectory to s, computed from scratch over its recorded states.
  Reference reference(TreeState s, bool by_sight) const {
    const std::span<const std::uint32_t> targets = sight->target_cells();
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
    const double growth = std::exp(config.length_weight_per_m * r.length_m);
    if (by_sight) {
      r.weight = r.d_m * growth;
    } else {
      r.d_m = rho_end;
      r.weight = rho_end + std::min(rho_end, config.sensing_radius_m) * (growth - 1.0);
    }
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

TEST_F(PathSelectorTest, TheChoiceIsTheMinimumWeightTrajectoryOfAtLeastT) {
  grow(2.0, 1.0, 1500);
  ASSERT_TRUE(tree_sees_target());
  const std::uint32_t min_step = 20;  // 1 s
  const PathChoice choice = selector->select(*planner, *sight, min_step);
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
  const PathChoice choice = selector->select(*planner, *sight, 20);
  const double nothing_seen =
      config.sensing_radius_m * static_cast<double>(sight->target_cells().size());
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
  const PathChoice choice = selector->select(*planner, *sight, 10);
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
  sight->set_target(grid, frontiers->target_cells());
  ASSERT_FALSE(tree_sees_target());
  std::uint32_t deepest = 0;
  for_each_state([&](TreeState, std::uint32_t step) { deepest = std::max(deepest, step); });
  ASSERT_GT(deepest, 10U);
  // WHEN a trajectory is chosen THEN there is none: creeping along the shortest one would be
  // the choice otherwise, and the vehicle is to stop and let the tree grow instead
  EXPECT_EQ(selector->select(*planner, *sight, 10).state.edge, kNoHandle);
}

TEST_F(PathSelectorTest, NoTrajectoryLastingTMeansNoChoice) {
  grow(2.0, 1.0, 200);
  std::uint32_t deepest = 0;
  for_each_state([&](TreeState, std::uint32_t step) { deepest = std::max(deepest, step); });
  EXPECT_NE(selector->select(*planner, *sight, deepest).state.edge, kNoHandle);
  EXPECT_EQ(selector->select(*planner, *sight, deepest + 1).state.edge, kNoHandle);
}

// With a reference speed, l(tr) is the distance at that speed in tr's duration: of two
// trajectories that end equally well, the faster weighs less.
TEST_F(PathSelectorTest, AReferenceSpeedWeighsTheDurationInsteadOfTheLength) {
  grow(2.0, 1.0, 1500);
  const std::uint32_t min_step = 20;
  PathSelectionConfig timed = config;
  timed.reference_speed_m_s = 1.5;
  auto by_time = PathSelector::create(80, 60, 0.1, 4000, timed).value();
  auto timed_sight = by_time.create_sight().value();
  timed_sight.set_target(grid, frontiers->target_cells());
  const PathChoice choice = by_time.select(*planner, timed_sight, min_step);
  ASSERT_NE(choice.state.edge, kNoHandle);
  const double step_s = planner->config().integration_step_s;
  double minimum = std::numeric_limits<double>::infinity();
  for_each_state([&](TreeState s, std::uint32_t step) {
    if (step < min_step) return;
    const Reference r = reference(s, true);
    const double l_m = timed.reference_speed_m_s * step_s * static_cast<double>(step);
    minimum = std::min(minimum, r.d_m * std::exp(config.length_weight_per_m * l_m));
  });
  EXPECT_NEAR(choice.weight, minimum, 1e-5 * minimum);
  EXPECT_NEAR(choice.length_m,
              timed.reference_speed_m_s * step_s *
                  planner->tree().step_of(choice.state.edge, choice.state.index),
              1e-9);
  // The length chooses another trajectory on this tree: speed decided between them.
  const TreeState by_length = selector->select(*planner, *sight, min_step).state;
  EXPECT_FALSE(by_length.edge == choice.state.edge && by_length.index == choice.state.index);
}

// Whether the trajectory to s keeps the course that ends at c: s lies on the path to c, or c on
// the path to s (both resolved states).
bool keeps_course(const Tree<DdVelocity::State>& tree, TreeState s, TreeState c) {
  const auto on_path_to = [&](TreeState a, TreeState b) {  // a on the path from the root to b
    for (EdgeHandle e = b.edge; e != kNoHandle; e = tree.edge(e).parent) {
      if (e == a.edge) return e != b.edge || a.index <= b.index;
    }
    return false;
  };
  return on_path_to(s, c) || on_path_to(c, s);
}

TEST_F(PathSelectorTest, LeavingTheLastCourseCostsItsLengthInTheWeight) {
  grow(2.0, 1.0, 1500);
  const std::uint32_t min_step = 20;
  const TreeState best = selector->select(*planner, *sight, min_step).state;
  ASSERT_NE(best.edge, kNoHandle);
  // The course: the last state of a deep edge that branches off the best trajectory.
  TreeState course;
  std::uint32_t deepest = 0;
  planner->visit_edges([&](EdgeHandle e, const Edge& edge) {
    const TreeState end{e, edge.last};
    const std::uint32_t step = planner->tree().step_of(e, edge.last);
    if (edge.parent != kNoHandle && step > deepest && !keeps_course(planner->tree(), best, end)) {
      deepest = step;
      course = end;
    }
  });
  ASSERT_NE(course.edge, kNoHandle);
  for (const double change_m : {0.0, 2.0, 50.0}) {
    PathSelectionConfig with_change = config;
    with_change.course_change_m = change_m;
    auto kept = PathSelector::create(80, 60, 0.1, 4000, with_change).value();
    auto kept_sight = kept.create_sight().value();
    kept_sight.set_target(grid, frontiers->target_cells());
    const PathChoice choice = kept.select(*planner, kept_sight, min_step, course);
    ASSERT_NE(choice.state.edge, kNoHandle);
    // The brute-force minimum, a trajectory off the course weighing exp(lambda change) more.
    double minimum = std::numeric_limits<double>::infinity();
    TreeState argmin;
    for_each_state([&](TreeState s, std::uint32_t step) {
      if (step < min_step) return;
      const double off = keeps_course(planner->tree(), s, course) ? 0.0 : change_m;
      const double w = reference(s, true).weight * std::exp(config.length_weight_per_m * off);
      if (w < minimum) {
        minimum = w;
        argmin = s;
      }
    });
    EXPECT_NEAR(choice.weight, minimum, 1e-5 * minimum) << change_m;
    EXPECT_EQ(keeps_course(planner->tree(), choice.state, course),
              keeps_course(planner->tree(), argmin, course))
        << change_m;
    if (change_m == 0.0) {
      EXPECT_FALSE(keeps_course(planner->tree(), choice.state, course));
    }
    if (change_m == 50.0) {
      EXPECT_TRUE(keeps_course(planner->tree(), choice.state, course));
    }
  }
}

// A corridor length_m long and 3 m wide whose last 1.7 m are unknown, the robot at rest at
// (1, 1.5) facing along it, the target chosen and the planner's problem set.
class PathSelectorFromAfar : public ::testing::Test {
 protected:
  const DdVelocity robot = DdVelocity::create({}).value();
  std::optional<OccupancyGrid> grid;
  std::optional<DdVelocityPlanner> planner;
  std::optional<FrontierMap> frontiers;
  std::optional<PathSelector> selector;
  std::optional<TargetSight> sight;

  void build(double length_m) {
    const int width = static_cast<int>(std::lround(length_m / 0.1));
    grid.emplace(OccupancyGrid::create(width, 30, 0.1, 0.0, 0.0, Cell::kObstacle).value());
    grid->fill_rect(0.3, 0.3, length_m - 0.3, 2.7, Cell::kFree);
    grid->fill_rect(length_m - 2.0, 0.3, length_m - 0.3, 2.7, Cell::kUnknown);
    PlannerConfig pc;
    pc.max_edges = 4000;
    pc.max_trajectories = 2000;
    pc.stop_at_goal = false;
    planner.emplace(DdVelocityPlanner::create(robot, *grid, pc).value());
    frontiers.emplace(FrontierMap::create(width, 30, 0.1, FrontierConfig{}).value());
    selector.emplace(
        PathSelector::create(width, 30, 0.1, pc.max_edges, PathSelectionConfig{}).value());
    sight.emplace(selector->create_sight().value());
    ASSERT_EQ(frontiers->update(*grid, planner->checker().clearance(), 1.0, 1.5),
              ExplorationStatus::kTarget);
    ASSERT_TRUE(planner->set_problem(robot.rest_state(1.0, 1.5, 0.0),
                                     Goal::cells(frontiers->approach_cells())));
    sight->set_target(*grid, frontiers->target_cells());
  }
};

// A corridor 16 m long: a tree that has just come within sensing range of the frontier sees
// only the few cells straight ahead, at the edge of the range. Standing still must not be the
// best choice then (with d_max alone for an unseen cell it was: the trajectory's length cost
// more than the few cells gained, and the robot stalled).
TEST_F(PathSelectorFromAfar, SeeingAFewFrontierCellsStillMovesTowardThem) {
  ASSERT_NO_FATAL_FAILURE(build(16.0));
  // Grow until the first tree state sees a target cell.
  PathChoice choice;
  for (std::uint64_t edges = 20; edges <= 4000 && !choice.sees_target; edges += 20) {
    (void)planner->solve([&] { return planner->stats().edges_added >= edges; });
    choice = selector->select(*planner, *sight, 20);
  }
  ASSERT_TRUE(choice.sees_target) << "the tree never came within sight of the frontier";
  const auto& end = planner->tree().edge_state(choice.state.edge, choice.state.index);
  EXPECT_GT(end[0], 8.0) << "chose a trajectory of " << choice.length_m << " m ending at ("
                         << end[0] << ", " << end[1] << ")";
}

// A corridor 60 m long: no tree state sees the frontier, rho is about 56 m. The choice must
// head for it, not take the shortest step that ends any closer (with rho * exp(lambda l),
// beyond 20 m of rho every metre driven toward F weighs more than it gains).
TEST_F(PathSelectorFromAfar, FarFromTheFrontierTheChoiceHeadsForIt) {
  ASSERT_NO_FATAL_FAILURE(build(60.0));
  (void)planner->solve([&] { return planner->stats().edges_added >= 60; });
  const PathChoice choice = selector->select(*planner, *sight, 20);
  ASSERT_NE(choice.state.edge, kNoHandle);
  ASSERT_FALSE(choice.sees_target);
  const double root_rho = planner->rho_m(robot.rest_state(1.0, 1.5, 0.0));
  ASSERT_GT(root_rho, 50.0);
  // The most any trajectory of at least T gets closer.
  double least_rho = root_rho;
  planner->visit_edges([&](EdgeHandle e, const Edge& edge) {
    for (int k = edge.first; k <= edge.last; ++k) {
      const auto index = static_cast<std::uint16_t>(k);
      if (planner->tree().step_of(e, index) < 20) continue;
      least_rho = std::min(least_rho, planner->rho_m(planner->tree().edge_state(e, index)));
    }
  });
  ASSERT_LT(least_rho, root_rho - 4.0) << "the tree hardly left the start";
  EXPECT_LT(choice.d_m, root_rho - 0.75 * (root_rho - least_rho))
      << "chose a trajectory of " << choice.length_m << " m, rho " << root_rho << " -> "
      << choice.d_m << " m (the tree reaches " << least_rho << " m)";
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
  config = PathSelectionConfig{};
  config.reference_speed_m_s = -1.0;
  EXPECT_FALSE(PathSelector::create(10, 10, 0.1, 100, config).ok());
  config = PathSelectionConfig{};
  config.course_change_m = -1.0;
  const auto negative = PathSelector::create(10, 10, 0.1, 100, config);
  ASSERT_FALSE(negative.ok());
  EXPECT_NE(negative.error().message.find("course_change_m"), std::string::npos);
}

}  // namespace
}  // namespace grip
