// The OMPL adapter: OMPL's own sanity checks on the state space, propagation through OMPL equal
// to the core's propagation of the same control (exactly), the validity checker and the goal
// answering as the planner's checker and Goal do, controls within the model's limits and,
// given the state, aimed at a velocity as the planner's are.

#include "adapter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "grip/scenes/scenes.hpp"

namespace grip::ompl_bridge {
namespace {

// Per vehicle: the rooms scene, the planner (for its checker) and the OMPL problem. The scene
// lives on the heap: the planner and the problem point at its grid.
template <VehicleModel V>
struct Problem {
  V vehicle;
  std::unique_ptr<Scene> scene;
  std::optional<Planner<V>> planner;
  Goal goal;
  OmplProblem ompl;

  explicit Problem(const V& v)
      : vehicle(v), scene(std::make_unique<Scene>(make_scene(SceneId::kRooms).value())) {
    planner.emplace(Planner<V>::create(vehicle, scene->grid, PlannerConfig{}).value());
    goal = Goal::disk(scene->goal_x_m, scene->goal_y_m, scene->goal_radius_m);
    const auto start =
        vehicle.rest_state(scene->start_x_m, scene->start_y_m, scene->start_theta_rad);
    ompl = make_problem(vehicle, planner->checker(), start, goal, settings_for(planner->config()));
    ompl.setup->getSpaceInformation()->setup();
  }
};

template <typename T>
class OmplAdapter : public ::testing::Test {};
using Vehicles = ::testing::Types<DdVelocity, DdAcceleration, Car>;
TYPED_TEST_SUITE(OmplAdapter, Vehicles);

template <VehicleModel V>
V default_model() {
  if constexpr (std::is_same_v<V, DdVelocity>) {
    return DdVelocity::create(DdVelocityParams{}).value();
  } else if constexpr (std::is_same_v<V, DdAcceleration>) {
    return DdAcceleration::create(DdAccelerationParams{}).value();
  } else {
    return Car::create(CarParams{}).value();
  }
}

TYPED_TEST(OmplAdapter, TheStateSpacePassesOmplsSanityChecks) {
  const auto vehicle = default_model<TypeParam>();
  const Scene scene = make_scene(SceneId::kRooms).value();
  const auto space = make_state_space(vehicle, scene.grid);
  EXPECT_EQ(space->getDimension(), static_cast<unsigned>(TypeParam::kStateDim));
  EXPECT_NO_THROW(space->sanityChecks());
}

TYPED_TEST(OmplAdapter, StatesConvertBothWaysExactly) {
  const auto vehicle = default_model<TypeParam>();
  const Scene scene = make_scene(SceneId::kRooms).value();
  const auto space = make_state_space(vehicle, scene.grid);
  ob::ScopedState<> s(space);
  Random rng(7);
  for (int i = 0; i < 100; ++i) {
    typename TypeParam::State q;
    for (int k = 0; k < TypeParam::kStateDim; ++k) q[k] = rng.uniform(-1.0, 1.0);
    to_ompl<TypeParam>(q, s.get());
    EXPECT_EQ(to_core<TypeParam>(s.get()), q);
  }
}

TYPED_TEST(OmplAdapter, PropagationThroughOmplEqualsTheCoresExactly) {
  Problem<TypeParam> p(default_model<TypeParam>());
  const oc::SpaceInformationPtr& si = p.ompl.setup->getSpaceInformation();
  const double dt = p.planner->config().integration_step_s;
  EXPECT_EQ(si->getPropagationStepSize(), dt);
  EXPECT_EQ(si->getMinControlDuration(), 20U);
  EXPECT_EQ(si->getMaxControlDuration(), 80U);

  Random rng(3);
  ob::State* from = si->allocState();
  ob::State* to = si->allocState();
  oc::Control* control = si->allocControl();
  for (int trial = 0; trial < 20; ++trial) {
    // A moving start (velocities mid-range) and a random admissible control.
    auto q = p.vehicle.rest_state(p.scene->start_x_m, p.scene->start_y_m, rng.uniform(-3.0, 3.0));
    for (int k = 0; k < 5; ++k) q = p.vehicle.step(q, p.vehicle.sample_control(rng), dt);
    const auto u = p.vehicle.sample_control(rng);
    const int steps = 20 + static_cast<int>(rng.below(61));
    to_ompl<TypeParam>(q, from);
    to_ompl_control<TypeParam>(u, control);
    *p.ompl.counters = WorkCounters{};
    si->propagate(from, control, steps, to);

    auto expected = q;
    for (int k = 0; k < steps; ++k) expected = p.vehicle.step(expected, u, dt);
    EXPECT_EQ(to_core<TypeParam>(to), expected) << "trial " << trial;
    EXPECT_EQ(p.ompl.counters->propagations, static_cast<std::uint64_t>(steps));
  }
  si->freeControl(control);
  si->freeState(to);
  si->freeState(from);
}

TYPED_TEST(OmplAdapter, PropagateWhileValidStopsWhereThePlannersCheckerSaysSo) {
  Problem<TypeParam> p(default_model<TypeParam>());
  const oc::SpaceInformationPtr& si = p.ompl.setup->getSpaceInformation();
  const double dt = p.planner->config().integration_step_s;
  // Full speed ahead (or full acceleration) from the start towards the wall 2 m to its left.
  auto q = p.vehicle.rest_state(p.scene->start_x_m, p.scene->start_y_m, std::numbers::pi);
  typename TypeParam::Control u;
  if constexpr (std::is_same_v<TypeParam, Car>) {
    u = {p.vehicle.params().max_accel_m_s2, 0.0};
  } else if constexpr (std::is_same_v<TypeParam, DdAcceleration>) {
    u = {p.vehicle.params().max_wheel_accel_m_s2, p.vehicle.params().max_wheel_accel_m_s2};
  } else {
    u = {p.vehicle.params().max_wheel_speed_m_s, p.vehicle.params().max_wheel_speed_m_s};
  }
  ob::State* from = si->allocState();
  ob::State* to = si->allocState();
  oc::Control* control = si->allocControl();
  to_ompl<TypeParam>(q, from);
  to_ompl_control<TypeParam>(u, control);
  *p.ompl.counters = WorkCounters{};
  const unsigned valid = si->propagateWhileValid(from, control, 200, to);

  unsigned expected_valid = 0;
  for (; expected_valid < 200; ++expected_valid) {
    const auto next = p.vehicle.step(q, u, dt);
    if (!p.planner->chassis_free(next)) break;
    q = next;
  }
  ASSERT_LT(expected_valid, 200U) << "the maneuver was meant to reach the wall";
  EXPECT_EQ(valid, expected_valid);
  EXPECT_EQ(to_core<TypeParam>(to), q);
  EXPECT_EQ(p.ompl.counters->collision_checks, expected_valid + 1U);
  si->freeControl(control);
  si->freeState(to);
  si->freeState(from);
}

TYPED_TEST(OmplAdapter, TheValidityCheckerIsThePlannersCheckerWithItsMargin) {
  Problem<TypeParam> p(default_model<TypeParam>());
  EXPECT_EQ(p.planner->collision_margin_m(),
            step_collision_margin_m(p.vehicle, p.planner->config().integration_step_s));
  const oc::SpaceInformationPtr& si = p.ompl.setup->getSpaceInformation();
  ob::State* s = si->allocState();
  auto sampler = si->allocStateSampler();
  int free = 0;
  *p.ompl.counters = WorkCounters{};
  for (int i = 0; i < 2000; ++i) {
    sampler->sampleUniform(s);
    const auto q = to_core<TypeParam>(s);
    const bool expected = p.planner->chassis_free(q);
    EXPECT_EQ(si->isValid(s), expected) << "at (" << q[0] << ", " << q[1] << ", " << q[2] << ")";
    free += expected ? 1 : 0;
  }
  EXPECT_EQ(p.ompl.counters->collision_checks, 2000U);
  EXPECT_GT(free, 100);  // both answers occur
  EXPECT_LT(free, 1900);
  si->freeState(s);
}

TYPED_TEST(OmplAdapter, TheGoalIsTheScenesGoalRegion) {
  Problem<TypeParam> p(default_model<TypeParam>());
  const oc::SpaceInformationPtr& si = p.ompl.setup->getSpaceInformation();
  const auto& goal = static_cast<const DiskGoal&>(*p.ompl.setup->getGoal());
  ob::State* s = si->allocState();
  Random rng(5);
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    const double x = p.goal.x_m() + rng.uniform(-2.0, 2.0);
    const double y = p.goal.y_m() + rng.uniform(-2.0, 2.0);
    to_ompl<TypeParam>(p.vehicle.rest_state(x, y, 0.0), s);
    EXPECT_EQ(goal.isSatisfied(s), p.goal.contains(x, y)) << x << ", " << y;
    inside += p.goal.contains(x, y) ? 1 : 0;
  }
  EXPECT_GT(inside, 100);
  for (int i = 0; i < 500; ++i) {
    goal.sampleGoal(s);
    EXPECT_TRUE(goal.isSatisfied(s));
    EXPECT_TRUE(si->satisfiesBounds(s));
  }
  si->freeState(s);
}

TYPED_TEST(OmplAdapter, SampledControlsAreTheModelsAdmissibleOnes) {
  Problem<TypeParam> p(default_model<TypeParam>());
  const oc::SpaceInformationPtr& si = p.ompl.setup->getSpaceInformation();
  auto sampler = si->allocControlSampler();
  oc::Control* c = si->allocControl();
  for (int i = 0; i < 2000; ++i) {
    sampler->sample(c);
    const auto u = to_core_control<TypeParam>(c);
    EXPECT_TRUE(p.vehicle.validate_control(u).ok()) << u.transpose();
  }
  si->freeControl(c);
}

// dd-accel's turn-rate limit as a difference of wheel speeds.
double wheel_speed_difference_limit(const DdAcceleration& vehicle) {
  return 2.0 * vehicle.params().half_axle_m * vehicle.max_turn_rate_rad_s();
}

// Where uniform controls drive the velocity state: dd-accel's turn-rate limit, the car's full
// lock (the vehicles' sampling tests).
template <VehicleModel V>
bool at_turn_limit(const V& vehicle, const typename V::State& q) {
  if constexpr (std::is_same_v<V, DdAcceleration>) {
    return std::abs(q[4] - q[3]) > 0.99 * wheel_speed_difference_limit(vehicle);
  } else {
    return std::abs(q[4]) > 0.99 * vehicle.params().max_steer_rad;
  }
}

template <typename T>
class OmplAimedSampler : public ::testing::Test {};
using AimingVehicles = ::testing::Types<DdAcceleration, Car>;
TYPED_TEST_SUITE(OmplAimedSampler, AimingVehicles);

TYPED_TEST(OmplAimedSampler, GivenTheStateItAimsAtAVelocityAsThePlannersSamplerDoes) {
  // GIVEN the sampler OMPL's planners get, and a state turning hard at the scene's start
  Problem<TypeParam> p(default_model<TypeParam>());
  const oc::SpaceInformationPtr& si = p.ompl.setup->getSpaceInformation();
  auto sampler = si->allocControlSampler();
  auto q = p.vehicle.rest_state(p.scene->start_x_m, p.scene->start_y_m, p.scene->start_theta_rad);
  if constexpr (std::is_same_v<TypeParam, DdAcceleration>) {
    const double limit = wheel_speed_difference_limit(p.vehicle);
    q[3] = 1.0 - 0.5 * limit;
    q[4] = 1.0 + 0.5 * limit;
  } else {
    q[3] = 1.0;
    q[4] = 0.6;
  }
  ob::State* from = si->allocState();
  ob::State* to = si->allocState();
  to_ompl<TypeParam>(q, from);
  oc::Control* control = si->allocControl();
  oc::Control* previous = si->allocControl();
  sampler->sample(previous);
  const ProblemSettings settings = settings_for(p.planner->config());
  const unsigned mean_steps = (settings.min_steps + settings.max_steps) / 2;

  // WHEN controls are held for the mean duration: drawn without the state, with it (as OMPL's
  // control planners draw them), and as the next control after another
  const auto share_at_limit = [&](auto draw) {
    constexpr int kDraws = 2'000;
    int at_limit = 0;
    for (int i = 0; i < kDraws; ++i) {
      draw();
      const auto u = to_core_control<TypeParam>(control);
      EXPECT_TRUE(p.vehicle.validate_control(u).ok()) << u.transpose();
      si->propagate(from, control, static_cast<int>(mean_steps), to);
      if (at_turn_limit(p.vehicle, to_core<TypeParam>(to))) ++at_limit;
    }
    return static_cast<double>(at_limit) / kDraws;
  };
  const double uniform = share_at_limit([&] { sampler->sample(control); });
  const double given_state = share_at_limit([&] { sampler->sample(control, from); });
  const double next = share_at_limit([&] { sampler->sampleNext(control, previous, from); });

  // THEN with the state, the model's share of aimed controls (half) keeps edges off the limit
  // that uniform controls end at
  EXPECT_GT(uniform, 0.3);
  EXPECT_LT(given_state, 0.75 * uniform) << "uniform " << uniform;
  EXPECT_LT(next, 0.75 * uniform) << "uniform " << uniform;
  si->freeControl(previous);
  si->freeControl(control);
  si->freeState(to);
  si->freeState(from);
}

TEST(OmplPlanners, EveryPlannerOfTheComparisonIsCreatedAndAnUnknownOneRefused) {
  Problem<DdVelocity> p(default_model<DdVelocity>());
  for (std::string_view name : kOmplPlanners) {
    ASSERT_TRUE(set_planner(p.ompl, name).ok()) << name;
    EXPECT_NO_THROW(p.ompl.setup->setup()) << name;
    p.ompl.setup->clear();
  }
  EXPECT_FALSE(set_planner(p.ompl, "prm").ok());
}

}  // namespace
}  // namespace grip::ompl_bridge
