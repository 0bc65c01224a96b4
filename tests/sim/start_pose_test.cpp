#include "grip/sim/start_pose.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "grip/planner/step_margin.hpp"
#include "grip/sim/range_sensor.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/world/collision_checker.hpp"
#include "test_paths.hpp"

namespace grip::sim {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

LoadedMap movingai(const std::string& rows, int height, int width, const std::string& name) {
  const std::string text = "type octile\nheight " + std::to_string(height) + "\nwidth " +
                           std::to_string(width) + "\nmap\n" + rows;
  auto map = parse_movingai_map(text, name);
  EXPECT_TRUE(map.ok()) << (map.ok() ? "" : map.error().message);
  return std::move(map).value();
}

const Footprint kDd{0.25, 0.25, 0.2};
const Footprint kCar{0.6, 0.15, 0.2};

TEST(ParseStartTest, AcceptsXYAndXYTheta) {
  auto xy = parse_start("1.5,2");
  ASSERT_TRUE(xy.ok());
  EXPECT_DOUBLE_EQ(xy->x_m, 1.5);
  EXPECT_DOUBLE_EQ(xy->y_m, 2.0);
  EXPECT_DOUBLE_EQ(xy->theta_rad, 0.0);
  auto xyt = parse_start(" -1 , 2.5 ,0.5");
  ASSERT_TRUE(xyt.ok());
  EXPECT_DOUBLE_EQ(xyt->x_m, -1.0);
  EXPECT_DOUBLE_EQ(xyt->theta_rad, 0.5);
}

TEST(ParseStartTest, RejectsMalformedTextQuotingIt) {
  for (const char* bad : {"", "1", "1,", "a,2", "1,2,3,4", "1;2", "nan,1", "1,2x"}) {
    auto r = parse_start(bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_TRUE(contains(r.error().message, std::string("'") + bad + "'")) << r.error().message;
  }
}

TEST(CheckStartTest, AStartInsideAnObstacleNamesTheCellAndItsFileLine) {
  // 4 x 4 map cells of 1 m; the obstacle '@' sits in the file's row 2 (line 6), column 3.
  const LoadedMap map = movingai("....\n..@.\n....\n....\n", 4, 4, "room.map");
  const auto s = check_start(map, kDd, 0.0, StartPose{2.5, 2.5, 0.0});
  ASSERT_FALSE(s.ok());
  const std::string& m = s.error().message;
  EXPECT_TRUE(contains(m, "room.map: start (2.5, 2.5, 0)")) << m;
  EXPECT_TRUE(contains(m, "from room.map:6:3")) << m;
  EXPECT_EQ(s.error().code, ErrorCode::kInvalidArgument);
}

TEST(CheckStartTest, AChassisOverlappingAnObstacleFromAFreeCellIsRefusedToo) {
  const LoadedMap map = movingai("....\n..@.\n....\n....\n", 4, 4, "room.map");
  // Centre in the free cell left of the obstacle, front 0.25 m ahead reaching x = 2.05.
  const auto s = check_start(map, kDd, 0.0, StartPose{1.8, 2.5, 0.0});
  ASSERT_FALSE(s.ok());
  EXPECT_TRUE(contains(s.error().message, "room.map:6:3")) << s.error().message;
  EXPECT_TRUE(check_start(map, kDd, 0.0, StartPose{1.6, 2.5, 0.0}).ok());
}

TEST(CheckStartTest, TheChassisGrownByThePlannersMarginMustBeFreeToo) {
  const LoadedMap map = movingai("....\n..@.\n....\n....\n", 4, 4, "room.map");
  // The front at x = 1.85, 0.15 m short of the obstacle at x = 2: free with a margin of 0.1 m,
  // not with 0.2 m (the planner would refuse that start).
  EXPECT_TRUE(check_start(map, kDd, 0.1, StartPose{1.6, 2.5, 0.0}).ok());
  const auto s = check_start(map, kDd, 0.2, StartPose{1.6, 2.5, 0.0});
  ASSERT_FALSE(s.ok());
  EXPECT_TRUE(contains(s.error().message, "collision margin of 0.2 m")) << s.error().message;
  EXPECT_TRUE(contains(s.error().message, "room.map:6:3")) << s.error().message;
}

TEST(CheckStartTest, AStartOutsideOrAcrossTheEdgeIsRefused) {
  const LoadedMap map = movingai("....\n....\n", 2, 4, "open.map");
  const auto outside = check_start(map, kDd, 0.0, StartPose{5.0, 1.0, 0.0});
  ASSERT_FALSE(outside.ok());
  EXPECT_TRUE(contains(outside.error().message, "outside the map")) << outside.error().message;
  const auto edge = check_start(map, kDd, 0.0, StartPose{0.1, 1.0, 0.0});
  ASSERT_FALSE(edge.ok());
  EXPECT_TRUE(contains(edge.error().message, "edge of the map")) << edge.error().message;
}

TEST(ChooseStartTest, ItPicksTheLargestRegionNearestTheBottomLeft) {
  // A 3 x 3 m pocket at the bottom-left, walled off from a larger hall on the right.
  const LoadedMap map = movingai(
      "...@........\n"
      "...@........\n"
      "...@........\n"
      "@@@@........\n"
      "............\n"
      "............\n",
      6, 12, "halls.map");
  auto start = choose_start(map, kDd, 0.0, 0.3);
  ASSERT_TRUE(start.ok()) << start.error().message;
  // Candidates need 0.32 + 0.3 m of clearance: in the lower hall, the cell nearest (0, 0) is the
  // one at 0.65 m from the map's left and bottom edges (its centre at 0.65: clearance 0.65
  // - 0.07 m half diagonal > 0.62).
  EXPECT_NEAR(start->x_m, 0.65, 1e-9);
  EXPECT_NEAR(start->y_m, 0.65, 1e-9);
  EXPECT_TRUE(check_start(map, kDd, 0.0, *start).ok());
  // Block the lower hall's left part: the top-left pocket (3 x 3 m) is now smaller than the
  // hall on the right, which wins although the pocket is nearer the corner. Its cell nearest
  // the corner is in the notch at the hall's left: 0.65 m from the walls left and below.
  const LoadedMap walled = movingai(
      "...@........\n"
      "...@........\n"
      "...@........\n"
      "@@@@........\n"
      "@@@@@.......\n"
      "@@@@@.......\n",
      6, 12, "walled.map");
  auto right = choose_start(walled, kDd, 0.0, 0.3);
  ASSERT_TRUE(right.ok());
  EXPECT_NEAR(right->x_m, 4.65, 1e-9);
  EXPECT_NEAR(right->y_m, 2.65, 1e-9);
}

TEST(ChooseStartTest, ASmallArenaGivesUpTheRoomToSpareThenEveryHeadingButNeverTheMargin) {
  // 1 m x 1 m: the centre cells are 0.45 m (less a 0.07 m half diagonal) from the edge. The
  // dd robot (0.32 m radius) fits in every heading once the room to spare is down to 0.075 m.
  const LoadedMap map = movingai(".\n", 1, 1, "tiny.map");
  auto start = choose_start(map, kDd, 0.0, 0.3);
  ASSERT_TRUE(start.ok()) << start.error().message;
  EXPECT_NEAR(start->x_m, 0.45, 1e-9);
  EXPECT_NEAR(start->y_m, 0.45, 1e-9);
  // So it does with a planner's margin of 0.075 m and no room to spare.
  auto with_margin = choose_start(map, kDd, 0.075, 0.3);
  ASSERT_TRUE(with_margin.ok()) << with_margin.error().message;
  EXPECT_NEAR(with_margin->x_m, 0.45, 1e-9);
  // The car (0.63 m radius) fits in no heading everywhere, but in some heading somewhere: its
  // chassis, 0.75 m x 0.4 m, and with a margin of 0.05 m 0.85 m x 0.5 m, lies within the
  // square.
  for (const double margin : {0.0, 0.05}) {
    auto car = choose_start(map, kCar, margin, 0.3);
    ASSERT_TRUE(car.ok()) << car.error().message;
    EXPECT_TRUE(check_start(map, kCar, margin, *car).ok()) << margin;
  }
  // With 0.2 m (1.15 m x 0.8 m) it fits nowhere: the margin is never given up.
  auto none = choose_start(map, kCar, 0.2, 0.3);
  ASSERT_FALSE(none.ok());
  EXPECT_TRUE(contains(none.error().message, "tiny.map: no place")) << none.error().message;
  EXPECT_TRUE(contains(none.error().message, "collision margin of 0.2 m")) << none.error().message;
  EXPECT_FALSE(choose_start(map, kDd, -1.0).ok());
  EXPECT_FALSE(choose_start(map, kDd, 0.0, -1.0).ok());
}

TEST(ChooseStartTest, InACorridorTheCarStartsAlongIt) {
  // 8 m x 1 m: too narrow for the car in every heading (1.26 m across), wide enough along it.
  const LoadedMap map = movingai("........\n", 1, 8, "corridor.map");
  auto start = choose_start(map, kCar, 0.1);
  ASSERT_TRUE(start.ok()) << start.error().message;
  EXPECT_TRUE(check_start(map, kCar, 0.1, *start).ok());
  EXPECT_NEAR(std::sin(start->theta_rad), 0.0, 1e-9) << "across the corridor";
}

// ---- The real maps in ../shared/maps: nobody here drew them. ----------------------------------

std::vector<fs::path> shared_maps() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(GRIP_SHARED_MAPS_DIR)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".map" || ext == ".yaml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The crash: a map whose resolution is finite and positive but extreme ended in a
// float-to-int overflow, then an out-of-bounds read. The loaders now refuse such maps; the
// world code behind them must hold even when handed one directly.
TEST(ChooseStartTest, AnExtremeResolutionIsRefusedOrHandledNeverACrash) {
  for (const double resolution : {1e-300, 4.9e-324, 1e-9, 1e9, 1e300}) {
    auto grid = OccupancyGrid::create(12, 10, resolution, 0.0, 0.0, Cell::kFree);
    ASSERT_TRUE(grid.ok()) << resolution;
    const LoadedMap map{std::move(grid).value(), MapFormat::kMovingAi, "extreme.map", {}, 0, 5, 1};
    for (const Footprint& footprint : {kDd, kCar}) {
      auto start = choose_start(map, footprint, 0.05);
      if (start) {
        EXPECT_TRUE(std::isfinite(start->x_m) && std::isfinite(start->y_m)) << resolution;
      } else {
        EXPECT_TRUE(contains(start.error().message, "extreme.map")) << start.error().message;
      }
      const Status s = check_start(map, footprint, 0.05, StartPose{1.0, 1.0, 0.3});
      if (!s) {
        EXPECT_TRUE(contains(s.error().message, "extreme.map")) << s.error().message;
      }
    }
  }
}

TEST(SharedMapsTest, EveryMapLoadsAndHasAStartForTheLargestVehicle) {
  if (!fs::is_directory(GRIP_SHARED_MAPS_DIR)) {
    GTEST_SKIP() << GRIP_SHARED_MAPS_DIR << " does not exist";
  }
  const std::vector<fs::path> files = shared_maps();
  ASSERT_GE(files.size(), 5U);
  const Car car = Car::create(CarParams{}).value();
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    auto map = load_map(file.string());
    ASSERT_TRUE(map.ok()) << map.error().message;
    const OccupancyGrid& g = map->grid;
    std::uint32_t free = 0;
    for (const Cell c : g.cells()) {
      ASSERT_NE(c, Cell::kUnknown);
      free += c == Cell::kFree ? 1U : 0U;
    }
    EXPECT_GT(free, 0U);
    EXPECT_LT(free, g.cell_count());
    // The margin the planner checks the start with (its 50 ms integration step).
    const double margin = step_collision_margin_m(car, 0.05);
    auto start = choose_start(*map, car.footprint(), margin);
    ASSERT_TRUE(start.ok()) << start.error().message;
    EXPECT_TRUE(check_start(*map, car.footprint(), margin, *start).ok());
    // The first sweep from the start reveals free space all around the chassis.
    auto known = OccupancyGrid::create(g.width(), g.height(), g.resolution(), g.origin_x(),
                                       g.origin_y(), Cell::kUnknown);
    ASSERT_TRUE(known.ok());
    auto sensor = RangeSensor::create(g, RangeSensor::default_radius_m(g));
    ASSERT_TRUE(sensor.ok());
    (void)sensor->sense(start->x_m, start->y_m, *known);
    auto checker = CollisionChecker::create(*known, car.footprint(), margin);
    ASSERT_TRUE(checker.ok());
    EXPECT_TRUE(checker->is_free(start->x_m, start->y_m, start->theta_rad));
  }
}

TEST(SharedMapsTest, KnownMapsHaveTheirDocumentedSizes) {
  if (!fs::is_directory(GRIP_SHARED_MAPS_DIR)) {
    GTEST_SKIP() << GRIP_SHARED_MAPS_DIR << " does not exist";
  }
  const fs::path dir(GRIP_SHARED_MAPS_DIR);
  auto maze = load_map((dir / "movingai" / "maze-32-32-4.map").string());
  ASSERT_TRUE(maze.ok()) << maze.error().message;
  EXPECT_EQ(maze->grid.width(), 320);
  EXPECT_EQ(maze->grid.at(0, 319), Cell::kObstacle);  // '@' at the file's top-left
  EXPECT_EQ(maze->grid.at(10, 300), Cell::kFree);     // '.' at line 6, column 2
  auto depot = load_map((dir / "ros" / "depot.yaml").string());
  ASSERT_TRUE(depot.ok()) << depot.error().message;
  EXPECT_EQ(depot->grid.width(), 604);
  EXPECT_EQ(depot->grid.height(), 307);
  EXPECT_DOUBLE_EQ(depot->grid.resolution(), 0.05);
  auto sandbox = load_map((dir / "ros" / "tb3_sandbox.yaml").string());
  ASSERT_TRUE(sandbox.ok()) << sandbox.error().message;
  EXPECT_DOUBLE_EQ(sandbox->grid.origin_x(), -10.0);
  EXPECT_GT(sandbox->unknown_pixels, 100000U);
}

}  // namespace
}  // namespace grip::sim
