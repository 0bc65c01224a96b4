#include "grip/world/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace grip {
namespace {

OccupancyGrid make_grid(int w, int h, double res, double ox = 0.0, double oy = 0.0,
                        Cell fill = Cell::kUnknown) {
  auto grid = OccupancyGrid::create(w, h, res, ox, oy, fill);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

void expect_error_mentions(const Result<OccupancyGrid>& result, const std::string& name,
                           const std::string& value) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(result.error().message.find(name), std::string::npos) << result.error().message;
  EXPECT_NE(result.error().message.find(value), std::string::npos) << result.error().message;
}

TEST(OccupancyGridTest, CreateReportsSizesAndStartsFilledWithTheFillValue) {
  const OccupancyGrid grid = make_grid(30, 20, 0.5, -1.0, 2.0);
  EXPECT_EQ(grid.width(), 30);
  EXPECT_EQ(grid.height(), 20);
  EXPECT_EQ(grid.cell_count(), 600u);
  EXPECT_DOUBLE_EQ(grid.resolution(), 0.5);
  EXPECT_DOUBLE_EQ(grid.origin_x(), -1.0);
  EXPECT_DOUBLE_EQ(grid.origin_y(), 2.0);
  EXPECT_DOUBLE_EQ(grid.width_m(), 15.0);
  EXPECT_DOUBLE_EQ(grid.height_m(), 10.0);
  EXPECT_EQ(grid.revision(), 0u);
  for (const Cell cell : grid.cells()) {
    EXPECT_EQ(cell, Cell::kUnknown);
  }
  const OccupancyGrid free_grid = make_grid(3, 3, 1.0, 0.0, 0.0, Cell::kFree);
  EXPECT_EQ(free_grid.at(1, 1), Cell::kFree);
}

TEST(OccupancyGridTest, CreateRejectsBadParametersNamingThem) {
  expect_error_mentions(OccupancyGrid::create(0, 10, 0.1), "width_cells", "0");
  expect_error_mentions(OccupancyGrid::create(-5, 10, 0.1), "width_cells", "-5");
  expect_error_mentions(OccupancyGrid::create(10, 0, 0.1), "height_cells", "0");
  expect_error_mentions(OccupancyGrid::create(20000, 10, 0.1), "width_cells", "20000");
  expect_error_mentions(OccupancyGrid::create(16384, 16384, 0.1), "width_cells * height_cells",
                        "268435456");
  expect_error_mentions(OccupancyGrid::create(10, 10, 0.0), "resolution_m", "0");
  expect_error_mentions(OccupancyGrid::create(10, 10, -0.1), "resolution_m", "-0.1");
  expect_error_mentions(OccupancyGrid::create(10, 10, std::nan("")), "resolution_m", "nan");
  expect_error_mentions(OccupancyGrid::create(10, 10, std::numeric_limits<double>::infinity()),
                        "resolution_m", "inf");
  expect_error_mentions(OccupancyGrid::create(10, 10, 0.1, std::nan(""), 0.0), "origin_x_m", "nan");
  expect_error_mentions(
      OccupancyGrid::create(10, 10, 0.1, 0.0, -std::numeric_limits<double>::infinity()),
      "origin_y_m", "-inf");
  expect_error_mentions(OccupancyGrid::create(10, 10, 0.1, 0.0, 0.0, static_cast<Cell>(7)), "fill",
                        "7");
}

TEST(OccupancyGridTest, IndexIsRowMajorWithRowZeroAtTheBottom) {
  const OccupancyGrid grid = make_grid(7, 5, 1.0);
  EXPECT_EQ(grid.index(0, 0), 0u);
  EXPECT_EQ(grid.index(6, 0), 6u);
  EXPECT_EQ(grid.index(0, 1), 7u);
  EXPECT_EQ(grid.index(3, 4), 31u);
  EXPECT_EQ(grid.cell_x(31), 3);
  EXPECT_EQ(grid.cell_y(31), 4);
  // Row 0 is the bottom: its centres have the smallest y.
  EXPECT_LT(grid.cell_center_y(0), grid.cell_center_y(4));
}

TEST(OccupancyGridTest, InBoundsAcceptsExactlyTheGridCells) {
  const OccupancyGrid grid = make_grid(4, 3, 1.0);
  EXPECT_TRUE(grid.in_bounds(0, 0));
  EXPECT_TRUE(grid.in_bounds(3, 2));
  EXPECT_FALSE(grid.in_bounds(-1, 0));
  EXPECT_FALSE(grid.in_bounds(0, -1));
  EXPECT_FALSE(grid.in_bounds(4, 0));
  EXPECT_FALSE(grid.in_bounds(0, 3));
}

TEST(OccupancyGridTest, ReadingOutsideTheGridGivesObstacle) {
  const OccupancyGrid grid = make_grid(4, 3, 1.0, 0.0, 0.0, Cell::kFree);
  EXPECT_EQ(grid.at(-1, 0), Cell::kObstacle);
  EXPECT_EQ(grid.at(4, 1), Cell::kObstacle);
  EXPECT_EQ(grid.at(2, 3), Cell::kObstacle);
  EXPECT_EQ(grid.at(2, 2), Cell::kFree);
}

TEST(OccupancyGridTest, SetWritesOneCellAndBumpsRevisionOnlyOnChange) {
  OccupancyGrid grid = make_grid(4, 3, 1.0, 0.0, 0.0, Cell::kFree);
  grid.set(2, 1, Cell::kObstacle);
  EXPECT_EQ(grid.at(2, 1), Cell::kObstacle);
  EXPECT_EQ(grid.at(grid.index(2, 1)), Cell::kObstacle);
  EXPECT_EQ(grid.at(1, 1), Cell::kFree);
  EXPECT_EQ(grid.revision(), 1u);
  grid.set(2, 1, Cell::kObstacle);
  EXPECT_EQ(grid.revision(), 1u);
  grid.set(2, 1, Cell::kUnknown);
  EXPECT_EQ(grid.revision(), 2u);
}

TEST(OccupancyGridTest, SetOutsideTheGridIsABrokenContract) {
  OccupancyGrid grid = make_grid(4, 3, 1.0);
  EXPECT_DEATH(grid.set(4, 0, Cell::kFree), "invariant violated");
}

TEST(OccupancyGridTest, ToCellFloorsAndRejectsPointsOutsideOrNotFinite) {
  const OccupancyGrid grid = make_grid(10, 8, 0.5, -2.0, 1.0);
  int cx = -7;
  int cy = -7;
  ASSERT_TRUE(grid.to_cell(-2.0, 1.0, cx, cy));
  EXPECT_EQ(cx, 0);
  EXPECT_EQ(cy, 0);
  ASSERT_TRUE(grid.to_cell(0.26, 2.74, cx, cy));
  EXPECT_EQ(cx, 4);
  EXPECT_EQ(cy, 3);
  ASSERT_TRUE(grid.to_cell(2.999, 4.999, cx, cy));
  EXPECT_EQ(cx, 9);
  EXPECT_EQ(cy, 7);
  cx = -7;
  EXPECT_FALSE(grid.to_cell(3.0, 2.0, cx, cy));  // x = origin + width is outside
  EXPECT_FALSE(grid.to_cell(-2.001, 2.0, cx, cy));
  EXPECT_FALSE(grid.to_cell(0.0, 0.999, cx, cy));
  EXPECT_FALSE(grid.to_cell(0.0, 5.0, cx, cy));
  EXPECT_FALSE(grid.to_cell(std::nan(""), 2.0, cx, cy));
  EXPECT_FALSE(grid.to_cell(0.0, std::numeric_limits<double>::infinity(), cx, cy));
  EXPECT_FALSE(grid.to_cell(1e300, 2.0, cx, cy));
  EXPECT_EQ(cx, -7);  // untouched on failure
}

TEST(OccupancyGridTest, CellCentresMapBackToTheirCells) {
  const OccupancyGrid grid = make_grid(10, 8, 0.1, 3.0, -4.0);
  EXPECT_DOUBLE_EQ(grid.cell_center_x(0), 3.05);
  EXPECT_DOUBLE_EQ(grid.cell_center_y(7), -4.0 + 0.75);
  for (int cy = 0; cy < grid.height(); ++cy) {
    for (int cx = 0; cx < grid.width(); ++cx) {
      int rx = -1;
      int ry = -1;
      ASSERT_TRUE(grid.to_cell(grid.cell_center_x(cx), grid.cell_center_y(cy), rx, ry));
      EXPECT_EQ(rx, cx);
      EXPECT_EQ(ry, cy);
    }
  }
}

TEST(OccupancyGridTest, FillRectSetsExactlyTheCellsWhoseCentresLieInside) {
  OccupancyGrid grid = make_grid(10, 10, 1.0, 0.0, 0.0, Cell::kFree);
  // Corners given in reverse order; centres x in {2.5, 3.5, 4.5}, y in {1.5, 2.5}.
  grid.fill_rect(5.0, 3.0, 2.0, 1.2, Cell::kObstacle);
  int obstacles = 0;
  for (int cy = 0; cy < 10; ++cy) {
    for (int cx = 0; cx < 10; ++cx) {
      const bool inside = cx >= 2 && cx <= 4 && cy >= 1 && cy <= 2;
      EXPECT_EQ(grid.at(cx, cy), inside ? Cell::kObstacle : Cell::kFree) << cx << "," << cy;
      obstacles += grid.at(cx, cy) == Cell::kObstacle ? 1 : 0;
    }
  }
  EXPECT_EQ(obstacles, 6);
  EXPECT_EQ(grid.revision(), 1u);
}

TEST(OccupancyGridTest, FillRectClipsToTheGridAndBumpsRevisionOnlyOnChange) {
  OccupancyGrid grid = make_grid(4, 4, 1.0, 0.0, 0.0, Cell::kFree);
  grid.fill_rect(-100.0, -100.0, 100.0, 0.9, Cell::kUnknown);
  for (int cx = 0; cx < 4; ++cx) {
    EXPECT_EQ(grid.at(cx, 0), Cell::kUnknown);
    EXPECT_EQ(grid.at(cx, 1), Cell::kFree);
  }
  EXPECT_EQ(grid.revision(), 1u);
  grid.fill_rect(-100.0, -100.0, 100.0, 0.9, Cell::kUnknown);  // nothing changes
  EXPECT_EQ(grid.revision(), 1u);
  grid.fill_rect(10.0, 10.0, 20.0, 20.0, Cell::kObstacle);  // wholly outside
  EXPECT_EQ(grid.revision(), 1u);
  grid.fill_rect(0.0, 0.0, std::nan(""), 3.0, Cell::kObstacle);  // ignored
  EXPECT_EQ(grid.revision(), 1u);
  EXPECT_EQ(grid.at(1, 1), Cell::kFree);
}

TEST(OccupancyGridTest, MutableCellsCountsAsAMutationAndWritesThrough) {
  OccupancyGrid grid = make_grid(3, 2, 1.0, 0.0, 0.0, Cell::kFree);
  const std::uint64_t before = grid.revision();
  std::span<Cell> cells = grid.mutable_cells();
  EXPECT_GT(grid.revision(), before);
  ASSERT_EQ(cells.size(), 6u);
  cells[grid.index(2, 1)] = Cell::kObstacle;
  EXPECT_EQ(grid.at(2, 1), Cell::kObstacle);
  const std::uint64_t after = grid.revision();
  grid.mark_changed();
  EXPECT_EQ(grid.revision(), after + 1);
}

}  // namespace
}  // namespace grip
