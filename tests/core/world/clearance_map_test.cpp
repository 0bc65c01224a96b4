#include "grip/world/clearance_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "grip/common/random.hpp"

namespace grip {
namespace {

OccupancyGrid make_grid(int w, int h, double res, Cell fill = Cell::kFree) {
  auto grid = OccupancyGrid::create(w, h, res, 0.0, 0.0, fill);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

// Brute force: squared centre distance, in cells, to the nearest non-free cell or to the
// nearest cell outside the grid.
std::uint32_t brute_force_d2(const OccupancyGrid& grid, int cx, int cy) {
  std::int64_t best = std::numeric_limits<std::int64_t>::max();
  for (int y = -1; y <= grid.height(); ++y) {
    for (int x = -1; x <= grid.width(); ++x) {
      if (grid.at(x, y) == Cell::kFree) {  // at() reads outside as kObstacle
        continue;
      }
      const std::int64_t dx = x - cx;
      const std::int64_t dy = y - cy;
      best = std::min(best, dx * dx + dy * dy);
    }
  }
  return static_cast<std::uint32_t>(best);
}

TEST(ClearanceMapTest, MatchesABruteForceTransformOnRandomGrids) {
  Random random(7);
  for (int trial = 0; trial < 40; ++trial) {
    const int w = 1 + static_cast<int>(random.below(30));
    const int h = 1 + static_cast<int>(random.below(30));
    OccupancyGrid grid = make_grid(w, h, 0.1);
    const double density = random.uniform(0.0, 0.3);
    for (int cy = 0; cy < h; ++cy) {
      for (int cx = 0; cx < w; ++cx) {
        if (random.uniform01() < density) {
          grid.set(cx, cy, random.below(2) == 0 ? Cell::kObstacle : Cell::kUnknown);
        }
      }
    }
    auto map = ClearanceMap::create_for(grid);
    ASSERT_TRUE(map.ok());
    for (int cy = 0; cy < h; ++cy) {
      for (int cx = 0; cx < w; ++cx) {
        ASSERT_EQ(map->squared_cells(grid.index(cx, cy)), brute_force_d2(grid, cx, cy))
            << "trial " << trial << " cell " << cx << "," << cy;
      }
    }
  }
}

// `count` cells made obstacles at random (some may repeat).
void scatter_obstacles(OccupancyGrid& grid, Random& random, int count) {
  for (int k = 0; k < count; ++k) {
    grid.set(static_cast<int>(random.below(static_cast<std::uint32_t>(grid.width()))),
             static_cast<int>(random.below(static_cast<std::uint32_t>(grid.height()))),
             Cell::kObstacle);
  }
}

// Every cell changed at random inside a box, free <-> obstacle or unknown.
CellBox change_a_box(OccupancyGrid& grid, Random& random) {
  const int x0 = static_cast<int>(random.below(static_cast<std::uint32_t>(grid.width())));
  const int y0 = static_cast<int>(random.below(static_cast<std::uint32_t>(grid.height())));
  const int x1 = std::min(grid.width() - 1, x0 + static_cast<int>(random.below(8)));
  const int y1 = std::min(grid.height() - 1, y0 + static_cast<int>(random.below(8)));
  const double density = random.uniform(0.0, 0.6);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      grid.set(x, y,
               random.uniform01() >= density ? Cell::kFree
               : random.below(2) == 0        ? Cell::kObstacle
                                             : Cell::kUnknown);
    }
  }
  return CellBox{x0, y0, x1, y1};
}

TEST(ClearanceMapTest, AWindowedUpdateAnswersEveryThresholdUpToItsBoundAsAFullCompute) {
  // GIVEN random grids changed box by box, the map updated in windows after each change
  Random random(17);
  for (int trial = 0; trial < 30; ++trial) {
    const int w = 5 + static_cast<int>(random.below(60));
    const int h = 5 + static_cast<int>(random.below(60));
    OccupancyGrid grid = make_grid(w, h, 0.1);
    for (int k = 0; k < 6; ++k) change_a_box(grid, random);
    auto updated = ClearanceMap::create_for(grid);
    ASSERT_TRUE(updated.ok());
    const auto bound = static_cast<std::uint32_t>(1 + random.below(40));
    for (int step = 0; step < 8; ++step) {
      CellBox changed = change_a_box(grid, random);
      if (random.below(2) == 0) changed.add(change_a_box(grid, random));
      const CellBox rewritten = updated->update(grid, changed, bound);
      // THEN the window holds the change, every d2 up to the bound is exact and every larger
      // one is larger in both (so any threshold up to the bound compares the same), and the
      // map follows the grid's revision
      EXPECT_TRUE(rewritten.x0 <= changed.x0 && rewritten.y0 <= changed.y0 &&
                  rewritten.x1 >= changed.x1 && rewritten.y1 >= changed.y1);
      EXPECT_EQ(updated->exact_up_to(), bound);
      EXPECT_EQ(updated->source_revision(), grid.revision());
      const ClearanceMap full = ClearanceMap::create_for(grid).value();
      for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
        const std::uint32_t exact = full.squared_cells(i);
        const std::uint32_t got = updated->squared_cells(i);
        if (exact <= bound) {
          ASSERT_EQ(got, exact) << "trial " << trial << " step " << step << " cell " << i;
        } else {
          ASSERT_GT(got, bound) << "trial " << trial << " step " << step << " cell " << i;
        }
      }
    }
  }
}

