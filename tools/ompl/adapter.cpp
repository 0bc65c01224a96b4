#include "adapter.hpp"

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>
#include <cmath>
#include <limits>
#include <numbers>

namespace grip::ompl_bridge {

DiskGoal::DiskGoal(const ob::SpaceInformationPtr& si, const grip::Goal& goal,
                   Bounds velocity_bounds)
    : ob::GoalSampleableRegion(si), goal_(goal), velocity_bounds_(std::move(velocity_bounds)) {
  setThreshold(goal.radius_m());
}

double DiskGoal::distanceGoal(const ob::State* st) const {
  const auto& pose = pose_of(st);
  return std::hypot(pose.getX() - goal_.x_m(), pose.getY() - goal_.y_m());
}

void DiskGoal::sampleGoal(ob::State* st) const {
  const double r = goal_.radius_m() * std::sqrt(rng_.uniform01());
  const double a = rng_.uniformReal(-std::numbers::pi, std::numbers::pi);
  auto& pose = pose_of(st);
  pose.setXY(goal_.x_m() + r * std::cos(a), goal_.y_m() + r * std::sin(a));
  pose.setYaw(rng_.uniformReal(-std::numbers::pi, std::numbers::pi));
  if (!velocity_bounds_.empty()) {
    double* v = st->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(1)->values;
    for (std::size_t i = 0; i < velocity_bounds_.size(); ++i) {
      v[i] = rng_.uniformReal(velocity_bounds_[i].first, velocity_bounds_[i].second);
    }
  }
}

unsigned int DiskGoal::maxSampleCount() const { return std::numeric_limits<unsigned int>::max(); }

XyProjection::XyProjection(const ob::StateSpace* space, const OccupancyGrid& grid, double cell_m)
    : ob::ProjectionEvaluator(space), cell_m_(cell_m) {
  ob::RealVectorBounds b(2);
  b.setLow(0, grid.origin_x());
  b.setHigh(0, grid.origin_x() + grid.width_m());
  b.setLow(1, grid.origin_y());
  b.setHigh(1, grid.origin_y() + grid.height_m());
  setBounds(b);
}

void XyProjection::project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const {
  const auto& pose = pose_of(state);
  projection(0) = pose.getX();
  projection(1) = pose.getY();
}

void XyProjection::defaultCellSizes() { cellSizes_ = {cell_m_, cell_m_}; }

ProblemSettings settings_for(const PlannerConfig& config) {
  ProblemSettings s;
  s.step_s = config.integration_step_s;
  s.min_steps =
      static_cast<unsigned>(std::llround(config.min_plan_duration_s / config.integration_step_s));
  s.max_steps =
      static_cast<unsigned>(std::llround(config.max_plan_duration_s / config.integration_step_s));
  return s;
}

Status set_planner(OmplProblem& problem, std::string_view name) {
  const oc::SpaceInformationPtr& si = problem.setup->getSpaceInformation();
  ob::PlannerPtr planner;
  if (name == "pdst") {
    planner = std::make_shared<oc::PDST>(si);
  } else if (name == "kpiece1") {
    planner = std::make_shared<oc::KPIECE1>(si);
  } else if (name == "sst") {
    planner = std::make_shared<oc::SST>(si);
    auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
    objective->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
    problem.setup->setOptimizationObjective(objective);
  } else if (name == "rrt") {
    planner = std::make_shared<oc::RRT>(si);
  } else if (name == "est") {
    planner = std::make_shared<oc::EST>(si);
  } else {
    return invalid_argument("unknown OMPL planner '" + std::string(name) +
                            "' (pdst, kpiece1, sst, rrt, est)");
  }
  problem.setup->setPlanner(planner);
  return Ok{};
}

}  // namespace grip::ompl_bridge
