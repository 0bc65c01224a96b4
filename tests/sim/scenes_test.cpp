#include "grip/scenes/scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "grip/world/clearance_map.hpp"
#include "grip/world/collision_checker.hpp"
#include "grip/world/distance_field.hpp"

namespace grip {
namespace {

Scene build(SceneId id) {
  auto scene = make_scene(id);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
  return std::move(scene).value();
}

class EveryScene : public ::testing::TestWithParam<SceneId> {};

TEST_P(EveryScene, IsThirtyMetresSquareAtTenCentimetresAndFullyKnown) {
  const Scene scene = build(GetParam());
  EXPECT_EQ(scene.grid.width(), 300);
  EXPECT_EQ(scene.grid.height(), 300);
  EXPECT_DOUBLE_EQ(scene.grid.resolution(), 0.1);
  EXPECT_DOUBLE_EQ(scene.grid.origin_x(), 0.0);
  EXPECT_DOUBLE_EQ(scene.grid.origin_y(), 0.0);
  int free = 0;
  for (const Cell cell : scene.grid.cells()) {
    ASSERT_NE(cell, Cell::kUnknown);
    free += cell == Cell::kFree ? 1 : 0;
  }
  EXPECT_GT(free, 50000);  // mostly open: walls and furniture are a minority
  EXPECT_EQ(scene.name, scene_name(GetParam()));
  EXPECT_GT(scene.description.size(), 40u);
}

TEST_P(EveryScene, HasABorderWallThreeCellsThick) {
  const Scene scene = build(GetParam());
  const OccupancyGrid& grid = scene.grid;
  for (int k = 0; k < 300; ++k) {
    for (int d = 0; d < 3; ++d) {
      ASSERT_EQ(grid.at(k, d), Cell::kObstacle);
      ASSERT_EQ(grid.at(k, 299 - d), Cell::kObstacle);
      ASSERT_EQ(grid.at(d, k), Cell::kObstacle);
      ASSERT_EQ(grid.at(299 - d, k), Cell::kObstacle);
    }
  }
}

TEST_P(EveryScene, IsIdenticalEveryTimeItIsBuilt) {
  const Scene first = build(GetParam());
  const Scene second = build(GetParam());
  EXPECT_TRUE(std::equal(first.grid.cells().begin(), first.grid.cells().end(),
                         second.grid.cells().begin(), second.grid.cells().end()));
  EXPECT_EQ(first.start_x_m, second.start_x_m);
  EXPECT_EQ(first.start_y_m, second.start_y_m);
  EXPECT_EQ(first.start_theta_rad, second.start_theta_rad);
  EXPECT_EQ(first.goal_x_m, second.goal_x_m);
  EXPECT_EQ(first.goal_y_m, second.goal_y_m);
  EXPECT_EQ(first.goal_radius_m, second.goal_radius_m);
}

TEST_P(EveryScene, StartsBottomLeftWithTheGoalFarAway) {
  const Scene scene = build(GetParam());
  EXPECT_LT(scene.start_x_m, 5.0);
  EXPECT_LT(scene.start_y_m, 5.0);
  EXPECT_GT(std::hypot(scene.goal_x_m - scene.start_x_m, scene.goal_y_m - scene.start_y_m), 20.0);
  EXPECT_GT(scene.goal_radius_m, 0.0);
}

TEST_P(EveryScene, StartAndGoalAreAtLeastOneAndAHalfMetresFromEveryWall) {
  const Scene scene = build(GetParam());
  auto clearance = ClearanceMap::create_for(scene.grid);
  ASSERT_TRUE(clearance.ok());
  int cx = 0;
  int cy = 0;
  ASSERT_TRUE(scene.grid.to_cell(scene.start_x_m, scene.start_y_m, cx, cy));
  // The map's value is a lower bound for the cell centre; allow for the offset of the point.
  const double start_offset = std::hypot(scene.start_x_m - scene.grid.cell_center_x(cx),
                                         scene.start_y_m - scene.grid.cell_center_y(cy));
  EXPECT_GE(clearance->clearance_m(scene.grid.index(cx, cy)) - start_offset, 1.5);
  ASSERT_TRUE(scene.grid.to_cell(scene.goal_x_m, scene.goal_y_m, cx, cy));
  const double goal_offset = std::hypot(scene.goal_x_m - scene.grid.cell_center_x(cx),
                                        scene.goal_y_m - scene.grid.cell_center_y(cy));
  EXPECT_GE(clearance->clearance_m(scene.grid.index(cx, cy)) - goal_offset, 1.5);
}

TEST_P(EveryScene, TheLargestVehicleFitsAtTheStart) {
  const Scene scene = build(GetParam());
  auto checker = CollisionChecker::create(scene.grid, Footprint{0.45, 0.15, 0.225}, 0.1);
  ASSERT_TRUE(checker.ok());
  EXPECT_TRUE(checker->is_free(scene.start_x_m, scene.start_y_m, scene.start_theta_rad));
  EXPECT_TRUE(checker->is_free(scene.goal_x_m, scene.goal_y_m, 0.0));
}

TEST_P(EveryScene, TheGoalIsReachableFromTheStartWithTheRobotsInflation) {
  const Scene scene = build(GetParam());
  const std::vector<std::uint32_t> goal =
      goal_cells(scene.grid, scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m);
  ASSERT_FALSE(goal.empty());
  auto field = DistanceField::create(300, 300, 0.1);
  ASSERT_TRUE(field.ok());
  const ClearanceMap clearance = ClearanceMap::create_for(scene.grid).value();
  field->compute(scene.grid, clearance, goal, 0.25);
  const double distance = field->distance_m(scene.start_x_m, scene.start_y_m);
  EXPECT_TRUE(std::isfinite(distance));
  // The way is long: far longer than the straight line.
  EXPECT_GT(distance,
            1.5 * std::hypot(scene.goal_x_m - scene.start_x_m, scene.goal_y_m - scene.start_y_m));
}

INSTANTIATE_TEST_SUITE_P(AllScenes, EveryScene, ::testing::ValuesIn(all_scenes()),
                         [](const ::testing::TestParamInfo<SceneId>& param_info) {
                           return std::string(scene_name(param_info.param));
                         });

TEST(ScenesTest, ListsTheThreeScenesInOrder) {
  const auto scenes = all_scenes();
  ASSERT_EQ(scenes.size(), 3u);
  EXPECT_EQ(scenes[0], SceneId::kMeandros);
  EXPECT_EQ(scenes[1], SceneId::kLabyrinth);
  EXPECT_EQ(scenes[2], SceneId::kRooms);
}

TEST(ScenesTest, NamesRoundTrip) {
  for (const SceneId id : all_scenes()) {
    auto by_name = make_scene(scene_name(id));
    ASSERT_TRUE(by_name.ok());
    EXPECT_EQ(by_name->name, scene_name(id));
    const Scene by_id = build(id);
    EXPECT_TRUE(std::equal(by_name->grid.cells().begin(), by_name->grid.cells().end(),
                           by_id.grid.cells().begin(), by_id.grid.cells().end()));
  }
  EXPECT_EQ(scene_name(SceneId::kMeandros), "meandros");
  EXPECT_EQ(scene_name(SceneId::kLabyrinth), "labyrinth");
  EXPECT_EQ(scene_name(SceneId::kRooms), "rooms");
}

TEST(ScenesTest, AnUnknownNameIsAnErrorListingTheValidNames) {
  const auto scene = make_scene("mazes");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().code, ErrorCode::kInvalidArgument);
  const std::string& message = scene.error().message;
  EXPECT_NE(message.find("mazes"), std::string::npos) << message;
  EXPECT_NE(message.find("meandros"), std::string::npos) << message;
  EXPECT_NE(message.find("labyrinth"), std::string::npos) << message;
  EXPECT_NE(message.find("rooms"), std::string::npos) << message;
}

TEST(ScenesTest, AnUnknownSceneIdIsAnError) {
  EXPECT_FALSE(make_scene(static_cast<SceneId>(42)).ok());
}

TEST(ScenesTest, MeandrosIsASerpentineOfSixCorridors) {
  const Scene scene = build(SceneId::kMeandros);
  // Walk up the middle column: six free runs separated by five walls.
  int runs = 0;
  bool in_free = false;
  for (int cy = 3; cy < 297; ++cy) {
    const bool free = scene.grid.at(150, cy) == Cell::kFree;
    runs += free && !in_free ? 1 : 0;
    in_free = free;
  }
  EXPECT_EQ(runs, 6);
  // Openings alternate: the first wall is open on the right, the second on the left.
  EXPECT_EQ(scene.grid.at(280, 51), Cell::kFree);
  EXPECT_EQ(scene.grid.at(20, 51), Cell::kObstacle);
  EXPECT_EQ(scene.grid.at(20, 100), Cell::kFree);
  EXPECT_EQ(scene.grid.at(280, 100), Cell::kObstacle);
  auto field = DistanceField::create(300, 300, 0.1);
  ASSERT_TRUE(field.ok());
  field->compute(scene.grid,
                 goal_cells(scene.grid, scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m));
  EXPECT_GT(field->distance_m(scene.start_x_m, scene.start_y_m), 140.0);
}

TEST(ScenesTest, TheLabyrinthIsAPerfectMaze) {
  const Scene scene = build(SceneId::kLabyrinth);
  // 8 x 8 maze cells of pitch 3.7 m; count the openings between neighbours: a perfect maze
  // (a spanning tree) on 64 cells has exactly 63.
  const auto free_at = [&](double x, double y) {
    int cx = 0;
    int cy = 0;
    EXPECT_TRUE(scene.grid.to_cell(x, y, cx, cy));
    return scene.grid.at(cx, cy) == Cell::kFree;
  };
  int openings = 0;
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 8; ++i) {
      const double centre_x = i * 3.7 + 2.0;
      const double centre_y = j * 3.7 + 2.0;
      ASSERT_TRUE(free_at(centre_x, centre_y));
      if (i + 1 < 8 && free_at((i + 1) * 3.7 + 0.15, centre_y)) {
        ++openings;
      }
      if (j + 1 < 8 && free_at(centre_x, (j + 1) * 3.7 + 0.15)) {
        ++openings;
      }
    }
  }
  EXPECT_EQ(openings, 63);
}