TEST(ClearanceMapTest, AChangeLargerThanTheUpdateWindowRecomputesTheWholeMap) {
  // GIVEN a map larger than the smallest update window (2^20 cells) with walls at random, and a
  // change that spans it: its window holds more cells than the scratch sized at creation
  OccupancyGrid grid = make_grid(1100, 1000, 0.05);
  Random random(5);
  scatter_obstacles(grid, random, 2000);
  auto map = ClearanceMap::create_for(grid);
  ASSERT_TRUE(map.ok());
  grid.set(2, 3, Cell::kObstacle);
  grid.set(1090, 990, Cell::kUnknown);
  // WHEN it is updated with a bound
  const CellBox rewritten = map->update(grid, CellBox{2, 3, 1090, 990}, 25);
  // THEN the whole map was rewritten, exact everywhere, as compute() leaves it
  EXPECT_EQ(rewritten.x0, 0);
  EXPECT_EQ(rewritten.y0, 0);
  EXPECT_EQ(rewritten.x1, 1099);
  EXPECT_EQ(rewritten.y1, 999);
  EXPECT_EQ(map->exact_up_to(), std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(map->source_revision(), grid.revision());
  const ClearanceMap full = ClearanceMap::create_for(grid).value();
  EXPECT_TRUE(std::equal(map->squared_cells().begin(), map->squared_cells().end(),
                         full.squared_cells().begin()));
  EXPECT_EQ(map->squared_cells(grid.index(3, 3)), 1U);
}

TEST(ClearanceMapTest, AnEmptyChangeOnlyFollowsTheRevision) {
  OccupancyGrid grid = make_grid(20, 20, 0.1);
  auto map = ClearanceMap::create_for(grid);
  ASSERT_TRUE(map.ok());
  grid.set(3, 3, Cell::kUnknown);
  grid.set(3, 3, Cell::kObstacle);  // non-free either way: clearance is unchanged
  EXPECT_TRUE(map->update(grid, CellBox{}, 9).empty());
  EXPECT_EQ(map->source_revision(), grid.revision());
  EXPECT_EQ(map->squared_cells(grid.index(4, 3)), 16U) << "unchanged: (3, 3) was not seen";
}

TEST(ClearanceMapTest, TheOutsideOfTheGridCountsAsNonFree) {
  const OccupancyGrid grid = make_grid(9, 5, 0.5);
  auto map = ClearanceMap::create_for(grid);
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(map->squared_cells(grid.index(0, 0)), 1u);
  EXPECT_EQ(map->squared_cells(grid.index(4, 2)), 9u);  // 3 cells to rows -1 and 5
  EXPECT_EQ(map->squared_cells(grid.index(8, 4)), 1u);
}

TEST(ClearanceMapTest, ClearanceIsALowerBoundOfTheDistanceToNonFreeSpace) {
  OccupancyGrid grid = make_grid(21, 21, 0.1);
  grid.set(10, 10, Cell::kObstacle);
  auto map = ClearanceMap::create_for(grid);
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(map->clearance_m(grid.index(10, 10)), 0.0);
  // Straight above the obstacle by 3 cells: the true distance from the centre to the
  // obstacle's top edge is 0.25 m; the bound is 0.3 - 0.0707.
  const double bound = map->clearance_m(grid.index(10, 13));
  EXPECT_NEAR(bound, 0.3 - 0.1 * std::sqrt(0.5), 1e-12);
  EXPECT_LE(bound, 0.25);
  // Every free cell: the bound never exceeds the exact centre-to-square distance.
  for (int cy = 0; cy < 21; ++cy) {
    for (int cx = 0; cx < 21; ++cx) {
      const double dx = std::max(std::abs(cx - 10) - 0.5, 0.0) * 0.1;
      const double dy = std::max(std::abs(cy - 10) - 0.5, 0.0) * 0.1;
      const double border = 0.1 * (std::min(std::min(cx, cy), std::min(20 - cx, 20 - cy)) + 0.5);
      const double exact = std::min(std::hypot(dx, dy), border);
      EXPECT_LE(map->clearance_m(grid.index(cx, cy)), exact + 1e-12) << cx << "," << cy;
    }
  }
}

TEST(ClearanceMapTest, SquaredThresholdSelectsExactlyTheCellsWithEnoughClearance) {
  OccupancyGrid grid = make_grid(40, 40, 0.1);
  Random random(3);
  scatter_obstacles(grid, random, 60);
  auto map = ClearanceMap::create_for(grid);
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(map->squared_cells_at_least(0.0), 0u);
  EXPECT_EQ(map->squared_cells_at_least(-1.0), 0u);
  for (const double c : {0.01, 0.05, 0.1, 0.2, 0.25, 0.33, 0.5}) {
    const std::uint32_t k = map->squared_cells_at_least(c);
    for (std::uint32_t i = 0; i < map->cell_count(); ++i) {
      if (map->squared_cells(i) >= k) {
        EXPECT_GE(map->clearance_m(i), c - 1e-12);
      } else {
        EXPECT_LT(map->clearance_m(i), c + 1e-9);
      }
    }
  }
}

TEST(ClearanceMapTest, ComputeFollowsTheGridAndRecordsItsRevision) {
  OccupancyGrid grid = make_grid(10, 10, 0.1);
  auto map = ClearanceMap::create(10, 10, 0.1);
  ASSERT_TRUE(map.ok());
  EXPECT_FALSE(map->computed());
  map->compute(grid);
  EXPECT_TRUE(map->computed());
  EXPECT_EQ(map->squared_cells(grid.index(5, 5)), 25u);
  grid.set(5, 6, Cell::kUnknown);
  map->compute(grid);
  EXPECT_EQ(map->source_revision(), grid.revision());
  EXPECT_EQ(map->squared_cells(grid.index(5, 5)), 1u);
  EXPECT_EQ(map->squared_cells(grid.index(5, 6)), 0u);
}

TEST(ClearanceMapTest, CreateRejectsBadSizes) {
  EXPECT_FALSE(ClearanceMap::create(0, 10, 0.1).ok());
  EXPECT_FALSE(ClearanceMap::create(10, 10, 0.0).ok());
  const auto bad = ClearanceMap::create(10, -3, 0.1);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("height_cells"), std::string::npos);
}

TEST(ClearanceMapTest, ComputingFromAGridOfAnotherSizeIsABrokenContract) {
  const OccupancyGrid grid = make_grid(10, 11, 0.1);
  auto map = ClearanceMap::create(10, 10, 0.1);
  ASSERT_TRUE(map.ok());
  EXPECT_DEATH(map->compute(grid), "invariant violated");
}

}  // namespace
}  // namespace grip
