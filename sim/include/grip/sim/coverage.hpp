#pragma once
// Coverage of an exploration run: the sensed fraction of the free space the vehicle can reach
// from its start.

#include <cstdint>
#include <utility>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/distance_field.hpp"
#include "grip/world/footprint.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::sim {

// The free cells of `truth` the vehicle can reach from (x, y): its reference point moves
// through cells with at least half its width of clearance, and its body covers the free cells
// within its circumscribed radius of those (through free space). Gaps narrower than the
// vehicle, and free pockets inside obstacles (the racks of real maps are dotted outlines), are
// not reachable. A start too close to a wall for that falls back to every free cell
// 8-connected to it. Errors: the start outside the map.
Result<std::vector<std::uint32_t>> reachable_free_cells(const OccupancyGrid& truth, double x_m,
                                                        double y_m, const Footprint& footprint);

// The cells of `reachable` that `known` has sensed (not unknown).
std::size_t sensed_cells(const OccupancyGrid& known, const std::vector<std::uint32_t>& reachable);
// Their fraction of `reachable`; 1 when it is empty.
double coverage_of(const OccupancyGrid& known, const std::vector<std::uint32_t>& reachable);

// How far a point is, along the free cells of `truth` (8-connected, as the planner's rho), from
// the nearest reachable cell not sensed yet: what a vehicle on its way to unexplored ground
// shortens while it senses nothing new (the last frontier of a maze can be minutes away).
// Memory is taken by create().
class UnsensedDistance {
 public:
  // `truth` and `reachable` (reachable_free_cells of it) must outlive the object. Errors as
  // for DistanceField::create.
  static Result<UnsensedDistance> create(const OccupancyGrid& truth,
                                         const std::vector<std::uint32_t>& reachable);
  // [m] +infinity when every reachable cell is sensed, or none is reachable from (x_m, y_m).
  // One wavefront over the map: O(cells).
  double from(const OccupancyGrid& known, double x_m, double y_m);

 private:
  UnsensedDistance(const OccupancyGrid& truth, const std::vector<std::uint32_t>& reachable,
                   DistanceField field)
      : truth_(&truth), reachable_(&reachable), field_(std::move(field)) {
    unsensed_.reserve(reachable.size());
  }
  const OccupancyGrid* truth_;
  const std::vector<std::uint32_t>* reachable_;
  std::vector<std::uint32_t> unsensed_;
  DistanceField field_;
};

}  // namespace grip::sim
