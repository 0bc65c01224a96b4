#pragma once
// What the simulator does with a map it loaded, for the map loaders' fuzz targets: choose a
// start for a vehicle (clearance, collision checker) and check the chassis there and at a few
// poses around the map, far outside it included. None of it may crash or overflow on any map a
// loader accepts.

#include <cstdlib>

#include "grip/sim/map_file.hpp"
#include "grip/sim/start_pose.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip::fuzz {

inline void use_loaded_map(const sim::LoadedMap& map) {
  // A loaded map is the ground truth: only free and obstacle, within the grid's limits.
  if (map.grid.cell_count() == 0 || map.grid.cell_count() > OccupancyGrid::kMaxCells) std::abort();
  with_default_vehicle(VehicleKind::kCar, [&](const auto& vehicle) {
    const Footprint& footprint = vehicle.footprint();
    auto checker = CollisionChecker::create(map.grid, footprint, 0.05);
    if (!checker) return;
    const double w = map.grid.width_m();
    const double h = map.grid.height_m();
    const double x0 = map.grid.origin_x();
    const double y0 = map.grid.origin_y();
    for (const double fx : {-1e300, -1.0, 0.0, 0.25, 0.5, 0.99, 1.0, 7.0, 1e300}) {
      for (const double theta : {0.0, 0.7, 3.1, -1e20}) {
        static_cast<void>(checker->is_free(x0 + fx * w, y0 + fx * h, theta));
      }
    }
    auto start = sim::choose_start(map, footprint, 0.05);
    if (start) {
      if (!sim::check_start(map, footprint, 0.05, *start).ok()) std::abort();  // it chose it
      static_cast<void>(map.describe_cell(0, 0));
    }
  });
}

}  // namespace grip::fuzz
