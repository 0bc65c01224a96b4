#include "grip/world/distance_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "grip/common/random.hpp"

namespace grip {
namespace {

constexpr std::uint32_t kInf = DistanceField::kUnreachable;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

OccupancyGrid make_grid(int w, int h, double res, Cell fill = Cell::kFree) {
  auto grid = OccupancyGrid::create(w, h, res, 0.0, 0.0, fill);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

DistanceField make_field(const OccupancyGrid& grid) {
  auto field = DistanceField::create(grid.width(), grid.height(), grid.resolution());
  EXPECT_TRUE(field.ok());
  return std::move(field).value();
}

// Reference: Bellman-Ford style relaxation to a fixed point, same costs, same corner rule.
std::vector<std::uint32_t> reference_costs(const OccupancyGrid& grid,
                                           const std::vector<bool>& traversable,
                                           const std::vector<std::uint32_t>& targets) {
  const int w = grid.width();
  const int h = grid.height();
  std::vector<std::uint32_t> cost(grid.cell_count(), kInf);
  for (const std::uint32_t t : targets) {
    cost[t] = 0;
  }
  const auto pass = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && traversable[grid.index(x, y)];
  };
  bool changed = true;
  while (changed) {
    changed = false;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::uint32_t from = cost[grid.index(x, y)];
        if (from == kInf) {
          continue;
        }
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || !pass(x + dx, y + dy)) {
              continue;
            }
            const bool diagonal = dx != 0 && dy != 0;
            if (diagonal && !(pass(x + dx, y) && pass(x, y + dy))) {
              continue;
            }
            const std::uint32_t c = from + (diagonal ? 99u : 70u);
            std::uint32_t& to = cost[grid.index(x + dx, y + dy)];
            if (c < to) {
              to = c;
              changed = true;
            }
          }
        }
      }
    }
  }
  return cost;
}

std::vector<bool> free_cells(const OccupancyGrid& grid) {
  std::vector<bool> out(grid.cell_count());
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    out[i] = grid.at(i) == Cell::kFree;
  }
  return out;
}

OccupancyGrid random_grid(Random& random, int w, int h, double density) {
  OccupancyGrid grid = make_grid(w, h, 0.1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (random.uniform01() < density) {
        grid.set(x, y, random.below(2) == 0 ? Cell::kObstacle : Cell::kUnknown);
      }
    }
  }
  return grid;
}

TEST(DistanceFieldTest, CreateRejectsBadSizesNamingThem) {
  const auto bad_width = DistanceField::create(0, 10, 0.1);
  ASSERT_FALSE(bad_width.ok());
  EXPECT_NE(bad_width.error().message.find("width_cells"), std::string::npos);
  const auto bad_resolution = DistanceField::create(10, 10, -1.0);
  ASSERT_FALSE(bad_resolution.ok());
  EXPECT_NE(bad_resolution.error().message.find("resolution_m"), std::string::npos);
  EXPECT_NE(bad_resolution.error().message.find("-1"), std::string::npos);
}

TEST(DistanceFieldTest, MatchesABellmanFordReferenceOnRandomGrids) {
  Random random(5);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 1 + static_cast<int>(random.below(25));
    const int h = 1 + static_cast<int>(random.below(25));
    const OccupancyGrid grid = random_grid(random, w, h, random.uniform(0.0, 0.4));
    std::vector<std::uint32_t> targets;
    const std::uint32_t count = 1 + random.below(4);
    for (std::uint32_t k = 0; k < count; ++k) {
      targets.push_back(random.below(grid.cell_count()));  // may be non-free: still a seed
    }
    DistanceField field = make_field(grid);
    const std::uint32_t reached = field.compute(grid, targets);
    const std::vector<std::uint32_t> expected = reference_costs(grid, free_cells(grid), targets);
    std::uint32_t expected_reached = 0;
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      ASSERT_EQ(field.cost_at(i), expected[i]) << "trial " << trial << " cell " << i;
      expected_reached += expected[i] != kInf ? 1u : 0u;
      if (expected[i] == kInf) {
        EXPECT_EQ(field.at(i), kInfinity);
        EXPECT_FALSE(field.reachable(i));
      } else {
        EXPECT_DOUBLE_EQ(field.at(i), expected[i] * 0.1 / 70.0);
        EXPECT_TRUE(field.reachable(i));
      }
    }
    EXPECT_EQ(reached, expected_reached);
  }
}

