// The simulator's per-tick work allocates nothing: a sensor sweep, plan submission and the
// executor's integration steps (with collisions and contingencies) are counted by the
// interposed allocator on a real map-sized grid. The counter is first proven to fire.

#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "grip/platform/alloc_counter.hpp"
#include "grip/sim/plan_executor.hpp"
#include "grip/sim/range_sensor.hpp"

namespace grip::sim {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

class SimLoopAllocationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(alloc_counter::interposed()) << "grip_alloc_counter is not the process allocator";
  }
  static std::uint64_t counted() {
    return alloc_counter::counts().allocations + alloc_counter::counts().deallocations;
  }
};

void* volatile g_sink = nullptr;

TEST_F(SimLoopAllocationTest, TheCounterFiresOnDeliberateAllocations) {
  alloc_counter::arm();
  g_sink = std::malloc(64);
  std::free(g_sink);
  alloc_counter::disarm();
  EXPECT_GE(counted(), 2U);
}

TEST_F(SimLoopAllocationTest, SensorSweepsAllocateNothing) {
  OccupancyGrid truth = OccupancyGrid::create(300, 300, 0.1, 0.0, 0.0, Cell::kFree).value();
  truth.fill_rect(12.0, 5.0, 12.5, 25.0, Cell::kObstacle);
  OccupancyGrid known = OccupancyGrid::create(300, 300, 0.1, 0.0, 0.0, Cell::kUnknown).value();
  RangeSensor sensor = RangeSensor::create(truth, RangeSensor::default_radius_m(truth)).value();
  std::size_t changed = 0;
  alloc_counter::arm();
  for (int i = 0; i < 50; ++i) {
    changed += sensor.sense(5.0 + 0.3 * i, 15.0, known).changed_cells.size();
  }
  alloc_counter::disarm();
  EXPECT_GT(changed, 1000U);  // the sweeps did real work while counted
  EXPECT_EQ(counted(), 0U);
}

template <VehicleModel V>
std::uint64_t allocations_while_executing(const V& vehicle) {
  OccupancyGrid truth = OccupancyGrid::create(300, 300, 0.1, 0.0, 0.0, Cell::kFree).value();
  truth.fill_rect(6.5, 0.0, 30.0, 30.0, Cell::kObstacle);  // driven into: collisions recorded
  auto executor = PlanExecutor<V>::create(vehicle, truth, vehicle.rest_state(5.0, 15.0, 0.0), 0);
  EXPECT_TRUE(executor.ok());
  // Straight ahead: equal wheels, or the car's acceleration with no steering.
  const double second = V::kKind == VehicleKind::kCar ? 0.0 : 0.3;
  const std::vector<PlanStep> plan(200, PlanStep{{0.3, second}, 0.1});
  alloc_counter::arm();
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(executor->submit(plan, (3 * k) * kSecond), PlanVerdict::kAccepted);
    executor->run_until((3 * k + 1) * kSecond + kSecond / 3);
    executor->abandon_plans();
    executor->run_until((3 * k + 3) * kSecond);
  }
  alloc_counter::disarm();
  EXPECT_EQ(executor->stats().plans_started, 10U);
  EXPECT_GT(executor->stats().ticks, 500U);
  EXPECT_GT(executor->stats().collisions, 0U) << executor->state().transpose();
  return alloc_counter::counts().allocations + alloc_counter::counts().deallocations;
}

TEST_F(SimLoopAllocationTest, ExecutingPlansAllocatesNothingForAnyVehicle) {
  EXPECT_EQ(allocations_while_executing(DdVelocity::create(DdVelocityParams{}).value()), 0U);
  EXPECT_EQ(allocations_while_executing(DdAcceleration::create(DdAccelerationParams{}).value()),
            0U);
  EXPECT_EQ(allocations_while_executing(Car::create(CarParams{}).value()), 0U);
}

}  // namespace
}  // namespace grip::sim
