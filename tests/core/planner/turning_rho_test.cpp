#include "grip/planner/turning_rho.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "grip/common/random.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {
namespace {

constexpr double kPi = std::numbers::pi;

// Hand-computed lengths for a turning radius R (vehicle frame: x ahead, y to the left).
TEST(TurningDistanceTest, HandComputedCases) {
  const double r = 0.5;
  // Straight ahead or straight behind: the distance itself, reversing costs no more.
  EXPECT_NEAR(TurningDistance::exact_m(r, 2.0, 0.0), 2.0, 1e-12);
  EXPECT_NEAR(TurningDistance::exact_m(r, -1.5, 0.0), 1.5, 1e-12);
  // On the turning circle, a diameter to the side: half a turn at full lock, forward or back.
  EXPECT_NEAR(TurningDistance::exact_m(r, 0.0, 2.0 * r), kPi * r, 1e-12);
  EXPECT_NEAR(TurningDistance::exact_m(r, 0.0, -2.0 * r), kPi * r, 1e-12);
  // A quarter turn lands at (R, R).
  EXPECT_NEAR(TurningDistance::exact_m(r, r, r), 0.5 * kPi * r, 1e-12);
  // Half a radius to the side (inside the left circle): back up sqrt(3)/2 R, then a sixth of
  // a turn forward onto the point; turning toward it from the right circle is longer.
  EXPECT_NEAR(TurningDistance::exact_m(r, 0.0, 0.5 * r), (std::sqrt(3.0) / 2 + kPi / 3) * r, 1e-9);
  // Turning in place is impossible: a point 1 cm to the side costs ten times its distance
  // (back up, then turn onto it: sqrt(R^2 - (R - 0.01)^2) and an arc as long).
  EXPECT_GT(TurningDistance::exact_m(r, 0.0, 0.01), 0.19);
  // Far away, a turn toward the point and a straight: at least the distance, at most a
  // quarter turn more.
  const double far = TurningDistance::exact_m(r, 0.0, 10.0);
  EXPECT_GT(far, 10.0);
  EXPECT_NEAR(far, 0.5 * kPi * r + std::sqrt((10.0 - r) * (10.0 - r) - r * r) + 0.0, 0.05);
}

TEST(TurningDistanceTest, SymmetricAndNeverShorterThanTheStraightLine) {
  Random rng(7);
  for (int i = 0; i < 2000; ++i) {
    const double r = rng.uniform(0.1, 2.0);
    const double x = rng.uniform(-5.0, 5.0);
    const double y = rng.uniform(-5.0, 5.0);
    const double d = TurningDistance::exact_m(r, x, y);
    EXPECT_GE(d, std::hypot(x, y) - 1e-9);
    EXPECT_NEAR(d, TurningDistance::exact_m(r, -x, y), 1e-9);
    EXPECT_NEAR(d, TurningDistance::exact_m(r, x, -y), 1e-9);
    // Never more than turning to face the point on the far side of a circle and driving on.
    EXPECT_LE(d, kPi * r + std::hypot(x, y) + 2.0 * r);
  }
}

TEST(TurningDistanceTest, TableMatchesTheClosedFormWithinItsCells) {
  const double r = 0.5;
  const double cell = 0.02;
  auto table = TurningDistance::create(r, 1.6, cell);
  ASSERT_TRUE(table.ok()) << table.error().message;
  Random rng(3);
  for (int i = 0; i < 2000; ++i) {
    // On table points the table is exact to float precision.
    const double x = std::round(rng.uniform(-1.6, 1.6) / cell) * cell;
    const double y = std::round(rng.uniform(-1.6, 1.6) / cell) * cell;
    EXPECT_NEAR(table->at(x, y), TurningDistance::exact_m(r, x, y), 1e-5) << x << ", " << y;
  }
  // Beyond the table: the closed form.
  EXPECT_NEAR(table->at(0.0, 4.0), TurningDistance::exact_m(r, 0.0, 4.0), 1e-12);
}

TEST(TurningDistanceTest, RefusesBadSizes) {
  const auto refused = [](double r, double range, double cell, const char* name) {
    auto t = TurningDistance::create(r, range, cell);
    ASSERT_FALSE(t.ok());
    EXPECT_NE(t.error().message.find(name), std::string::npos) << t.error().message;
  };
  refused(0.0, 1.0, 0.1, "turning_radius_m");
  refused(std::nan(""), 1.0, 0.1, "turning_radius_m");
  refused(0.5, -1.0, 0.1, "range_m");
  refused(0.5, 1.0, 0.0, "resolution_m");
  refused(0.5, 1000.0, 1e-3, "table cells");
}

OccupancyGrid free_grid(int w, int h, double res) {
  auto grid = OccupancyGrid::create(w, h, res, 0.0, 0.0, Cell::kFree);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

DistanceField field_toward(const OccupancyGrid& grid, const std::vector<std::uint32_t>& targets) {
  auto field = DistanceField::create(grid.width(), grid.height(), grid.resolution());
  EXPECT_TRUE(field.ok());
  field->compute(grid, targets);
  return std::move(field).value();
}

TEST(TurningRhoTest, AStateFacingAwayPaysForTheTurn) {
  // Open ground, F a cell 3 m east of the vehicle: rho_A* is 3 m whatever the heading.
  OccupancyGrid grid = free_grid(100, 60, 0.1);
  const DistanceField field = field_toward(grid, {grid.index(65, 30)});
  auto rho = TurningRho::create(0.5, grid.resolution());
  ASSERT_TRUE(rho.ok()) << rho.error().message;
  const double x = 3.55;
  const double y = 3.05;
  const double grid_m = field.distance_m(x, y);
  // Facing F: the grid distance.
  EXPECT_NEAR(rho->at(field, x, y, 0.0), grid_m, 1e-9);
  // Facing away: reversing straight there is as short, so no more either.
  EXPECT_NEAR(rho->at(field, x, y, kPi), grid_m, 1e-9);
  // Facing north: a quarter turn first, more than the grid distance.
  const double sideways = rho->at(field, x, y, 0.5 * kPi);
  EXPECT_GT(sideways, grid_m + 0.2);
  EXPECT_LT(sideways, grid_m + kPi * 0.5);
  // In F's cell rho is 0 whatever the heading.
  EXPECT_EQ(rho->at(field, 6.55, 3.05, 0.5 * kPi), 0.0);
  // Unreachable or outside the grid: +infinity.
  EXPECT_EQ(rho->at(field, -1.0, 3.0, 0.0), std::numeric_limits<double>::infinity());

  // A new wavefront, toward a cell north of the vehicle: once told, rho follows it, and the
  // state facing north is the one that needs no turn.
  const DistanceField north = field_toward(grid, {grid.index(35, 55)});
  rho->forget();
  EXPECT_NEAR(rho->at(north, x, y, 0.5 * kPi), north.distance_m(x, y), 1e-9);
  EXPECT_GT(rho->at(north, x, y, 0.0), north.distance_m(x, y) + 0.2);
}

TEST(TurningRhoTest, AUTurnBesideTheGoalNeedsReversing) {
  // F is one cell 0.4 m to the left of the vehicle: the grid says 0.4 m, the car cannot go
  // sideways and must back and turn (more than 0.4 m), a vehicle facing it drives straight on.
  OccupancyGrid grid = free_grid(60, 60, 0.1);
  const DistanceField field = field_toward(grid, {grid.index(30, 34)});
  auto rho = TurningRho::create(0.5, grid.resolution());
  ASSERT_TRUE(rho.ok());
  const double x = 3.05;
  const double y = 3.05;
  EXPECT_NEAR(rho->at(field, x, y, 0.5 * kPi), field.distance_m(x, y), 1e-9);
  EXPECT_GT(rho->at(field, x, y, 0.0), field.distance_m(x, y) + 0.3);
}

}  // namespace
}  // namespace grip