TEST(DistanceFieldTest, MatchesTheReferenceWithInflation) {
  Random random(8);
  for (int trial = 0; trial < 30; ++trial) {
    const OccupancyGrid grid = random_grid(random, 30, 24, random.uniform(0.0, 0.08));
    const double inflation = random.uniform(0.0, 0.35);
    auto clearance = ClearanceMap::create_for(grid);
    ASSERT_TRUE(clearance.ok());
    std::vector<bool> traversable(grid.cell_count());
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      traversable[i] = grid.at(i) == Cell::kFree && clearance->clearance_m(i) >= inflation;
    }
    const std::vector<std::uint32_t> targets = {random.below(grid.cell_count())};
    DistanceField field = make_field(grid);
    field.compute(grid, *clearance, targets, inflation);
    const std::vector<std::uint32_t> expected = reference_costs(grid, traversable, targets);
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      ASSERT_EQ(field.cost_at(i), expected[i]) << "trial " << trial << " cell " << i;
      ASSERT_EQ(field.traversable(i), traversable[i]) << "trial " << trial << " cell " << i;
    }
  }
}

TEST(DistanceFieldTest, OneFieldReusedThroughMapChangesEqualsAFreshOneEveryTime) {
  // One field kept through random map changes, its traversable set rebuilt only in the window
  // the clearance update rewrote and its wavefront rerun from other targets each time (the
  // last wavefront's labels cleared, not the whole field), against the reference.
  Random random(13);
  OccupancyGrid grid = random_grid(random, 40, 30, 0.05);
  const double inflation = 0.15;
  auto clearance = ClearanceMap::create_for(grid).value();
  const std::uint32_t exact = clearance.squared_cells_at_least(inflation);
  DistanceField field = make_field(grid);
  field.prepare(grid, clearance, inflation);
  for (int round = 0; round < 40; ++round) {
    const int x0 = static_cast<int>(random.below(36));
    const int y0 = static_cast<int>(random.below(26));
    const CellBox box{x0, y0, x0 + static_cast<int>(random.below(6)),
                      y0 + static_cast<int>(random.below(6))};
    const Cell value = random.below(2) == 0 ? Cell::kFree : Cell::kObstacle;
    CellBox changed;
    for (int y = box.y0; y <= std::min(box.y1, 29); ++y) {
      for (int x = box.x0; x <= std::min(box.x1, 39); ++x) {
        if ((grid.at(grid.index(x, y)) == Cell::kFree) != (value == Cell::kFree)) {
          changed.add(CellBox{x, y, x, y});
        }
        grid.set(x, y, value);
      }
    }
    const CellBox window = clearance.update(grid, changed, exact);
    field.prepare(grid, clearance, inflation, window);
    const std::vector<std::uint32_t> targets = {random.below(grid.cell_count()),
                                                random.below(grid.cell_count())};
    field.propagate(targets);

    const auto fresh_clearance = ClearanceMap::create_for(grid).value();
    std::vector<bool> traversable(grid.cell_count());
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      traversable[i] = grid.at(i) == Cell::kFree && fresh_clearance.clearance_m(i) >= inflation;
    }
    const std::vector<std::uint32_t> expected = reference_costs(grid, traversable, targets);
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      ASSERT_EQ(field.traversable(i), traversable[i]) << "round " << round << " cell " << i;
      ASSERT_EQ(field.cost_at(i), expected[i]) << "round " << round << " cell " << i;
    }
  }
}

