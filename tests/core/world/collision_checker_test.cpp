#include "grip/world/collision_checker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "grip/common/random.hpp"

namespace grip {
namespace {

constexpr double kPi = std::numbers::pi;

OccupancyGrid make_grid(int w, int h, double res, Cell fill = Cell::kFree) {
  auto grid = OccupancyGrid::create(w, h, res, 0.0, 0.0, fill);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

CollisionChecker make_checker(const OccupancyGrid& grid, Footprint footprint, double margin) {
  auto checker = CollisionChecker::create(grid, footprint, margin);
  EXPECT_TRUE(checker.ok()) << (checker.ok() ? "" : checker.error().message);
  return std::move(checker).value();
}

// Exact reference: the closed rectangle against every closed non-free cell square by the
// separating axis theorem, and against the outside of the grid (a convex set stays inside the
// open grid rectangle iff all its corners do). Independent of the checker's scanline.
bool reference_is_free(const OccupancyGrid& grid, const Footprint& fp, double x, double y,
                       double theta) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const double res = grid.resolution();
  std::array<double, 4> cx{};
  std::array<double, 4> cy{};
  const std::array<std::array<double, 2>, 4> body = {{{fp.front_m, -fp.half_width_m},
                                                      {fp.front_m, fp.half_width_m},
                                                      {-fp.rear_m, fp.half_width_m},
                                                      {-fp.rear_m, -fp.half_width_m}}};
  for (std::size_t k = 0; k < 4; ++k) {
    cx[k] = (x + c * body[k][0] - s * body[k][1] - grid.origin_x()) / res;
    cy[k] = (y + s * body[k][0] + c * body[k][1] - grid.origin_y()) / res;
    if (!(cx[k] > 0.0 && cy[k] > 0.0 && cx[k] < grid.width() && cy[k] < grid.height())) {
      return false;
    }
  }
  const std::array<std::array<double, 2>, 4> axes = {{{1, 0}, {0, 1}, {c, s}, {-s, c}}};
  // Only cells near the corners' bounding box can meet the rectangle.
  const auto [xlo, xhi] = std::minmax_element(cx.begin(), cx.end());
  const auto [ylo, yhi] = std::minmax_element(cy.begin(), cy.end());
  const int i0 = std::max(static_cast<int>(*xlo) - 2, 0);
  const int i1 = std::min(static_cast<int>(*xhi) + 2, grid.width() - 1);
  const int j0 = std::max(static_cast<int>(*ylo) - 2, 0);
  const int j1 = std::min(static_cast<int>(*yhi) + 2, grid.height() - 1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      if (grid.at(i, j) == Cell::kFree) {
        continue;
      }
      const std::array<double, 4> sx = {double(i), double(i + 1), double(i + 1), double(i)};
      const std::array<double, 4> sy = {double(j), double(j), double(j + 1), double(j + 1)};
      bool separated = false;
      for (const auto& axis : axes) {
        double rmin = std::numeric_limits<double>::infinity();
        double rmax = -rmin;
        double qmin = rmin;
        double qmax = -rmin;
        for (std::size_t k = 0; k < 4; ++k) {
          const double pr = cx[k] * axis[0] + cy[k] * axis[1];
          const double pq = sx[k] * axis[0] + sy[k] * axis[1];
          rmin = std::min(rmin, pr);
          rmax = std::max(rmax, pr);
          qmin = std::min(qmin, pq);
          qmax = std::max(qmax, pq);
        }
        if (rmax < qmin || qmax < rmin) {
          separated = true;
          break;
        }
      }
      if (!separated) {
        return false;
      }
    }
  }
  return true;
}

const Footprint kRobot{0.35, 0.15, 0.2};  // 0.5 m x 0.4 m, reference 0.15 m from the rear

TEST(CollisionCheckerTest, CreateRejectsBadFootprintsAndMarginsNamingThem) {
  const OccupancyGrid grid = make_grid(10, 10, 0.1);
  const auto expect_error = [&](Footprint fp, double margin, const std::string& name,
                                const std::string& value) {
    const auto result = CollisionChecker::create(grid, fp, margin);
    ASSERT_FALSE(result.ok()) << name;
    EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(result.error().message.find(name), std::string::npos) << result.error().message;
    EXPECT_NE(result.error().message.find(value), std::string::npos) << result.error().message;
  };
  const double nan = std::nan("");
  expect_error({0.3, 0.2, 0.0}, 0.0, "half_width_m", "0");
  expect_error({0.3, 0.2, -0.1}, 0.0, "half_width_m", "-0.1");
  expect_error({nan, 0.2, 0.2}, 0.0, "front_m", "nan");
  expect_error({0.3, std::numeric_limits<double>::infinity(), 0.2}, 0.0, "rear_m", "inf");
  expect_error({0.2, -0.2, 0.2}, 0.0, "front_m + footprint.rear_m", "0");
  expect_error({0.3, 0.2, 0.2}, -0.01, "margin_m", "-0.01");
  expect_error({0.3, 0.2, 0.2}, nan, "margin_m", "nan");
  EXPECT_TRUE(CollisionChecker::create(grid, {0.5, -0.1, 0.2}, 0.0).ok());
  const auto shared = CollisionChecker::create(grid, {0.3, 0.2, 0.2}, 0.0, -0.5);
  ASSERT_FALSE(shared.ok());
  EXPECT_NE(shared.error().message.find("shared_clearance_m"), std::string::npos);
}

TEST(CollisionCheckerTest, ExtremeResolutionsAndPosesNeverOverflow) {
  // Every float-to-int conversion saturates or is checked first (run under UBSan with
  // float-cast-overflow): no resolution, pose or heading can index outside the grid.
  constexpr double kHuge = 1e300;
  const double inf = std::numeric_limits<double>::infinity();
  for (const double resolution : {4.9e-324, 1e-300, 1e-6, 0.1, 1e6, 1e300}) {
    auto grid = OccupancyGrid::create(70, 65, resolution, -3.0, 2.0, Cell::kFree);
    ASSERT_TRUE(grid.ok());
    auto checker = CollisionChecker::create(*grid, Footprint{0.6, 0.15, 0.2}, 0.05, 0.3);
    ASSERT_TRUE(checker.ok()) << checker.error().message;
    for (const double x : {-kHuge, -3.0, 0.0, 1.0, 3.5, kHuge, inf}) {
      for (const double theta : {0.0, 0.8, -2.0, 1e20}) {
        static_cast<void>(checker->is_free(x, x * 0.5, theta));
        static_cast<void>(checker->rectangle_is_free_exact(x, 2.5, theta));
      }
    }
    checker->refresh();
  }
}

TEST(CollisionCheckerTest, ReportsItsFootprintAndMargin) {
  const OccupancyGrid grid = make_grid(10, 10, 0.1);
  const CollisionChecker checker = make_checker(grid, kRobot, 0.05);
  EXPECT_EQ(checker.footprint().front_m, 0.35);
  EXPECT_EQ(checker.margin(), 0.05);
  EXPECT_DOUBLE_EQ(checker.checked_footprint().half_width_m, 0.25);
  EXPECT_DOUBLE_EQ(Footprint({0.35, 0.15, 0.2}).circumscribed_radius(), std::hypot(0.35, 0.2));
  EXPECT_FALSE(checker.stale());
}

TEST(CollisionCheckerTest, ACornerJustInsideAnObstacleCellCollidesAndJustOutsideIsFree) {
  OccupancyGrid grid = make_grid(50, 50, 0.1);
  grid.set(21, 24, Cell::kObstacle);  // [2.1, 2.2] x [2.4, 2.5]
  const Footprint fp{0.3, 0.3, 0.2};
  const CollisionChecker checker = make_checker(grid, fp, 0.0);
  // At 30 degrees the front-left corner is the top vertex, at x = 2 + 0.3 c - 0.2 s = 2.1598,
  // y = y0 + 0.3 s + 0.2 c = y0 + 0.3232.
  const double theta = kPi / 6.0;
  const double top = 0.3 * std::sin(theta) + 0.2 * std::cos(theta);
  EXPECT_FALSE(checker.is_free(2.0, 2.4 - top + 0.003, theta));
  EXPECT_TRUE(checker.is_free(2.0, 2.4 - top - 0.003, theta));
  EXPECT_FALSE(reference_is_free(grid, fp, 2.0, 2.4 - top + 0.003, theta));
  EXPECT_TRUE(reference_is_free(grid, fp, 2.0, 2.4 - top - 0.003, theta));
}

TEST(CollisionCheckerTest, ACellInTheBoundingBoxButOffTheRotatedRectangleIsFree) {
  const Footprint fp{0.3, 0.3, 0.2};
  // At 45 degrees around (2.05, 2.05) the front edge lies on x + y = 4.524.
  OccupancyGrid off = make_grid(50, 50, 0.1);
  off.set(23, 23, Cell::kObstacle);  // nearest corner (2.3, 2.3): x + y = 4.6, off the edge
  OccupancyGrid on = make_grid(50, 50, 0.1);
  on.set(22, 23, Cell::kObstacle);  // corner (2.2, 2.3): x + y = 4.5, across the edge
  const CollisionChecker off_checker = make_checker(off, fp, 0.0);
  const CollisionChecker on_checker = make_checker(on, fp, 0.0);
  EXPECT_TRUE(off_checker.is_free(2.05, 2.05, kPi / 4.0));
  EXPECT_FALSE(on_checker.is_free(2.05, 2.05, kPi / 4.0));
}

TEST(CollisionCheckerTest, TheRectangleNotJustItsReferencePointIsChecked) {
  OccupancyGrid grid = make_grid(40, 40, 0.1);
  grid.set(13, 10, Cell::kObstacle);  // [1.3, 1.4] x [1.0, 1.1]
  const CollisionChecker checker = make_checker(grid, kRobot, 0.0);
  // Reference cell (10, 10) is free, but the front (to x = 1.4) overlaps the obstacle.
  EXPECT_EQ(grid.at(10, 10), Cell::kFree);
  EXPECT_FALSE(checker.is_free(1.05, 1.05, 0.0));
  EXPECT_FALSE(checker.fast_path_free(1.05, 1.05));
  // Turned around, the short rear (0.15 m) stops at x = 0.9 + ... and misses it.
  EXPECT_TRUE(checker.is_free(1.05, 1.05, kPi));
  // The side (half width 0.2) reaches it when turned by 90 degrees and moved.
  EXPECT_FALSE(checker.is_free(1.15, 1.05, kPi / 2.0));
}

TEST(CollisionCheckerTest, AnUnknownCellCountsAsACollision) {
  OccupancyGrid grid = make_grid(40, 40, 0.1);
  const CollisionChecker clear = make_checker(grid, kRobot, 0.0);
  EXPECT_TRUE(clear.is_free(2.0, 2.0, 0.3));
  OccupancyGrid unknown = make_grid(40, 40, 0.1);
  unknown.set(21, 20, Cell::kUnknown);
  const CollisionChecker checker = make_checker(unknown, kRobot, 0.0);
  EXPECT_FALSE(checker.is_free(2.0, 2.0, 0.3));
  EXPECT_FALSE(checker.rectangle_is_free_exact(2.0, 2.0, 0.3));
}

TEST(CollisionCheckerTest, TouchingTheGridBorderCollidesAndStayingInsideIsFree) {
  // 0.25 m cells make the coordinates below exact.
  const OccupancyGrid grid = make_grid(20, 20, 0.25);
  const Footprint fp{0.5, 0.5, 0.25};
  const CollisionChecker checker = make_checker(grid, fp, 0.0);
  EXPECT_FALSE(checker.is_free(0.5, 2.0, 0.0));  // rear edge exactly on x = 0
  EXPECT_TRUE(checker.is_free(0.51, 2.0, 0.0));
  EXPECT_FALSE(checker.is_free(2.0, 4.75, 0.0));  // left side exactly on y = 5
  EXPECT_TRUE(checker.is_free(2.0, 4.74, 0.0));
  EXPECT_FALSE(checker.is_free(4.6, 2.0, 0.0));   // front beyond x = 5
  EXPECT_FALSE(checker.is_free(-1.0, 2.0, 0.0));  // reference point outside
  EXPECT_FALSE(checker.is_free(2.0, 100.0, 0.0));
}

TEST(CollisionCheckerTest, TouchingAnObstacleCellEdgeExactlyCountsAsCollision) {
  OccupancyGrid grid = make_grid(20, 20, 0.25);
  grid.set(10, 8, Cell::kObstacle);  // [2.5, 2.75] x [2.0, 2.25]
  const CollisionChecker checker = make_checker(grid, {0.5, 0.5, 0.25}, 0.0);
  EXPECT_FALSE(checker.is_free(2.0, 2.1, 0.0));  // front edge on x = 2.5
  EXPECT_TRUE(checker.is_free(1.99, 2.1, 0.0));
  EXPECT_FALSE(checker.is_free(2.0, 1.75, 0.0));  // front-left corner at (2.5, 2.0): a corner
  EXPECT_TRUE(checker.is_free(2.0, 1.74, 0.0));
}

TEST(CollisionCheckerTest, TheMarginGrowsTheCheckedRectangleOnEverySide) {
  OccupancyGrid grid = make_grid(40, 40, 0.1);
  grid.set(20, 25, Cell::kObstacle);  // [2.0, 2.1] x [2.5, 2.6]
  // Left side at y = 2.0 + 0.2 = 2.2 without margin, 2.55 with a 0.35 margin... use 0.25.
  const CollisionChecker thin = make_checker(grid, kRobot, 0.0);
  const CollisionChecker padded = make_checker(grid, kRobot, 0.35);
  EXPECT_TRUE(thin.is_free(2.05, 2.0, 0.0));
  EXPECT_FALSE(padded.is_free(2.05, 2.0, 0.0));
  EXPECT_TRUE(reference_is_free(grid, kRobot, 2.05, 2.0, 0.0));
  EXPECT_FALSE(reference_is_free(grid, kRobot.inflated(0.35), 2.05, 2.0, 0.0));
}

TEST(CollisionCheckerTest, NonFiniteStatesAreNeverFree) {
  const OccupancyGrid grid = make_grid(40, 40, 0.1);
  const CollisionChecker checker = make_checker(grid, kRobot, 0.0);
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(checker.is_free(2.0, 2.0, 1.0));
  EXPECT_FALSE(checker.is_free(nan, 2.0, 1.0));
  EXPECT_FALSE(checker.is_free(2.0, nan, 1.0));
  EXPECT_FALSE(checker.is_free(2.0, 2.0, nan));
  EXPECT_FALSE(checker.is_free(inf, 2.0, 1.0));
  EXPECT_FALSE(checker.is_free(2.0, 2.0, inf));
}

// Random grids and poses: is_free and the exact path must agree with the reference exactly,
// and the fast path may only ever say "free" where the reference does.
void compare_with_reference(std::uint64_t seed, const Footprint& fp, double margin, double res,
                            int poses, int width = 48, int height = 36) {
  Random random(seed);
  OccupancyGrid grid = make_grid(width, height, res);
  for (int k = 0; k < 40; ++k) {
    const int cx = static_cast<int>(random.below(static_cast<std::uint32_t>(width)));
    const int cy = static_cast<int>(random.below(static_cast<std::uint32_t>(height)));
    grid.set(cx, cy, random.below(3) == 0 ? Cell::kUnknown : Cell::kObstacle);
  }
  grid.fill_rect(3.0 * res, 20.0 * res, 9.0 * res, 23.0 * res, Cell::kObstacle);  // a wall
  const CollisionChecker checker = make_checker(grid, fp, margin);
  const Footprint checked = fp.inflated(margin);
  int free_count = 0;
  int fast_count = 0;
  for (int n = 0; n < poses; ++n) {
    const double x = random.uniform(-0.1 * grid.width_m(), 1.1 * grid.width_m());
    const double y = random.uniform(-0.1 * grid.height_m(), 1.1 * grid.height_m());
    const double theta = random.uniform(-4.0, 4.0);
    const bool expected = reference_is_free(grid, checked, x, y, theta);
    ASSERT_EQ(checker.is_free(x, y, theta), expected)
        << "pose " << n << ": " << x << ", " << y << ", " << theta;
    ASSERT_EQ(checker.rectangle_is_free_exact(x, y, theta), expected)
        << "pose " << n << ": " << x << ", " << y << ", " << theta;
    // A smaller margin for this call: the chassis grown by it, whichever tier answers; a larger
    // one, or one not finite, is the checker's own.
    const double smaller = margin * random.uniform01();
    ASSERT_EQ(checker.is_free(x, y, theta, smaller),
              reference_is_free(grid, fp.inflated(smaller), x, y, theta))
        << "pose " << n << ": " << x << ", " << y << ", " << theta << " margin " << smaller;
    ASSERT_EQ(checker.is_free(x, y, theta, margin + 1.0), expected);
    ASSERT_EQ(checker.is_free(x, y, theta, std::nan("")), expected);
    if (checker.fast_path_free(x, y)) {
      ASSERT_TRUE(expected) << "fast path unsound at " << x << ", " << y << ", " << theta;
      ++fast_count;
    }
    free_count += expected ? 1 : 0;
  }
  // The comparison covers both answers and both paths.
  EXPECT_GT(free_count, poses / 10);
  EXPECT_LT(free_count, poses - poses / 10);
  EXPECT_GT(fast_count, 0);
}

TEST(CollisionCheckerTest, AgreesExactlyWithASeparatingAxisReferenceOnRandomPoses) {
  compare_with_reference(11, kRobot, 0.0, 0.1, 6000);
}

TEST(CollisionCheckerTest, AgreesWithTheReferenceWithAMarginAndCoarseCells) {
  compare_with_reference(12, kRobot, 0.05, 0.25, 6000);
}

TEST(CollisionCheckerTest, AgreesWithTheReferenceForAChassisAheadOfItsReferencePoint) {
  compare_with_reference(13, Footprint{0.6, -0.1, 0.15}, 0.02, 0.1, 4000, 80, 60);
}

TEST(CollisionCheckerTest, AgreesWithTheReferenceAtAxisAlignedHeadings) {
  Random random(21);
  OccupancyGrid grid = make_grid(30, 30, 0.1);
  for (int k = 0; k < 30; ++k) {
    grid.set(static_cast<int>(random.below(30)), static_cast<int>(random.below(30)),
             Cell::kObstacle);
  }
  const CollisionChecker checker = make_checker(grid, kRobot, 0.0);
  for (int n = 0; n < 3000; ++n) {
    const double x = random.uniform(0.0, 3.0);
    const double y = random.uniform(0.0, 3.0);
    const double theta = static_cast<double>(random.below(4)) * kPi / 2.0;
    ASSERT_EQ(checker.is_free(x, y, theta), reference_is_free(grid, kRobot, x, y, theta))
        << x << ", " << y << ", " << theta;
  }
}

TEST(CollisionCheckerTest, TheFastPathDecidesInOpenSpace) {
  const OccupancyGrid grid = make_grid(100, 100, 0.1);
  const CollisionChecker checker = make_checker(grid, kRobot, 0.05);
  EXPECT_TRUE(checker.fast_path_free(5.0, 5.0));
  EXPECT_TRUE(checker.is_free(5.0, 5.0, 2.0));
  // Within the circumscribed radius of the border the exact path must decide.
  EXPECT_FALSE(checker.fast_path_free(0.5, 5.0));
  EXPECT_TRUE(checker.is_free(0.5, 5.0, 0.0));
}

TEST(CollisionCheckerTest, RefreshPicksUpGridChanges) {
  OccupancyGrid grid = make_grid(60, 60, 0.1);
  CollisionChecker checker = make_checker(grid, kRobot, 0.0);
  ASSERT_TRUE(checker.is_free(3.0, 3.0, 0.0));
  ASSERT_TRUE(checker.fast_path_free(3.0, 3.0));
  grid.set(32, 30, Cell::kObstacle);
  EXPECT_TRUE(checker.stale());
  checker.refresh();
  EXPECT_FALSE(checker.stale());
  EXPECT_FALSE(checker.fast_path_free(3.0, 3.0));
  EXPECT_FALSE(checker.is_free(3.0, 3.0, 0.0));
  // The refreshed clearance equals one computed from scratch.
  auto fresh = ClearanceMap::create_for(grid);
  ASSERT_TRUE(fresh.ok());
  for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
    ASSERT_EQ(checker.clearance().squared_cells(i), fresh->squared_cells(i));
  }
  grid.set(32, 30, Cell::kFree);
  checker.refresh();
  EXPECT_TRUE(checker.is_free(3.0, 3.0, 0.0));
  EXPECT_TRUE(checker.fast_path_free(3.0, 3.0));
}

