#pragma once
// The project's vehicles, collision checker and goal region behind OMPL's control interfaces,
// so that OMPL's planners solve exactly the problem GRIP solves (never a second copy of the
// model):
//   state space    SE2 (x, y: the grid's extent; theta) + R^k for the vehicle's velocity
//                  components (k = kStateDim - 3; none for dd-vel), bounded by its limits;
//   control space  R^2 bounded by the vehicle's control limits, sampled by the vehicle's own
//                  sample_control (dd-vel's turn-rate limit is not a box: the box alone would
//                  admit controls the model forbids);
//   propagator     one vehicle.step(q, u, duration) per call; OMPL calls it once per
//                  propagation step, so with the step = PlannerConfig::integration_step_s every
//                  state is reached as the planner reaches it;
//   validity       CollisionChecker::is_free with the planner's margin (the chassis grown by
//                  half a step's motion at the state's speed: Planner::chassis_free), the
//                  planner's only per-step test (bounds hold by
//                  construction: outside the grid is never free, velocities saturate);
//   goal           the reference point within the goal radius (Goal::contains);
//   projection     (x, y), the default projection for KPIECE1, PDST and EST.
// Tools only: allocates and may throw (OMPL does). The grid must outlive everything built here.

#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/control/ControlSampler.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/StatePropagator.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grip/common/random.hpp"
#include "grip/common/result.hpp"
#include "grip/planner/planner.hpp"
#include "grip/planner/step_margin.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip::ompl_bridge {

namespace ob = ::ompl::base;
namespace oc = ::ompl::control;

// Work done through the adapter, counted the way the planner counts its own.
struct WorkCounters {
  std::uint64_t propagations = 0;      // vehicle.step calls (one per integration step)
  std::uint64_t collision_checks = 0;  // CollisionChecker::is_free calls
};

// Closed intervals [low, high] per dimension.
using Bounds = std::vector<std::pair<double, double>>;

// The velocity part of the state (after x, y, theta), in the order of V::State.
inline Bounds velocity_bounds(const DdVelocity&) { return {}; }
inline Bounds velocity_bounds(const DdAcceleration& v) {
  const double s = v.params().max_wheel_speed_m_s;
  return {{-s, s}, {-s, s}};
}
inline Bounds velocity_bounds(const Car& v) {
  const CarParams& p = v.params();
  return {{p.min_speed_m_s, p.max_speed_m_s}, {-p.max_steer_rad, p.max_steer_rad}};
}

// The control limits as a box (the sampler draws from the model's own distribution inside it).
inline Bounds control_bounds(const DdVelocity& v) {
  const double s = v.params().max_wheel_speed_m_s;
  return {{-s, s}, {-s, s}};
}
inline Bounds control_bounds(const DdAcceleration& v) {
  const double a = v.params().max_wheel_accel_m_s2;
  return {{-a, a}, {-a, a}};
}
inline Bounds control_bounds(const Car& v) {
  const CarParams& p = v.params();
  return {{-p.max_accel_m_s2, p.max_accel_m_s2}, {-p.max_steer_rate_rad_s, p.max_steer_rate_rad_s}};
}

// State layout: component 0 is SE2, component 1 (if the model has velocities) is R^k.
inline const ob::SE2StateSpace::StateType& pose_of(const ob::State* s) {
  return *s->as<ob::CompoundState>()->as<ob::SE2StateSpace::StateType>(0);
}
inline ob::SE2StateSpace::StateType& pose_of(ob::State* s) {
  return *s->as<ob::CompoundState>()->as<ob::SE2StateSpace::StateType>(0);
}

template <VehicleModel V>
typename V::State to_core(const ob::State* s) {
  typename V::State q;
  const auto& pose = pose_of(s);
  q[0] = pose.getX();
  q[1] = pose.getY();
  q[2] = pose.getYaw();
  if constexpr (V::kStateDim > 3) {
    const double* v =
        s->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(1)->values;
    for (int i = 3; i < V::kStateDim; ++i) q[i] = v[i - 3];
  }
  return q;
}

template <VehicleModel V>
void to_ompl(const typename V::State& q, ob::State* s) {
  auto& pose = pose_of(s);
  pose.setXY(q[0], q[1]);
  pose.setYaw(q[2]);
  if constexpr (V::kStateDim > 3) {
    double* v = s->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(1)->values;
    for (int i = 3; i < V::kStateDim; ++i) v[i - 3] = q[i];
  }
}

template <VehicleModel V>
typename V::Control to_core_control(const oc::Control* c) {
  const double* u = c->as<oc::RealVectorControlSpace::ControlType>()->values;
  return typename V::Control{u[0], u[1]};
}