TEST(DistanceFieldTest, WavefrontsInSeparateRoomsLeaveNoLabelsBehind) {
  // Walls cut a wide grid into 4 x 2 closed rooms, so each wavefront labels one room (a box
  // of a few columns across many rows of the grid): the next one, from a target in another
  // room, must read exactly as a fresh field's, with nothing left of the rooms before.
  OccupancyGrid grid = make_grid(81, 31, 0.1);
  for (int y = 0; y < 31; ++y) {
    for (int x = 0; x < 81; x += 20) grid.set(x, y, Cell::kObstacle);
  }
  for (int x = 0; x < 81; ++x) {
    grid.set(x, 0, Cell::kObstacle);
    grid.set(x, 15, Cell::kObstacle);
    grid.set(x, 30, Cell::kObstacle);
  }
  Random random(29);
  DistanceField field = make_field(grid);
  field.prepare(grid);
  for (int round = 0; round < 30; ++round) {
    const int room_x = static_cast<int>(random.below(4));
    const int room_y = static_cast<int>(random.below(2));
    const std::vector<std::uint32_t> targets = {
        grid.index(room_x * 20 + 1 + static_cast<int>(random.below(19)),
                   room_y * 15 + 1 + static_cast<int>(random.below(14)))};
    const std::uint32_t reached = field.propagate(targets);
    EXPECT_EQ(reached, 19U * 14U) << "round " << round;
    const std::vector<std::uint32_t> expected = reference_costs(grid, free_cells(grid), targets);
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      ASSERT_EQ(field.cost_at(i), expected[i]) << "round " << round << " cell " << i;
    }
  }
}

TEST(DistanceFieldTest, AWavefrontInStepsSettlesExactlyTheCellsUpToEachLimit) {
  // Each wavefront is run in steps, and left unfinished every other time: the next one, from
  // other targets, must not read what the unfinished one left queued.
  Random random(17);
  OccupancyGrid grid = random_grid(random, 60, 40, 0.2);
  DistanceField field = make_field(grid);
  field.prepare(grid);
  for (int round = 0; round < 20; ++round) {
    const std::vector<std::uint32_t> targets = {random.below(grid.cell_count()),
                                                random.below(grid.cell_count())};
    const std::vector<std::uint32_t> expected = reference_costs(grid, free_cells(grid), targets);
    field.start(targets);
    EXPECT_EQ(field.settled_limit(), 0U);
    const bool finish = round % 2 == 0;
    for (const std::uint32_t limit : {0U, 69U, 70U, 350U, 1000U, 2500U}) {
      if (!finish && limit > 350U) break;
      const bool complete = field.settle(limit);
      if (complete) break;
      EXPECT_EQ(field.settled_limit(), limit);
      for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
        if (expected[i] <= limit) {
          ASSERT_EQ(field.cost_at(i), expected[i]) << "round " << round << " limit " << limit;
        } else if (field.cost_at(i) != kInf) {
          // Queued beyond the limit: reached, at most at its label.
          ASSERT_GE(field.cost_at(i), expected[i]) << "round " << round << " cell " << i;
          ASSERT_NE(expected[i], kInf) << "round " << round << " cell " << i;
        }
      }
    }
    if (!finish) continue;
    EXPECT_TRUE(field.settle(kInf));
    EXPECT_EQ(field.settled_limit(), kInf);
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      ASSERT_EQ(field.cost_at(i), expected[i]) << "round " << round << " cell " << i;
    }
  }
}

