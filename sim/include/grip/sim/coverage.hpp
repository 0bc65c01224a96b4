#pragma once
// Coverage of an exploration run: the sensed fraction of the free space the vehicle can reach
// from its start.

#include <cstdint>
#include <vector>

#include "grip/common/result.hpp"
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

// The fraction of `reachable` that `known` has sensed (not unknown); 1 when it is empty.
double coverage_of(const OccupancyGrid& known, const std::vector<std::uint32_t>& reachable);

}  // namespace grip::sim
