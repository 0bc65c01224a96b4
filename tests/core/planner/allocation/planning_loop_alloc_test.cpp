// The planning loop allocates nothing: every call into malloc/calloc/realloc/free/operator new
// made while solve() runs is counted by the interposed allocator, for every vehicle and every
// selection strategy. The counter is first proven to fire on deliberate allocations. Nor does
// it fault in memory: create() has written every page the pools hold.

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <vector>

#include "grip/planner/planner.hpp"
#include "grip/platform/alloc_counter.hpp"
#include "grip/platform/memory.hpp"
#include "grip/scenes/scenes.hpp"

namespace grip {
namespace {

class PlanningLoopAllocationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(alloc_counter::interposed()) << "grip_alloc_counter is not the process allocator";
  }

  template <VehicleModel V>
  std::uint64_t allocations_while_solving(const V& vehicle, Selection selection,
                                          SafetyCheck safety) {
    const Scene scene = make_scene(SceneId::kLabyrinth).value();
    PlannerConfig config;
    config.selection = selection;
    config.safety = safety;
    config.max_edges = 8000;
    config.max_trajectories = 4000;
    config.stop_at_goal = false;  // the loop keeps running past the goal, as when replanning
    auto planner = Planner<V>::create(vehicle, scene.grid, config).value();
    EXPECT_TRUE(planner.set_problem(
        vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad),
        Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m)));
    BoundedVector<PlanStep> plan(4096);
    const PlannerStats& stats = planner.stats();

    alloc_counter::arm();
    const SolveResult result = planner.solve([&] { return stats.edges_added >= 1500; });
    const bool extracted = planner.extract_plan(planner.best_state(), plan);
    alloc_counter::disarm();

    EXPECT_TRUE(extracted);
    EXPECT_NE(result.status, SolveStatus::kNoSolution);
    EXPECT_GE(stats.edges_added, 1000U);  // the loop did real work while counted
    return alloc_counter::counts().allocations + alloc_counter::counts().deallocations;
  }
};

// Stores through a volatile pointer so that the compiler cannot elide the allocations.
void* volatile g_sink = nullptr;

TEST_F(PlanningLoopAllocationTest, TheCounterFiresOnDeliberateAllocations) {
  alloc_counter::arm();
  g_sink = std::malloc(64);
  std::free(g_sink);
  int* boxed = new int(3);
  g_sink = boxed;
  delete boxed;
  std::vector<double> v(100);
  g_sink = v.data();
  alloc_counter::disarm();
  EXPECT_EQ(alloc_counter::counts().allocations, 3U);
  EXPECT_EQ(alloc_counter::counts().deallocations, 2U);
}

TEST_F(PlanningLoopAllocationTest, GripAllocatesNothingForAnyVehicle) {
  EXPECT_EQ(allocations_while_solving(DdVelocity::create({}).value(), Selection::kGrip,
                                      SafetyCheck::kAtHorizon),
            0U);
  EXPECT_EQ(allocations_while_solving(DdAcceleration::create({}).value(), Selection::kGrip,
                                      SafetyCheck::kAtHorizon),
            0U);
  EXPECT_EQ(
      allocations_while_solving(Car::create({}).value(), Selection::kGrip, SafetyCheck::kAtHorizon),
      0U);
}

TEST_F(PlanningLoopAllocationTest, TheAllLeavesVariantAndTheBaselinesAllocateNothing) {
  const Car car = Car::create({}).value();
  EXPECT_EQ(allocations_while_solving(car, Selection::kGrip, SafetyCheck::kAllLeaves), 0U);
  EXPECT_EQ(allocations_while_solving(car, Selection::kRandom, SafetyCheck::kAtHorizon), 0U);
  EXPECT_EQ(allocations_while_solving(car, Selection::kRrt, SafetyCheck::kAtHorizon), 0U);
  EXPECT_EQ(allocations_while_solving(car, Selection::kRrtBias, SafetyCheck::kAtHorizon), 0U);
}

// Page faults taken by the calling thread while a fresh planner grows `edges` edges. A first
// planner of the same vehicle runs before, so that the code and the stack are resident, and
// stays alive, so that the second one's memory is not the first one's, already written.
template <VehicleModel V>
std::uint64_t page_faults_while_solving(const V& vehicle, std::uint64_t edges) {
  const Scene scene = make_scene(SceneId::kRooms).value();
  PlannerConfig config;
  config.stop_at_goal = false;
  config.max_edges = 8000;
  config.max_trajectories = 4000;
  const auto make = [&] {
    auto planner = Planner<V>::create(vehicle, scene.grid, config).value();
    EXPECT_TRUE(planner.set_problem(
        vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad),
        Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m)));
    return planner;
  };
  const auto grow = [&](Planner<V>& planner) {
    const PlannerStats& stats = planner.stats();
    (void)planner.solve([&] { return stats.edges_added >= edges; });
    EXPECT_EQ(stats.edges_added, edges);
  };
  auto warm_up = make();
  grow(warm_up);
  auto measured = make();
  const std::uint64_t before = platform::thread_usage().minor_faults;
  grow(measured);
  return platform::thread_usage().minor_faults - before;
}

TEST(PlanningLoopPageFaults, GrowingTheTreeWritesOnlyPagesCreateAlreadyWrote) {
  // 2,000 trajectories of up to 41 states are 0.5 to 0.8 MB: hundreds of pages, had create()
  // left them untouched. A few faults remain possible (the kernel's own bookkeeping).
  constexpr std::uint64_t kEdges = 2000;
  EXPECT_LE(page_faults_while_solving(DdVelocity::create({}).value(), kEdges), 8U);
  EXPECT_LE(page_faults_while_solving(DdAcceleration::create({}).value(), kEdges), 8U);
  EXPECT_LE(page_faults_while_solving(Car::create({}).value(), kEdges), 8U);
}

}  // namespace
}  // namespace grip

namespace grip {
namespace {

TEST(ReplanningAllocation, RetainmentWithANewMapAndTargetAllocatesNothing) {
  ASSERT_TRUE(alloc_counter::interposed());
  Scene scene = make_scene(SceneId::kRooms).value();
  const Car car = Car::create({}).value();
  PlannerConfig config;
  config.steps_per_record = 1;
  config.stop_at_goal = false;
  config.max_edges = 8000;
  config.max_trajectories = 4000;
  auto planner = Planner<Car>::create(car, scene.grid, config).value();
  const Goal goals[2] = {Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m),
                         Goal::disk(15.0, 5.0, 1.0)};
  ASSERT_TRUE(planner.set_problem(
      car.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad), goals[0]));
  const PlannerStats& stats = planner.stats();

  alloc_counter::arm();
  int retained = 0;
  for (int cycle = 0; cycle < 200; ++cycle) {
    const std::uint64_t target = stats.edges_added + 30;
    (void)planner.solve([&] { return stats.edges_added >= target; });
    // The map changes (a cell far from the vehicle toggles) and the target alternates.
    scene.grid.set(150, 280 - cycle % 20, cycle % 2 == 0 ? Cell::kObstacle : Cell::kFree);
    TreeState next = planner.state_at_step(planner.best_state(), 1);
    if (next.edge == kNoHandle) next = planner.root_state();
    retained += planner.retain(next, goals[cycle % 2], 1.0) == RetainStatus::kOk ? 1 : 0;
  }
  alloc_counter::disarm();

  EXPECT_EQ(retained, 200);
  EXPECT_EQ(alloc_counter::counts().allocations + alloc_counter::counts().deallocations, 0U);
}

}  // namespace
}  // namespace grip