TEST(DistanceFieldTest, AWavefrontCutOffAtALimitReadsExactWithinAndTheLimitBeyond) {
  // Random maps, targets and limits, one field reused: within the limit every lookup equals the
  // whole field's; beyond it every traversable cell reads the limit plus one (those cut off from
  // the targets too) and every other one unreachable; the next wavefront reads exact again.
  Random random(23);
  OccupancyGrid grid = random_grid(random, 50, 40, 0.25);
  const std::vector<bool> traversable = free_cells(grid);
  DistanceField field = make_field(grid);
  DistanceField whole = make_field(grid);
  field.prepare(grid);
  int rounds_cut_off = 0;
  int rounds_whole = 0;
  for (int round = 0; round < 30; ++round) {
    const std::vector<std::uint32_t> targets = {random.below(grid.cell_count()),
                                                random.below(grid.cell_count())};
    const std::vector<std::uint32_t> expected = reference_costs(grid, traversable, targets);
    whole.compute(grid, targets);
    const std::uint32_t limit = random.below(3000);
    field.propagate_within(targets, limit);
    const bool cut_off = std::any_of(expected.begin(), expected.end(),
                                     [&](std::uint32_t c) { return c != kInf && c > limit; });
    EXPECT_EQ(field.beyond_cost(), cut_off ? limit + 1 : kInf) << "round " << round;
    ++(cut_off ? rounds_cut_off : rounds_whole);
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      std::uint32_t want = expected[i];
      if (cut_off && expected[i] > limit) want = traversable[i] ? limit + 1 : kInf;
      ASSERT_EQ(field.cost_at(i), want) << "round " << round << " cell " << i;
      const double x = grid.cell_center_x(grid.cell_x(i));
      const double y = grid.cell_center_y(grid.cell_y(i));
      ASSERT_EQ(field.distance_m(x, y), field.at(i));
      // Descending stays within the settled cells, as on the whole field; from beyond the limit
      // it stays, or steps in.
      const std::uint32_t down = field.descend(i, 350);
      if (expected[i] <= limit) {
        ASSERT_EQ(down, whole.descend(i, 350)) << "round " << round << " cell " << i;
      } else if (down != i) {
        ASSERT_LE(field.cost_at(down), limit) << "round " << round << " cell " << i;
      }
    }
    // The next wavefront to the end reads every cell exactly.
    if (round % 3 == 0) {
      field.propagate(targets);
      EXPECT_EQ(field.beyond_cost(), kInf);
      for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
        ASSERT_EQ(field.cost_at(i), expected[i]) << "round " << round << " cell " << i;
      }
    }
  }
  // Both cases came up.
  EXPECT_GT(rounds_cut_off, 0);
  EXPECT_GT(rounds_whole, 0);
}

TEST(DistanceFieldTest, StraightAndDiagonalRunsCostSeventyAndNinetyNinePerCell) {
  const OccupancyGrid grid = make_grid(20, 20, 0.1);
  DistanceField field = make_field(grid);
  const std::vector<std::uint32_t> target = {grid.index(5, 5)};
  EXPECT_EQ(field.compute(grid, target), 400u);
  EXPECT_EQ(field.cost_at(grid.index(5, 5)), 0u);
  EXPECT_EQ(field.cost_at(grid.index(12, 5)), 7u * 70u);
  EXPECT_EQ(field.cost_at(grid.index(5, 0)), 5u * 70u);
  EXPECT_EQ(field.cost_at(grid.index(8, 8)), 3u * 99u);
  EXPECT_EQ(field.cost_at(grid.index(9, 7)), 2u * 99u + 2u * 70u);
  EXPECT_NEAR(field.at(grid.index(12, 5)), 0.7, 1e-12);
  EXPECT_NEAR(field.distance_m(0.85, 0.85), 0.3 * 99.0 / 70.0, 1e-12);
}

TEST(DistanceFieldTest, DiagonalStepsDoNotCutCorners) {
  OccupancyGrid grid = make_grid(2, 2, 1.0);
  grid.set(1, 0, Cell::kObstacle);
  DistanceField field = make_field(grid);
  const std::vector<std::uint32_t> target = {grid.index(0, 0)};
  field.compute(grid, target);
  EXPECT_EQ(field.cost_at(grid.index(1, 1)), 140u);  // around through (0, 1), not 99
  grid.set(0, 1, Cell::kObstacle);
  field.compute(grid, target);
  EXPECT_FALSE(field.reachable(grid.index(1, 1)));  // both sides blocked: no squeezing through
}

TEST(DistanceFieldTest, UnreachableObstacleAndOutsideCellsAreInfinite) {
  OccupancyGrid grid = make_grid(20, 10, 0.1);
  grid.fill_rect(1.0, 0.0, 1.09, 1.0, Cell::kObstacle);  // column 10 walls off the right half
  DistanceField field = make_field(grid);
  const std::vector<std::uint32_t> target = {grid.index(2, 5)};
  EXPECT_EQ(field.compute(grid, target), 100u);
  EXPECT_TRUE(std::isfinite(field.distance_m(0.55, 0.55)));
  EXPECT_EQ(field.distance_m(1.55, 0.55), kInfinity);   // walled off
  EXPECT_EQ(field.distance_m(1.05, 0.55), kInfinity);   // the wall itself
  EXPECT_EQ(field.distance_m(-0.01, 0.55), kInfinity);  // outside
  EXPECT_EQ(field.distance_m(0.5, 1.0), kInfinity);
  EXPECT_EQ(field.distance_m(std::nan(""), 0.5), kInfinity);
}