template <VehicleModel V>
void to_ompl_control(const typename V::Control& u, oc::Control* c) {
  double* out = c->as<oc::RealVectorControlSpace::ControlType>()->values;
  out[0] = u[0];
  out[1] = u[1];
}

// The state space for a vehicle on a grid: SE2 over the grid's extent, plus the velocities.
template <VehicleModel V>
std::shared_ptr<ob::CompoundStateSpace> make_state_space(const V& vehicle,
                                                         const OccupancyGrid& grid) {
  auto space = std::make_shared<ob::CompoundStateSpace>();
  auto se2 = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds xy(2);
  xy.setLow(0, grid.origin_x());
  xy.setHigh(0, grid.origin_x() + grid.width_m());
  xy.setLow(1, grid.origin_y());
  xy.setHigh(1, grid.origin_y() + grid.height_m());
  se2->setBounds(xy);
  space->addSubspace(se2, 1.0);
  const Bounds vb = velocity_bounds(vehicle);
  if (!vb.empty()) {
    auto velocities = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(vb.size()));
    ob::RealVectorBounds b(static_cast<unsigned>(vb.size()));
    for (unsigned i = 0; i < vb.size(); ++i) {
      b.setLow(i, vb[i].first);
      b.setHigh(i, vb[i].second);
    }
    velocities->setBounds(b);
    space->addSubspace(velocities, 1.0);
  }
  space->lock();
  return space;
}

// Controls drawn by the vehicle's own sample_control, from a generator seeded by OMPL's
// (so ompl::RNG::setSeed fixes them like every other random choice of the planner). Where
// OMPL gives the state, models that aim their controls at a velocity do so as in GRIP; OMPL
// draws the duration after the control, so they aim at the mean hold.
template <VehicleModel V>
class CoreControlSampler : public oc::ControlSampler {
 public:
  CoreControlSampler(const oc::ControlSpace* space, const V& vehicle, double mean_hold_s)
      : oc::ControlSampler(space),
        vehicle_(vehicle),
        mean_hold_s_(mean_hold_s),
        random_(rng_.getLocalSeed()) {}
  void sample(oc::Control* control) override {
    to_ompl_control<V>(vehicle_.sample_control(random_), control);
  }
  void sample(oc::Control* control, const ob::State* state) override {
    if constexpr (SteersToVelocityTarget<V>) {
      to_ompl_control<V>(vehicle_.sample_control(to_core<V>(state), mean_hold_s_, random_),
                         control);
    } else {
      sample(control);
    }
  }
  void sampleNext(oc::Control* control, const oc::Control*, const ob::State* state) override {
    sample(control, state);
  }

 private:
  V vehicle_;
  double mean_hold_s_;
  Random random_;
};

// One vehicle.step per call, counted.
template <VehicleModel V>
class CorePropagator : public oc::StatePropagator {
 public:
  CorePropagator(const oc::SpaceInformationPtr& si, const V& vehicle,
                 std::shared_ptr<WorkCounters> counters)
      : oc::StatePropagator(si), vehicle_(vehicle), counters_(std::move(counters)) {}
  void propagate(const ob::State* state, const oc::Control* control, double duration,
                 ob::State* result) const override {
    // state and result may be the same object: read it whole before writing.
    const typename V::State q = to_core<V>(state);
    to_ompl<V>(vehicle_.step(q, to_core_control<V>(control), duration), result);
    ++counters_->propagations;
  }

 private:
  V vehicle_;
  std::shared_ptr<WorkCounters> counters_;
};

// The planner's chassis test (Planner::chassis_free: the margin of the state's own speed for
// a propagation step of step_s), counted. The checker must outlive this object.
template <VehicleModel V>
class CoreValidityChecker : public ob::StateValidityChecker {
 public:
  CoreValidityChecker(const ob::SpaceInformationPtr& si, const V& vehicle,
                      const CollisionChecker& checker, double step_s,
                      std::shared_ptr<WorkCounters> counters)
      : ob::StateValidityChecker(si),
        vehicle_(vehicle),
        checker_(&checker),
        step_s_(step_s),
        counters_(std::move(counters)) {}
  bool isValid(const ob::State* state) const override {
    ++counters_->collision_checks;
    const typename V::State q = to_core<V>(state);
    return chassis_free_at(vehicle_, *checker_, q, step_s_);
  }

 private:
  V vehicle_;
  const CollisionChecker* checker_;
  double step_s_;
  std::shared_ptr<WorkCounters> counters_;
};

