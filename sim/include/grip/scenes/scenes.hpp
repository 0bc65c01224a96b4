#pragma once
// Built-in scenes in the spirit of the paper's (Sec. VI of Bekris and Kavraki 2007): "meandros" (a long
// serpentine of corridors), "labyrinth" (a perfect maze) and "rooms" (rooms joined by doors).
// Each is 30 m x 30 m at 0.1 m cells (300 x 300), fully known (every cell kFree or kObstacle),
// walled by a 0.3 m border, and deterministic: identical on every run and standard library.
// The start is in the bottom-left corner, the goal disk far from it; both lie at least 1.5 m
// from every wall.
//
// Sized for vehicles up to about 0.6 m x 0.45 m, a car's 0.5 m minimum turning radius, 3 m/s
// and 0.6 m/s^2 (7.5 m to brake from full speed).
//
// Everything here runs at start-up and may allocate.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

enum class SceneId { kMeandros, kLabyrinth, kRooms };

struct Scene {
  std::string name;         // as accepted by make_scene(std::string_view)
  std::string description;  // one or two sentences: layout, start and goal
  OccupancyGrid grid;
  double start_x_m;
  double start_y_m;
  double start_theta_rad;
  double goal_x_m;
  double goal_y_m;
  double goal_radius_m;
};

// Builds the scene (and checks it with validate_start_goal).
Result<Scene> make_scene(SceneId id);
// By name ("meandros", "labyrinth", "rooms"); an unknown name is a kInvalidArgument error whose
// message lists the valid names.
Result<Scene> make_scene(std::string_view name);
std::span<const SceneId> all_scenes() noexcept;
std::string_view scene_name(SceneId id) noexcept;

// Checks a start and goal against a grid: all values finite, goal_radius_m > 0, start and goal
// inside the grid and on kFree cells. Errors name the offending value.
Status validate_start_goal(const OccupancyGrid& grid, double start_x_m, double start_y_m,
                           double goal_x_m, double goal_y_m, double goal_radius_m);

// The kFree cells (grid indices, ascending) whose centres lie within goal_radius_m of the goal
// point: the target set of the distance field.
std::vector<std::uint32_t> goal_cells(const OccupancyGrid& grid, double goal_x_m, double goal_y_m,
                                      double goal_radius_m);

}  // namespace grip