TEST(DistanceFieldTest, NoTargetsLeavesEverythingUnreachable) {
  const OccupancyGrid grid = make_grid(5, 5, 0.1);
  DistanceField field = make_field(grid);
  EXPECT_EQ(field.compute(grid, std::span<const std::uint32_t>{}), 0u);
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    EXPECT_FALSE(field.reachable(i));
  }
}

TEST(DistanceFieldTest, SeveralTargetsGiveTheMinimumOfTheirFields) {
  Random random(17);
  const OccupancyGrid grid = random_grid(random, 40, 30, 0.15);
  DistanceField both = make_field(grid);
  DistanceField first = make_field(grid);
  DistanceField second = make_field(grid);
  const std::uint32_t a = grid.index(3, 4);
  const std::uint32_t b = grid.index(35, 25);
  const std::vector<std::uint32_t> targets = {a, b};
  both.compute(grid, targets);
  first.compute(grid, std::vector<std::uint32_t>{a});
  second.compute(grid, std::vector<std::uint32_t>{b});
  int finite = 0;
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    EXPECT_EQ(both.cost_at(i), std::min(first.cost_at(i), second.cost_at(i)));
    finite += both.reachable(i) ? 1 : 0;
  }
  EXPECT_GT(finite, 600);
}

TEST(DistanceFieldTest, InflationClosesNarrowPassages) {
  // A wall across the grid at x = 2.0 with a 0.3 m gap near the bottom and a 1.2 m gap at the
  // top; the target is left of the wall.
  OccupancyGrid grid = make_grid(40, 40, 0.1);
  grid.fill_rect(2.0, 0.0, 2.09, 4.0, Cell::kObstacle);
  grid.fill_rect(2.0, 0.5, 2.09, 0.79, Cell::kFree);  // rows 5..7: 0.3 m
  grid.fill_rect(2.0, 2.5, 2.09, 3.69, Cell::kFree);  // rows 25..36: 1.2 m
  const ClearanceMap clearance = ClearanceMap::create_for(grid).value();
  DistanceField field = make_field(grid);
  const std::vector<std::uint32_t> target = {grid.index(10, 6)};
  field.compute(grid, clearance, target, 0.0);
  const double through_gap = field.distance_m(3.05, 0.65);
  EXPECT_NEAR(through_gap, 2.0, 1e-9);  // straight through the narrow gap
  field.compute(grid, clearance, target, 0.25);
  const double around = field.distance_m(3.05, 0.65);
  EXPECT_TRUE(std::isfinite(around));  // through the wide gap instead
  EXPECT_GT(around, 4.0);
  EXPECT_FALSE(field.traversable(grid.index(20, 6)));
  EXPECT_TRUE(field.traversable(grid.index(20, 30)));
  EXPECT_DOUBLE_EQ(field.inflation(), 0.25);
  // Enough inflation closes the wide gap too.
  field.compute(grid, clearance, target, 0.7);
  EXPECT_EQ(field.distance_m(3.05, 0.65), kInfinity);
}

TEST(DistanceFieldTest, WithoutInflationTheClearanceMapIsNotRead) {
  // A stale clearance map (the grid changed since) passes with inflation 0: every free cell is
  // traversable, as for the field computed without one.
  Random random(23);
  OccupancyGrid grid = random_grid(random, 50, 40, 0.05);
  auto clearance = ClearanceMap::create_for(grid);
  ASSERT_TRUE(clearance.ok());
  grid.set(3, 4, Cell::kObstacle);
  DistanceField without = make_field(grid);
  DistanceField with = make_field(grid);
  const std::vector<std::uint32_t> target = {grid.index(25, 20)};
  without.compute(grid, target);
  with.compute(grid, *clearance, target, 0.0);
  EXPECT_FALSE(with.traversable(grid.index(3, 4)));
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    ASSERT_EQ(without.cost_at(i), with.cost_at(i));
  }
}

TEST(DistanceFieldTest, AStaleSharedClearanceMapIsABrokenContract) {
  OccupancyGrid grid = make_grid(10, 10, 0.1);
  auto clearance = ClearanceMap::create_for(grid);
  ASSERT_TRUE(clearance.ok());
  grid.set(1, 1, Cell::kObstacle);
  DistanceField field = make_field(grid);
  const std::vector<std::uint32_t> target = {0};
  EXPECT_DEATH(field.compute(grid, *clearance, target, 0.2), "invariant violated");
}

