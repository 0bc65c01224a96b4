#pragma once
// Where the vehicle starts on a loaded map: given by the user (`--start X,Y`) and checked, or
// chosen deterministically. Both run at start-up and may allocate.

#include <string_view>

#include "grip/common/result.hpp"
#include "grip/sim/map_file.hpp"
#include "grip/world/footprint.hpp"

namespace grip::sim {

struct StartPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
};

// Parses "X,Y" or "X,Y,THETA" (metres, metres, radians; blanks around numbers allowed).
// Errors (kInvalidArgument) quote the text and say which part is wrong.
Result<StartPose> parse_start(std::string_view text);

// Checks a start: finite, inside the grid, and the chassis at rest there, grown by check_margin_m
// on every side (the planner's collision margin: a start closer to an obstacle is one the
// planner refuses), touches no obstacle cell and stays inside the map. Errors
// (kInvalidArgument) name the map file, the start, the margin, and the first obstacle cell the
// grown chassis touches with where it is in the file (LoadedMap::describe_cell).
Status check_start(const LoadedMap& map, const Footprint& footprint, double check_margin_m,
                   const StartPose& start);

// The chosen start: among the cells whose centre is at least footprint.circumscribed_radius()
// + check_margin_m + roam_margin_m from every obstacle and from the map's edge (so the chassis
// grown by the planner's margin fits in every heading, with room to spare), take the largest
// 4-connected group of such cells (the widest region the vehicle can roam freely: not a closed
// pocket), and in it the cell whose centre is nearest the map's bottom-left corner (ties: the
// lower row, then the lower column); heading 0 (+x). When no cell has the room to spare, it is
// halved, quartered, then dropped (small arenas), never the check margin; only when the chassis
// fits nowhere even then, kInvalidArgument names the file and the clearance needed.
Result<StartPose> choose_start(const LoadedMap& map, const Footprint& footprint,
                               double check_margin_m, double roam_margin_m = 0.3);

}  // namespace grip::sim
