#include "grip/world/nearest_source_field.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "grip/common/random.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {
namespace {

// GIVEN random grids and sources added one by one, THEN after every addition each cell's cost
// equals a fresh multi-source wavefront's, and its nearest source really is that far away.
TEST(NearestSourceField, MatchesAFreshWavefrontAfterEveryAddedSource) {
  Random rng(17);
  for (int trial = 0; trial < 12; ++trial) {
    const int w = 12 + static_cast<int>(rng.below(10));
    const int h = 9 + static_cast<int>(rng.below(10));
    OccupancyGrid grid = OccupancyGrid::create(w, h, 0.1, 0.0, 0.0, Cell::kFree).value();
    for (int i = 0; i < w * h / 4; ++i) {
      grid.set(static_cast<int>(rng.below(static_cast<std::uint32_t>(w))),
               static_cast<int>(rng.below(static_cast<std::uint32_t>(h))),
               rng.uniform01() < 0.7 ? Cell::kObstacle : Cell::kUnknown);
    }
    DistanceField metric = DistanceField::create(w, h, 0.1).value();
    metric.prepare(grid);
    NearestSourceField field = NearestSourceField::create(w, h).value();
    field.reset();
    DistanceField reference = DistanceField::create(w, h, 0.1).value();
    DistanceField single = DistanceField::create(w, h, 0.1).value();
    std::vector<std::uint32_t> sources;
    for (int added = 0; added < 8; ++added) {
      const std::uint32_t c = rng.below(grid.cell_count());
      field.add_source(metric, c);
      if (metric.traversable(c)) sources.push_back(c);
      if (sources.empty()) continue;
      (void)reference.compute(grid, sources);
      for (std::uint32_t cell = 0; cell < grid.cell_count(); ++cell) {
        ASSERT_EQ(field.cost_to_source(cell), reference.cost_at(cell)) << "cell " << cell;
        const std::uint32_t nearest = field.nearest_source(cell);
        if (!reference.reachable(cell)) {
          EXPECT_EQ(nearest, NearestSourceField::kNoCell);
          continue;
        }
        const std::array<std::uint32_t, 1> one{nearest};
        (void)single.compute(grid, one);
        EXPECT_EQ(single.cost_at(cell), reference.cost_at(cell)) << "cell " << cell;
      }
    }
  }
}

TEST(NearestSourceField, IgnoresSourcesThatAreNotTraversableAndResetForgetsAll) {
  OccupancyGrid grid = OccupancyGrid::create(10, 10, 0.1, 0.0, 0.0, Cell::kFree).value();
  grid.set(5, 5, Cell::kObstacle);
  DistanceField metric = DistanceField::create(10, 10, 0.1).value();
  metric.prepare(grid);
  NearestSourceField field = NearestSourceField::create(10, 10).value();
  field.reset();
  field.add_source(metric, grid.index(5, 5));
  EXPECT_EQ(field.nearest_source(grid.index(0, 0)), NearestSourceField::kNoCell);
  field.add_source(metric, grid.index(1, 1));
  EXPECT_EQ(field.nearest_source(grid.index(9, 9)), grid.index(1, 1));
  field.reset();
  EXPECT_EQ(field.nearest_source(grid.index(9, 9)), NearestSourceField::kNoCell);
}

TEST(NearestSourceField, RefusesEmptySizes) {
  EXPECT_FALSE(NearestSourceField::create(0, 5));
  EXPECT_FALSE(NearestSourceField::create(5, -1));
}

}  // namespace
}  // namespace grip