TEST(DistanceFieldTest, AGridOfAnotherSizeIsABrokenContract) {
  const OccupancyGrid grid = make_grid(10, 10, 0.1);
  auto field = DistanceField::create(10, 12, 0.1);
  ASSERT_TRUE(field.ok());
  const std::vector<std::uint32_t> target = {0};
  EXPECT_DEATH(field->compute(grid, target), "invariant violated");
}

TEST(DistanceFieldTest, FollowsTheGridOrigin) {
  auto created = OccupancyGrid::create(10, 10, 0.5, 100.0, -50.0, Cell::kFree);
  ASSERT_TRUE(created.ok());
  const OccupancyGrid& grid = *created;
  DistanceField field = make_field(grid);
  field.compute(grid, std::vector<std::uint32_t>{grid.index(0, 0)});
  EXPECT_NEAR(field.distance_m(102.2, -49.9), 4 * 0.5, 1e-12);
  EXPECT_EQ(field.distance_m(1.0, 1.0), kInfinity);
}

TEST(DistanceFieldDescendTest, FollowsAShortestPathAroundAWall) {
  // A wall from the bottom up to row 14 at x = 10; the target is on the other side at (15, 2).
  OccupancyGrid grid = make_grid(20, 20, 0.1);
  for (int y = 0; y <= 14; ++y) grid.set(10, y, Cell::kObstacle);
  DistanceField field = make_field(grid);
  field.compute(grid, std::vector<std::uint32_t>{grid.index(15, 2)});
  const std::uint32_t from = grid.index(5, 2);
  // Each step lowers the cost by a step of a shortest path; the end is as far down as asked.
  const std::uint32_t drop = 5 * DistanceField::kOrthogonalCost;
  const std::uint32_t a = field.descend(from, drop);
  EXPECT_GE(field.cost_at(from) - field.cost_at(a), drop);
  EXPECT_LT(field.cost_at(from) - field.cost_at(a), drop + DistanceField::kDiagonalCost);
  // The path goes up and round the wall's top, not toward the target through the wall.
  EXPECT_GT(grid.cell_y(a), 2);
  // Asked for more than the path holds, it ends at the target.
  EXPECT_EQ(field.descend(from, DistanceField::kUnreachable), grid.index(15, 2));
  // An unreachable cell stays where it is.
  EXPECT_EQ(field.descend(grid.index(10, 3), drop), grid.index(10, 3));
}

// Blocks (DistanceField's `block`): the field over blocks of b x b cells equals the plain field
// over a grid of the blocks, a block traversable where one of its cells is.
struct BlockGrid {
  OccupancyGrid grid;  // of the blocks (its cells' values unused)
  std::vector<bool> traversable;
};

BlockGrid block_grid(const OccupancyGrid& grid, const std::vector<bool>& traversable, int b) {
  const int w = (grid.width() + b - 1) / b;
  const int h = (grid.height() + b - 1) / b;
  BlockGrid out{make_grid(w, h, grid.resolution() * b),
                std::vector<bool>(static_cast<std::size_t>(w * h), false)};
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    if (traversable[i])
      out.traversable[out.grid.index(grid.cell_x(i) / b, grid.cell_y(i) / b)] = true;
  }
  return out;
}

std::vector<bool> traversable_cells(const OccupancyGrid& grid, double inflation) {
  const auto clearance = ClearanceMap::create_for(grid).value();
  std::vector<bool> out(grid.cell_count());
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    out[i] = grid.at(i) == Cell::kFree && clearance.clearance_m(i) >= inflation;
  }
  return out;
}

TEST(DistanceFieldBlocksTest, CreateRejectsABlockOutsideItsRangeNamingIt) {
  for (const int block : {0, DistanceField::kMaxBlock + 1}) {
    const auto bad = DistanceField::create(10, 10, 0.1, block);
    ASSERT_FALSE(bad.ok()) << block;
    EXPECT_NE(bad.error().message.find("block must be in [1, 1024] (got " + std::to_string(block)),
              std::string::npos)
        << bad.error().message;
  }
  EXPECT_TRUE(DistanceField::create(10, 10, 0.1, DistanceField::kMaxBlock).ok());
  EXPECT_EQ(DistanceField::block_for(0.001, 2.0, 4.0), DistanceField::kMaxBlock);
}