TEST(ScenesTest, ValidateStartGoalRejectsBadPointsNamingThem) {
  const Scene scene = build(SceneId::kRooms);
  const OccupancyGrid& grid = scene.grid;
  EXPECT_TRUE(validate_start_goal(grid, 2.0, 2.0, 27.5, 27.5, 1.0).ok());
  const auto expect_error = [&](Status status, const std::string& part) {
    ASSERT_FALSE(status.ok()) << part;
    EXPECT_NE(status.error().message.find(part), std::string::npos) << status.error().message;
  };
  expect_error(validate_start_goal(grid, 0.1, 2.0, 27.5, 27.5, 1.0), "start (0.1, 2)");
  expect_error(validate_start_goal(grid, 0.1, 2.0, 27.5, 27.5, 1.0), "obstacle");
  expect_error(validate_start_goal(grid, 2.0, 2.0, 31.0, 27.5, 1.0), "outside the grid");
  expect_error(validate_start_goal(grid, 2.0, 2.0, 10.0, 5.0, 1.0), "goal (10, 5)");
  expect_error(validate_start_goal(grid, 2.0, 2.0, 27.5, 27.5, 0.0), "goal_radius_m");
  expect_error(validate_start_goal(grid, std::nan(""), 2.0, 27.5, 27.5, 1.0), "start_x_m");
  OccupancyGrid unknown = grid;
  unknown.set(20, 20, Cell::kUnknown);
  expect_error(validate_start_goal(unknown, 2.0, 2.0, 27.5, 27.5, 1.0), "unknown");
}

TEST(ScenesTest, GoalCellsAreTheFreeCellsWhoseCentresLieInTheDisk) {
  auto created = OccupancyGrid::create(20, 20, 0.1, 0.0, 0.0, Cell::kFree);
  ASSERT_TRUE(created.ok());
  OccupancyGrid& grid = *created;
  grid.set(10, 10, Cell::kObstacle);
  const std::vector<std::uint32_t> cells = goal_cells(grid, 1.05, 1.05, 0.15);
  // Centres within 0.15 m of (1.05, 1.05): the 3 x 3 block minus its corners (0.1414 <= 0.15,
  // so corners are in) -> 9 cells, minus the obstacle.
  EXPECT_EQ(cells.size(), 8u);
  EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end()));
  EXPECT_EQ(std::count(cells.begin(), cells.end(), grid.index(10, 10)), 0);
  EXPECT_EQ(std::count(cells.begin(), cells.end(), grid.index(11, 11)), 1);
  EXPECT_TRUE(goal_cells(grid, 50.0, 50.0, 1.0).empty());
}

}  // namespace
}  // namespace grip
