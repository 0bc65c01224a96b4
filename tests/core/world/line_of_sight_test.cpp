#include "grip/world/line_of_sight.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "grip/common/random.hpp"

namespace grip {
namespace {

using Cells = std::vector<std::pair<int, int>>;

OccupancyGrid make_grid(int w, int h, double res = 1.0, double ox = 0.0, double oy = 0.0) {
  auto grid = OccupancyGrid::create(w, h, res, ox, oy, Cell::kFree);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

struct Walk {
  Cells cells;
  TraversalResult result;
};

Walk walk(const OccupancyGrid& grid, double x0, double y0, double x1, double y1,
          std::size_t stop_after = 1000000) {
  Walk w;
  w.result = traverse_segment(grid, x0, y0, x1, y1, [&](int cx, int cy) {
    w.cells.emplace_back(cx, cy);
    return w.cells.size() < stop_after;
  });
  return w;
}

TEST(LineOfSightTest, AHorizontalSegmentVisitsEachCellOfItsRowInOrder) {
  const OccupancyGrid grid = make_grid(5, 5);
  const Walk w = walk(grid, 0.5, 0.5, 3.5, 0.5);
  EXPECT_EQ(w.cells, (Cells{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(w.result.end, TraversalEnd::kReachedEnd);
  EXPECT_EQ(w.result.cells_visited, 4U);
}

TEST(LineOfSightTest, AShallowSegmentCrossesRowsWhereHandComputationSays) {
  // From (0.5, 0.2) to (3.5, 1.2): x boundaries at t = 1/6, 1/2, 5/6, the y boundary at t = 0.8.
  const OccupancyGrid grid = make_grid(5, 5);
  const Walk w = walk(grid, 0.5, 0.2, 3.5, 1.2);
  EXPECT_EQ(w.cells, (Cells{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {3, 1}}));
  const Walk back = walk(grid, 3.5, 1.2, 0.5, 0.2);
  EXPECT_EQ(back.cells, (Cells{{3, 1}, {2, 1}, {2, 0}, {1, 0}, {0, 0}}));
}

TEST(LineOfSightTest, AnExactDiagonalVisitsBothCellsBesideEachCorner) {
  const OccupancyGrid grid = make_grid(5, 5);
  const Walk w = walk(grid, 0.5, 0.5, 2.5, 2.5);
  EXPECT_EQ(w.cells, (Cells{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 1}, {1, 2}, {2, 2}}));
  const Walk down = walk(grid, 2.5, 2.5, 0.5, 0.5);
  EXPECT_EQ(down.cells, (Cells{{2, 2}, {1, 2}, {2, 1}, {1, 1}, {0, 1}, {1, 0}, {0, 0}}));
}

TEST(LineOfSightTest, OriginAndResolutionPlaceTheCells) {
  const OccupancyGrid grid = make_grid(4, 4, 0.5, -1.0, -1.0);
  // u goes from 0.2 to 2.2 cells, v stays at 0.2.
  const Walk w = walk(grid, -0.9, -0.9, 0.1, -0.9);
  EXPECT_EQ(w.cells, (Cells{{0, 0}, {1, 0}, {2, 0}}));
}

TEST(LineOfSightTest, ASegmentLeavingTheGridStopsAtItsBorder) {
  const OccupancyGrid grid = make_grid(5, 3);
  const Walk w = walk(grid, 0.5, 0.5, 10.0, 0.5);
  EXPECT_EQ(w.cells.size(), 5U);
  EXPECT_EQ(w.cells.back(), std::make_pair(4, 0));
  EXPECT_EQ(w.result.end, TraversalEnd::kLeftGrid);
}

TEST(LineOfSightTest, AStartOutsideTheGridOrNotFiniteVisitsNothing) {
  const OccupancyGrid grid = make_grid(5, 5);
  const Walk outside = walk(grid, -0.5, 0.5, 2.5, 0.5);
  EXPECT_TRUE(outside.cells.empty());
  EXPECT_EQ(outside.result.end, TraversalEnd::kLeftGrid);
  const Walk nan = walk(grid, std::nan(""), 0.5, 2.5, 0.5);
  EXPECT_TRUE(nan.cells.empty());
  const Walk huge = walk(grid, 0.5, 0.5, 1e300, 0.5);
  EXPECT_EQ(huge.cells.size(), 5U);
}

TEST(LineOfSightTest, TheVisitorStopsTheTraversal) {
  const OccupancyGrid grid = make_grid(5, 5);
  const Walk w = walk(grid, 0.5, 0.5, 4.5, 0.5, 2);
  EXPECT_EQ(w.cells.size(), 2U);
  EXPECT_EQ(w.result.end, TraversalEnd::kStoppedByVisitor);
  EXPECT_EQ(w.result.cells_visited, 2U);
}

TEST(LineOfSightTest, ARayOfGivenRangeEndsInTheCellItReaches) {
  const OccupancyGrid grid = make_grid(10, 10);
  Cells cells;
  const TraversalResult r =
      traverse_ray(grid, 0.5, 5.5, std::numbers::pi / 2, 3.0, [&](int cx, int cy) {
        cells.emplace_back(cx, cy);
        return true;
      });
  EXPECT_EQ(r.end, TraversalEnd::kReachedEnd);
  EXPECT_EQ(cells, (Cells{{0, 5}, {0, 6}, {0, 7}, {0, 8}}));
}

TEST(LineOfSightTest, AWallIsSeenButNothingBehindIt) {
  OccupancyGrid grid = make_grid(5, 5);
  grid.set(2, 2, Cell::kObstacle);
  Cells seen;
  const bool reached = visible_cells(grid, 0.5, 2.5, 4.5, 2.5, [&](int cx, int cy) {
    seen.emplace_back(cx, cy);
    return true;
  });
  EXPECT_FALSE(reached);
  EXPECT_EQ(seen, (Cells{{0, 2}, {1, 2}, {2, 2}}));
  EXPECT_TRUE(cell_visible(grid, 0.5, 2.5, 2, 2, 10.0));   // the wall itself
  EXPECT_FALSE(cell_visible(grid, 0.5, 2.5, 3, 2, 10.0));  // behind it
  EXPECT_TRUE(cell_visible(grid, 0.5, 2.5, 1, 2, 10.0));
}

TEST(LineOfSightTest, UnknownCellsAreOpaqueLikeObstacles) {
  OccupancyGrid grid = make_grid(5, 1);
  grid.set(1, 0, Cell::kUnknown);
  EXPECT_TRUE(cell_visible(grid, 0.5, 0.5, 1, 0, 10.0));
  EXPECT_FALSE(cell_visible(grid, 0.5, 0.5, 2, 0, 10.0));
}

TEST(LineOfSightTest, NoSightThroughTwoObstaclesTouchingAtACorner) {
  OccupancyGrid grid = make_grid(4, 4);
  grid.set(1, 0, Cell::kObstacle);
  grid.set(0, 1, Cell::kObstacle);
  EXPECT_FALSE(cell_visible(grid, 0.5, 0.5, 1, 1, 10.0));
  EXPECT_FALSE(cell_visible(grid, 0.5, 0.5, 3, 3, 10.0));
  EXPECT_TRUE(cell_visible(grid, 0.5, 0.5, 1, 0, 10.0));
  grid.set(0, 1, Cell::kFree);
  // Only one corner cell blocked: the exact diagonal still touches it, so it stays hidden.
  EXPECT_FALSE(cell_visible(grid, 0.5, 0.5, 1, 1, 10.0));
  grid.set(1, 0, Cell::kFree);
  EXPECT_TRUE(cell_visible(grid, 0.5, 0.5, 3, 3, 10.0));
}

TEST(LineOfSightTest, CellVisibleRespectsRangeAndBounds) {
  const OccupancyGrid grid = make_grid(10, 10);
  EXPECT_TRUE(cell_visible(grid, 0.5, 0.5, 3, 0, 3.0));   // centre exactly 3 away
  EXPECT_FALSE(cell_visible(grid, 0.5, 0.5, 4, 0, 3.0));  // 4 away
  EXPECT_FALSE(cell_visible(grid, 0.5, 0.5, 10, 0, 30.0));
  EXPECT_FALSE(cell_visible(grid, -1.0, 0.5, 1, 0, 30.0));
}

// Reference: the parameter interval over which the segment lies in the open cell square
// (Liang-Barsky clipping), or an empty interval.
std::pair<double, double> clip(double u0, double v0, double u1, double v1, int cx, int cy) {
  double t0 = 0.0;
  double t1 = 1.0;
  const double d[2] = {u1 - u0, v1 - v0};
  const double p[2] = {u0, v0};
  const double lo[2] = {static_cast<double>(cx), static_cast<double>(cy)};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0.0) {
      if (p[a] < lo[a] || p[a] > lo[a] + 1.0) return {1.0, 0.0};
      continue;
    }
    double ta = (lo[a] - p[a]) / d[a];
    double tb = (lo[a] + 1.0 - p[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return {t0, t1};
}

TEST(LineOfSightTest, RandomSegmentsVisitExactlyTheCellsTheyCrossInOrder) {
  const OccupancyGrid grid = make_grid(40, 30);
  Random rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    const double u0 = rng.uniform(0.0, 40.0);
    const double v0 = rng.uniform(0.0, 30.0);
    const double u1 = rng.uniform(0.0, 40.0);
    const double v1 = rng.uniform(0.0, 30.0);
    const Walk w = walk(grid, u0, v0, u1, v1);
    ASSERT_EQ(w.result.end, TraversalEnd::kReachedEnd);
    // Every visited cell is crossed, in increasing order of where the segment enters it.
    double last_entry = -1.0;
    for (const auto& [cx, cy] : w.cells) {
      const auto [t0, t1] = clip(u0, v0, u1, v1, cx, cy);
      ASSERT_LT(t0, t1 + 1e-9) << "trial " << trial << " cell " << cx << "," << cy;
      ASSERT_GE(t0, last_entry - 1e-9) << "trial " << trial;
      last_entry = t0;
    }
    // Every crossed cell is visited.
    Cells expected;
    for (int cy = 0; cy < 30; ++cy) {
      for (int cx = 0; cx < 40; ++cx) {
        const auto [t0, t1] = clip(u0, v0, u1, v1, cx, cy);
        if (t1 - t0 > 1e-9) expected.emplace_back(cx, cy);
      }
    }
    for (const auto& c : expected) {
      ASSERT_NE(std::find(w.cells.begin(), w.cells.end(), c), w.cells.end())
          << "trial " << trial << " missed cell " << c.first << "," << c.second;
    }
    ASSERT_LE(w.cells.size(), expected.size() + 2) << "trial " << trial;
  }
}

}  // namespace
}  // namespace grip