TEST(DistanceFieldBlocksTest, BlockForKeepsBlocksWithinTheCellSizeAndHalfTheInflation) {
  EXPECT_EQ(DistanceField::block_for(0.1, 0.1, 0.3), 1);
  EXPECT_EQ(DistanceField::block_for(0.05, 0.1, 0.3), 2);
  EXPECT_EQ(DistanceField::block_for(0.025, 0.1, 0.3), 4);
  EXPECT_EQ(DistanceField::block_for(1.0 / 64.0, 0.1, 0.3), 6);
  EXPECT_EQ(DistanceField::block_for(0.02, 0.1, 0.1), 2);  // half the inflation: 0.05 m
  EXPECT_EQ(DistanceField::block_for(0.02, 0.1, 0.0), 1);  // no inflation: walls a cell thick
  EXPECT_EQ(DistanceField::block_for(0.02, 0.0, 0.3), 1);  // the map's own cells
  EXPECT_EQ(DistanceField::block_for(0.2, 0.1, 0.3), 1);   // cells already that large
}

TEST(DistanceFieldBlocksTest, EqualsTheFieldOfTheBlockGridAndReachesEveryCellTheCellsReach) {
  Random random(21);
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE(trial);
    const int w = 1 + static_cast<int>(random.below(60));
    const int h = 1 + static_cast<int>(random.below(60));
    OccupancyGrid grid = random_grid(random, w, h, random.uniform(0.0, 0.05));
    const int b = 1 + static_cast<int>(random.below(5));
    const double inflation = random.uniform(0.0, 0.3);
    const auto clearance = ClearanceMap::create_for(grid).value();
    std::vector<std::uint32_t> targets;
    for (std::uint32_t k = 0, n = 1 + random.below(3); k < n; ++k) {
      targets.push_back(random.below(grid.cell_count()));
    }
    auto field = DistanceField::create(w, h, 0.1, b).value();
    ASSERT_EQ(field.block(), b);
    field.compute(grid, clearance, targets, inflation);

    const std::vector<bool> cells = traversable_cells(grid, inflation);
    const BlockGrid blocks = block_grid(grid, cells, b);
    const auto block_of = [&](std::uint32_t i) {
      return blocks.grid.index(grid.cell_x(i) / b, grid.cell_y(i) / b);
    };
    std::vector<std::uint32_t> block_targets;
    for (const std::uint32_t t : targets) block_targets.push_back(block_of(t));
    const std::vector<std::uint32_t> expected =
        reference_costs(blocks.grid, blocks.traversable, block_targets);
    // Every cell reads its block's label, in the grid's cost units (a block is b cells), and
    // where the cells reach, so do the blocks.
    auto plain = DistanceField::create(w, h, 0.1).value();
    plain.compute(grid, clearance, targets, inflation);
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      const std::uint32_t e = expected[block_of(i)];
      ASSERT_EQ(field.traversable(i), blocks.traversable[block_of(i)]) << "cell " << i;
      ASSERT_EQ(field.cost_at(i), e == kInf ? kInf : e * static_cast<std::uint32_t>(b))
          << "cell " << i;
      const double x = grid.cell_center_x(grid.cell_x(i));
      const double y = grid.cell_center_y(grid.cell_y(i));
      ASSERT_EQ(field.cell_at(x, y), i);
      ASSERT_EQ(field.distance_m(x, y), field.at(i));
      if (plain.reachable(i)) {
        ASSERT_TRUE(field.reachable(i)) << "cell " << i;
      }
    }
  }
}