TEST(CollisionCheckerTest, ARefreshNearTheChangeAnswersAsACheckerBuiltAfresh) {
  // GIVEN a checker whose clearance is also shared up to 0.4 m, on a grid changed box by box
  Random random(31);
  // (wide: a row holds several 64-cell words of the checker's bit grids, most outside a change)
  OccupancyGrid grid = make_grid(300, 50, 0.1);
  auto created = CollisionChecker::create(grid, kRobot, 0.02, 0.4);
  ASSERT_TRUE(created.ok());
  CollisionChecker checker = std::move(created).value();
  for (int step = 0; step < 12; ++step) {
    const int x0 = static_cast<int>(random.below(294));
    const int y0 = static_cast<int>(random.below(44));
    const CellBox changed{x0, y0, x0 + 5, y0 + 5};
    for (int y = changed.y0; y <= changed.y1; ++y) {
      for (int x = changed.x0; x <= changed.x1; ++x) {
        grid.set(x, y, random.below(3) == 0 ? Cell::kObstacle : Cell::kFree);
      }
    }
    // WHEN it is refreshed near the change only
    ASSERT_TRUE(checker.stale());
    checker.refresh(changed);
    ASSERT_FALSE(checker.stale());
    // THEN it answers every pose, on both paths, as a checker created on the new grid, and a
    // distance field sharing its clearance finds the same cells traversable
    const CollisionChecker fresh = make_checker(grid, kRobot, 0.02);
    for (int n = 0; n < 1500; ++n) {
      const double x = random.uniform(0.0, grid.width_m());
      const double y = random.uniform(0.0, grid.height_m());
      const double theta = random.uniform(-4.0, 4.0);
      ASSERT_EQ(checker.is_free(x, y, theta), fresh.is_free(x, y, theta))
          << "step " << step << " pose " << x << ", " << y << ", " << theta;
      ASSERT_EQ(checker.fast_path_free(x, y), fresh.fast_path_free(x, y))
          << "step " << step << " at " << x << ", " << y;
    }
    for (int cy = 0; cy < grid.height(); ++cy) {
      for (int cx = 0; cx < grid.width(); ++cx) {
        const double x = grid.cell_center_x(cx);
        const double y = grid.cell_center_y(cy);
        ASSERT_EQ(checker.is_free(x, y, 0.3), fresh.is_free(x, y, 0.3))
            << "step " << step << " cell " << cx << ", " << cy;
        ASSERT_EQ(checker.fast_path_free(x, y), fresh.fast_path_free(x, y))
            << "step " << step << " cell " << cx << ", " << cy;
      }
    }
    const std::uint32_t at_least = checker.clearance().squared_cells_at_least(0.4);
    ASSERT_LE(at_least, checker.clearance().exact_up_to());
    for (std::uint32_t i = 0; i < grid.cell_count(); ++i) {
      ASSERT_EQ(checker.clearance().squared_cells(i) >= at_least,
                fresh.clearance().squared_cells(i) >= at_least)
          << "step " << step << " cell " << i;
    }
  }
}

TEST(CollisionCheckerTest, AnOffsetGridOriginIsHonoured) {
  auto created = OccupancyGrid::create(40, 40, 0.1, -10.0, 5.0, Cell::kFree);
  ASSERT_TRUE(created.ok());
  OccupancyGrid& grid = *created;
  grid.set(20, 20, Cell::kObstacle);  // [-8.0, -7.9] x [7.0, 7.1]
  const CollisionChecker checker = make_checker(grid, kRobot, 0.0);
  EXPECT_FALSE(checker.is_free(-7.95, 7.05, 0.0));
  EXPECT_TRUE(checker.is_free(-7.0, 6.0, 0.0));
  EXPECT_FALSE(checker.is_free(1.0, 1.0, 0.0));  // outside this grid
}

}  // namespace
}  // namespace grip