// F: the reference point within radius_m of the goal point. distanceGoal is the distance to
// that point and the threshold is the radius, so isSatisfied agrees with Goal::contains.
// Sampleable (uniform in the disk, heading and velocities uniform within their bounds) so that
// the planners with a goal bias (RRT, SST, EST) can use it.
class DiskGoal : public ob::GoalSampleableRegion {
 public:
  DiskGoal(const ob::SpaceInformationPtr& si, const grip::Goal& goal, Bounds velocity_bounds);
  double distanceGoal(const ob::State* st) const override;
  void sampleGoal(ob::State* st) const override;
  unsigned int maxSampleCount() const override;

 private:
  grip::Goal goal_;  // (ob::GoalRegion is a base class: the name needs qualifying)
  Bounds velocity_bounds_;
  mutable ::ompl::RNG rng_;
};

// (x, y) of the reference point, with cells of cell_m and the grid's extent as bounds (PDST
// subdivides within them).
class XyProjection : public ob::ProjectionEvaluator {
 public:
  XyProjection(const ob::StateSpace* space, const OccupancyGrid& grid, double cell_m);
  unsigned int getDimension() const override { return 2; }
  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override;
  void defaultCellSizes() override;

 private:
  double cell_m_;
};

// What is held equal between GRIP and OMPL.
struct ProblemSettings {
  double step_s = 0.05;     // propagation step = PlannerConfig::integration_step_s
  unsigned min_steps = 20;  // control duration range, in steps (PlannerConfig's
  unsigned max_steps = 80;  // min/max_plan_duration_s over the step)
  double projection_cell_m = 1.0;
};

// The settings that match a planner configuration.
ProblemSettings settings_for(const PlannerConfig& config);

// A configured problem without a planner: everything except the planner is set.
struct OmplProblem {
  std::shared_ptr<oc::SimpleSetup> setup;
  std::shared_ptr<WorkCounters> counters;
  std::shared_ptr<ob::CompoundStateSpace> space;
};

// Builds the problem for a vehicle from start to goal, checked by `checker` (which must be the
// planner's: same grid, same footprint, same margin; it must outlive the problem).
template <VehicleModel V>
OmplProblem make_problem(const V& vehicle, const CollisionChecker& checker,
                         const typename V::State& start, const Goal& goal,
                         const ProblemSettings& settings) {
  OmplProblem p;
  p.counters = std::make_shared<WorkCounters>();
  p.space = make_state_space(vehicle, checker.grid());
  p.space->registerDefaultProjection(
      std::make_shared<XyProjection>(p.space.get(), checker.grid(), settings.projection_cell_m));
  const Bounds cb = control_bounds(vehicle);
  auto cspace = std::make_shared<oc::RealVectorControlSpace>(p.space, 2);
  ob::RealVectorBounds b(2);
  for (unsigned i = 0; i < 2; ++i) {
    b.setLow(i, cb[i].first);
    b.setHigh(i, cb[i].second);
  }
  cspace->setBounds(b);
  const double mean_hold_s = 0.5 * (settings.min_steps + settings.max_steps) * settings.step_s;
  cspace->setControlSamplerAllocator([vehicle, mean_hold_s](const oc::ControlSpace* cs) {
    return std::make_shared<CoreControlSampler<V>>(cs, vehicle, mean_hold_s);
  });
  p.setup = std::make_shared<oc::SimpleSetup>(cspace);
  const oc::SpaceInformationPtr& si = p.setup->getSpaceInformation();
  si->setPropagationStepSize(settings.step_s);                           // seconds
  si->setMinMaxControlDuration(settings.min_steps, settings.max_steps);  // steps
  p.setup->setStateValidityChecker(
      std::make_shared<CoreValidityChecker<V>>(si, vehicle, checker, settings.step_s, p.counters));
  p.setup->setStatePropagator(std::make_shared<CorePropagator<V>>(si, vehicle, p.counters));
  ob::ScopedState<> s(p.space);
  to_ompl<V>(start, s.get());
  p.setup->setStartState(s);
  p.setup->setGoal(std::make_shared<DiskGoal>(si, goal, velocity_bounds(vehicle)));
  return p;
}

// The OMPL planners of the comparison, by name.
inline constexpr std::array<std::string_view, 5> kOmplPlanners{"pdst", "kpiece1", "sst", "rrt",
                                                               "est"};

// Creates the named planner (one of kOmplPlanners) and makes it the problem's planner. SST
// gets a path-length objective with an infinite cost threshold, so that it stops at its first
// solution like the others; every other parameter keeps OMPL's default. Call before setup().
Status set_planner(OmplProblem& problem, std::string_view name);

}  // namespace grip::ompl_bridge