TEST(DistanceFieldBlocksTest, AFieldOnBlocksKeptThroughMapChangesEqualsAFreshOne) {
  // The windowed prepare() rebuilds every block that holds a cell of the window.
  Random random(34);
  OccupancyGrid grid = random_grid(random, 41, 29, 0.03);
  const double inflation = 0.2;
  const int b = 3;
  auto clearance = ClearanceMap::create_for(grid).value();
  const std::uint32_t exact = clearance.squared_cells_at_least(inflation);
  auto field = DistanceField::create(41, 29, 0.1, b).value();
  field.prepare(grid, clearance, inflation);
  for (int round = 0; round < 40; ++round) {
    SCOPED_TRACE(round);
    const int x0 = static_cast<int>(random.below(38));
    const int y0 = static_cast<int>(random.below(26));
    const Cell value = random.below(2) == 0 ? Cell::kFree : Cell::kObstacle;
    CellBox changed;
    for (int y = y0; y <= std::min(y0 + static_cast<int>(random.below(5)), 28); ++y) {
      for (int x = x0; x <= std::min(x0 + static_cast<int>(random.below(5)), 40); ++x) {
        if ((grid.at(grid.index(x, y)) == Cell::kFree) != (value == Cell::kFree)) {
          changed.add(CellBox{x, y, x, y});
        }
        grid.set(x, y, value);
      }
    }
    field.prepare(grid, clearance, inflation, clearance.update(grid, changed, exact));
    const std::vector<std::uint32_t> targets = {random.below(grid.cell_count())};
    field.propagate(targets);
    auto fresh = DistanceField::create(41, 29, 0.1, b).value();
    fresh.compute(grid, ClearanceMap::create_for(grid).value(), targets, inflation);
    for (std::uint32_t i = 0; i < field.cell_count(); ++i) {
      ASSERT_EQ(field.traversable(i), fresh.traversable(i)) << "cell " << i;
      ASSERT_EQ(field.cost_at(i), fresh.cost_at(i)) << "cell " << i;
    }
  }
}

TEST(DistanceFieldBlocksTest, BlocksOfAtMostHalfTheInflationGoRoundAWallOneCellThick) {
  // A 2 cm map, 3 m x 2.4 m, with a wall one cell thick at x = 1.5 m from the floor to 1.4 m: the
  // cells on either side of it are close enough to share a block of 10 cm, but not traversable
  // (0.3 m of clearance); those a block further are, and blocks of them must not meet across it.
  OccupancyGrid grid = make_grid(150, 120, 0.02);
  for (int y = 0; y < 70; ++y) grid.set(75, y, Cell::kObstacle);
  const double inflation = 0.3;
  const int b = DistanceField::block_for(0.02, 0.1, inflation);
  ASSERT_EQ(b, 5);
  const auto clearance = ClearanceMap::create_for(grid).value();
  int target_x = 0;
  int target_y = 0;
  ASSERT_TRUE(grid.to_cell(1.1, 0.4, target_x, target_y));
  const std::vector<std::uint32_t> target = {grid.index(target_x, target_y)};
  auto blocks = DistanceField::create(150, 120, 0.02, b).value();
  blocks.compute(grid, clearance, target, inflation);
  auto cells = DistanceField::create(150, 120, 0.02).value();
  cells.compute(grid, clearance, target, inflation);
  // Across the wall, 0.8 m away in a straight line: round its top (at 1.4 m, passed 0.3 m
  // above it), more than 2 x 1.3 m.
  const double across = blocks.distance_m(1.9, 0.4);
  EXPECT_GT(across, 2.6);
  // Within a few blocks of the cells' own field (the seeds and the steps move by a block).
  EXPECT_NEAR(across, cells.distance_m(1.9, 0.4), 0.3);
  EXPECT_NEAR(blocks.distance_m(1.1, 1.8), cells.distance_m(1.1, 1.8), 0.2);
  // Descending from there climbs toward the wall's top, block by block, by the drop asked for.
  const std::uint32_t from = blocks.cell_at(1.9, 0.4);
  const std::uint32_t drop = 25 * DistanceField::kOrthogonalCost;  // half a metre of 2 cm cells
  const std::uint32_t ahead = blocks.descend(from, drop);
  EXPECT_GE(blocks.cost_at(from) - blocks.cost_at(ahead), drop);
  EXPECT_LT(blocks.cost_at(from) - blocks.cost_at(ahead), drop + 5 * DistanceField::kDiagonalCost);
  EXPECT_GT(grid.cell_y(ahead), grid.cell_y(from) + 10);
  EXPECT_TRUE(blocks.traversable(ahead));
}

}  // namespace
}  // namespace grip
