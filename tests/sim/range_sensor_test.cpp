#include "grip/sim/range_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace grip::sim {
namespace {

OccupancyGrid make_grid(int w, int h, Cell fill, double res = 1.0) {
  auto grid = OccupancyGrid::create(w, h, res, 0.0, 0.0, fill);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

// Distance from (x, y) to the nearest point of cell (cx, cy) of a 1 m grid.
double distance_to_cell(double x, double y, int cx, int cy) {
  const double dx = std::max({cx - x, 0.0, x - (cx + 1.0)});
  const double dy = std::max({cy - y, 0.0, y - (cy + 1.0)});
  return std::hypot(dx, dy);
}

class RangeSensorTest : public ::testing::Test {
 protected:
  OccupancyGrid truth = make_grid(21, 21, Cell::kFree);
  OccupancyGrid known = make_grid(21, 21, Cell::kUnknown);
};

TEST_F(RangeSensorTest, InTheOpenItSeesEveryCellWithinTheRadiusAndNothingBeyond) {
  auto sensor = RangeSensor::create(truth, 5.0);
  ASSERT_TRUE(sensor.ok());
  EXPECT_EQ(sensor->ray_count(), 63U);  // ceil(2 pi 5 / 0.5)
  const SenseResult r = sensor->sense(10.5, 10.5, known);
  std::uint32_t marked = 0;
  for (int cy = 0; cy < 21; ++cy) {
    for (int cx = 0; cx < 21; ++cx) {
      const double centre = std::hypot(cx + 0.5 - 10.5, cy + 0.5 - 10.5);
      const Cell c = known.at(cx, cy);
      if (c != Cell::kUnknown) {
        ++marked;
        EXPECT_EQ(c, Cell::kFree);
        EXPECT_LE(distance_to_cell(10.5, 10.5, cx, cy), 5.0) << cx << "," << cy;
        EXPECT_GE(cx, r.changed.x0);
        EXPECT_LE(cx, r.changed.x1);
        EXPECT_GE(cy, r.changed.y0);
        EXPECT_LE(cy, r.changed.y1);
      }
      if (centre <= 5.0 - std::sqrt(0.5)) {
        EXPECT_EQ(c, Cell::kFree) << "missed " << cx << "," << cy;
      }
    }
  }
  EXPECT_EQ(r.changed_cells.size(), marked);
  EXPECT_EQ(r.changed.x0, 5);  // (5, 10) is 0.5 m from the sensor's left reach
  EXPECT_EQ(r.changed.x1, 15);
  EXPECT_EQ(r.changed.y0, 5);
  EXPECT_EQ(r.changed.y1, 15);
}

TEST_F(RangeSensorTest, AWallIsMarkedAsObstacleAndHidesWhatIsBehindIt) {
  for (int y = 5; y <= 15; ++y) truth.set(13, y, Cell::kObstacle);
  auto sensor = RangeSensor::create(truth, 8.0);
  ASSERT_TRUE(sensor.ok());
  (void)sensor->sense(10.5, 10.5, known);
  EXPECT_EQ(known.at(12, 10), Cell::kFree);
  EXPECT_EQ(known.at(13, 10), Cell::kObstacle);
  for (int y = 8; y <= 12; ++y) {
    for (int x = 14; x <= 18; ++x) {
      EXPECT_EQ(known.at(x, y), Cell::kUnknown) << "seen behind the wall: " << x << "," << y;
    }
  }
  EXPECT_EQ(known.at(7, 10), Cell::kFree);  // the other way is open
}

TEST_F(RangeSensorTest, TwoObstaclesTouchingAtACornerCloseTheView) {
  truth.set(11, 10, Cell::kObstacle);
  truth.set(10, 11, Cell::kObstacle);
  truth.set(9, 10, Cell::kObstacle);
  truth.set(10, 9, Cell::kObstacle);
  auto sensor = RangeSensor::create(truth, 6.0);
  ASSERT_TRUE(sensor.ok());
  const SenseResult r = sensor->sense(10.5, 10.5, known);
  // Boxed in by four walls: the sensor cell, the four walls, and nothing else.
  EXPECT_EQ(r.changed_cells.size(), 5U);
  EXPECT_EQ(known.at(10, 10), Cell::kFree);
  EXPECT_EQ(known.at(11, 11), Cell::kUnknown);
  EXPECT_EQ(known.at(9, 9), Cell::kUnknown);
  EXPECT_EQ(r.changed.x0, 9);
  EXPECT_EQ(r.changed.x1, 11);
}

TEST_F(RangeSensorTest, ASecondSweepFromTheSamePlaceChangesNothing) {
  auto sensor = RangeSensor::create(truth, 4.0);
  ASSERT_TRUE(sensor.ok());
  const std::size_t first = sensor->sense(3.2, 4.7, known).changed_cells.size();
  EXPECT_GT(first, 0U);
  const SenseResult again = sensor->sense(3.2, 4.7, known);
  EXPECT_TRUE(again.changed_cells.empty());
  EXPECT_TRUE(again.changed.empty());
  EXPECT_GT(again.cells_visited, 0U);
}

TEST_F(RangeSensorTest, ASensorOutsideTheMapSeesNothing) {
  auto sensor = RangeSensor::create(truth, 4.0);
  ASSERT_TRUE(sensor.ok());
  const SenseResult r = sensor->sense(-1.0, 3.0, known);
  EXPECT_TRUE(r.changed.empty());
  EXPECT_EQ(r.cells_visited, 0U);
}

TEST_F(RangeSensorTest, TheMapEdgeStopsRaysAndNothingOutsideIsTouched) {
  auto sensor = RangeSensor::create(truth, 5.0);
  ASSERT_TRUE(sensor.ok());
  const SenseResult r = sensor->sense(0.5, 0.5, known);
  EXPECT_EQ(r.changed.x0, 0);
  EXPECT_EQ(r.changed.y0, 0);
  EXPECT_EQ(known.at(4, 0), Cell::kFree);
  EXPECT_EQ(known.at(0, 4), Cell::kFree);
  EXPECT_EQ(known.at(6, 0), Cell::kUnknown);
}

TEST(RangeSensorCreateTest, TheRadiusMustBePositiveAndFinite) {
  const OccupancyGrid grid = make_grid(10, 10, Cell::kFree);
  EXPECT_FALSE(RangeSensor::create(grid, 0.0).ok());
  EXPECT_FALSE(RangeSensor::create(grid, -1.0).ok());
  const auto nan = RangeSensor::create(grid, std::nan(""));
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().message.find("radius_m"), std::string::npos);
}

TEST(RangeSensorCreateTest, ARealSensorsBeamCountIsTakenAndOutOfRangeOnesRefused) {
  const OccupancyGrid truth = make_grid(41, 41, Cell::kFree);
  // GIVEN a 16-beam sensor of range 20 m: its beams are 7.9 m apart at full range
  auto sparse = RangeSensor::create(truth, 20.0, 16);
  ASSERT_TRUE(sparse.ok());
  EXPECT_EQ(sparse->ray_count(), 16U);
  OccupancyGrid seen_sparse = make_grid(41, 41, Cell::kUnknown);
  OccupancyGrid seen_dense = make_grid(41, 41, Cell::kUnknown);
  // WHEN it senses from the centre, beside a sensor with the default count
  const SenseResult few = sparse->sense(20.5, 20.5, seen_sparse);
  auto dense = RangeSensor::create(truth, 20.0);
  ASSERT_TRUE(dense.ok());
  const SenseResult many = dense->sense(20.5, 20.5, seen_dense);
  // THEN it sees fewer cells, as that sensor would
  EXPECT_LT(few.changed_cells.size() * 2, many.changed_cells.size());
  // AND a count below 16 or above 2^20 is refused, naming rays
  for (const std::uint32_t bad : {1U, 15U, (1U << 20) + 1}) {
    const auto refused = RangeSensor::create(truth, 5.0, bad);
    ASSERT_FALSE(refused.ok()) << bad;
    EXPECT_NE(refused.error().message.find("rays must be 0"), std::string::npos);
  }
}

TEST(RangeSensorCreateTest, TheDefaultRadiusIsATenthOfTheLargerSide) {
  const OccupancyGrid grid = make_grid(300, 150, Cell::kFree, 0.1);
  EXPECT_DOUBLE_EQ(RangeSensor::default_radius_m(grid), 3.0);
}

TEST(ForEachPatchTest, TilesCoverTheBoxExactlyWithinTheCellLimit) {
  auto count = [](const CellBox& box, std::uint32_t max_cells) {
    std::vector<CellBox> tiles;
    for_each_patch(box, max_cells, [&](const CellBox& t) { tiles.push_back(t); });
    return tiles;
  };
  const std::vector<CellBox> big = count(CellBox{0, 0, 299, 299}, 65536);
  ASSERT_EQ(big.size(), 2U);  // 300 wide: 218 rows fit in 65536 cells
  EXPECT_EQ(big[0].y1, 217);
  EXPECT_EQ(big[1].y0, 218);
  EXPECT_EQ(big[1].y1, 299);
  const std::vector<CellBox> wide = count(CellBox{2, 3, 11, 5}, 4);
  EXPECT_EQ(wide.size(), 9U);
  std::uint32_t cells = 0;
  for (const CellBox& t : wide) {
    const auto n = static_cast<std::uint32_t>((t.x1 - t.x0 + 1) * (t.y1 - t.y0 + 1));
    EXPECT_LE(n, 4U);
    cells += n;
  }
  EXPECT_EQ(cells, 30U);
  EXPECT_TRUE(count(CellBox{}, 10).empty());
}

}  // namespace
}  // namespace grip::sim
