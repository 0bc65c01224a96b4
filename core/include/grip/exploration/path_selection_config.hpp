#pragma once
// The configuration of the path weight (exploration/path_selector.hpp, which defines its terms),
// apart from the selector, so that the runtime's and the parameter file's settings can name its
// defaults without the planner's templates.

#include "grip/common/result.hpp"

namespace grip {

struct PathSelectionConfig {
  double sensing_radius_m = 3.0;      // d_max: the sensor's range (one tenth of the scene)
  double length_weight_per_m = 0.05;  // lambda: a trajectory 14 m longer weighs twice as much
  double sample_step_s = 0.2;         // states sampled along each edge this far apart in time
  // > 0: l(tr) is the distance covered at this speed [m/s] in tr's duration rather than tr's
  // length, so that of two trajectories to the same place the faster one weighs less. The
  // paper's length leaves speed out of the choice, and a vehicle whose speed changes at a
  // bounded rate then drives at the speed of whichever trajectory ends best, well below what
  // braking allows. 0: the length.
  double reference_speed_m_s = 0.0;
  // A trajectory that leaves the course of the last plan weighs as if it were this much longer
  // (PathSelector::select's `course`), so that the choice does not flip between branches of nearly
  // equal weight from one cycle to the next, the vehicle steering toward each in turn. 0: the
  // paper's choice, made afresh every cycle.
  double course_change_m = 0.0;

  // Errors name the bad value: any value not finite or not > 0 (lambda, the reference speed
  // and the course change may be 0).
  Status validate() const;
};

// A reference speed or course change for the runtime to take from the vehicle
// (rt::ExplorationDriver): "auto" in a parameter file.
inline constexpr double kPathWeightOfVehicle = -1.0;

// The path weight as a deployment sets it (a parameter file's exploration keys), carried as it is
// from the file to the runtime, which turns it into a PathSelectionConfig for its vehicle and map
// (rt::ExplorationDriver::create).
struct PathWeightSettings {
  double sensing_radius_m = 0.0;  // d_max; 0: the runtime's default (a tenth of the map's width)
  double length_weight_per_m = PathSelectionConfig{}.length_weight_per_m;
  // kPathWeightOfVehicle: the vehicle's; another negative value is refused.
  double reference_speed_m_s = kPathWeightOfVehicle;
  double course_change_m = kPathWeightOfVehicle;

  bool operator==(const PathWeightSettings&) const = default;
};

}  // namespace grip
