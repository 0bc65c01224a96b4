#pragma once
// Ground-truth maps from files (`grip sim --map FILE`): MovingAI `.map` grids and ROS map_server
// `.yaml` + `.pgm` maps (formats: ../shared/maps/README.md).
//
// The result is an OccupancyGrid with kFree and kObstacle only (the ground truth has no
// unknown), row 0 at the bottom (y up) while both file formats store the top row first.
// Unknown pixels of a ROS map (occupancy between free_thresh and occupied_thresh) become
// obstacles: nobody observed that space, so the simulator must not let the vehicle drive or see
// through it, and exploration ends at the edge of what the map maker surveyed.
//
// MovingAI cells have no physical size. Default: 1 m per map cell, each split into 10 x 10 grid
// cells of 0.1 m (the built-in scenes' resolution). At 1 m, the shared maps read as buildings
// (maze-32-32-4: 32 m with 4 m corridors, like the paper's 30 m scenes; room-64-64-8: 7 m rooms
// joined by 1 m doors; warehouse: 1 m aisles), passable by vehicles up to about 0.6 x 0.45 m, and
// the sensing radius (a tenth of the width) is a few metres, as in the paper.
//
// Errors name the file and the line (and column where it helps) in the compiler style
// "path:line:column: message": kIo when a file cannot be read, kParse for malformed content,
// kInvalidArgument for bad options. Semantic bounds apply as well as syntax: resolution in
// [OccupancyGrid::kMinResolutionM, kMaxResolutionM], origin within kMaxOriginM, sizes within
// the grid's limits, the file regular and at most kMaxMapFileBytes. Nothing here throws; all of it
// runs at start-up and may allocate.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::sim {

enum class MapFormat : std::uint8_t { kMovingAi, kRosMapServer };

// The largest map file read (a PGM of the largest grid, 2 bytes a pixel, fits; ASCII PGMs that
// large are refused). Larger files, and anything that is not a regular file, are kIo errors.
inline constexpr std::uintmax_t kMaxMapFileBytes = std::uintmax_t{64} << 20;

struct MapLoadOptions {
  double movingai_cell_m = 1.0;   // [m] side of one MovingAI map cell
  int movingai_subdivision = 10;  // grid cells per MovingAI cell side (>= 1)

  Status validate() const;
};

struct LoadedMap {
  OccupancyGrid grid;  // the ground truth
  MapFormat format;
  std::string path;                  // the file given (the .map or the .yaml)
  std::string image_path;            // ROS: the PGM it names, resolved; empty for MovingAI
  std::uint32_t unknown_pixels = 0;  // ROS: pixels between the thresholds, made obstacles
  int first_row_line = 0;            // MovingAI: file line of the top map row
  int cells_per_pixel = 1;           // grid cells per file cell side (MovingAI subdivision)

  // Where grid cell (cx, cy) comes from in the file, for error messages:
  // "maze.map:12:7" (MovingAI, line and column) or "depot.pgm pixel (column 5, row 7)".
  std::string describe_cell(int cx, int cy) const;
};

// By extension: ".map" is MovingAI, ".yaml" / ".yml" is ROS map_server; anything else is a
// kInvalidArgument error naming the file.
Result<LoadedMap> load_map(const std::string& path, const MapLoadOptions& options = {});
Result<LoadedMap> load_movingai_map(const std::string& path, const MapLoadOptions& options = {});
Result<LoadedMap> load_ros_map(const std::string& yaml_path);

// The parsers behind the loaders, on text already read (`name` is used in messages).
Result<LoadedMap> parse_movingai_map(std::string_view text, const std::string& name,
                                     const MapLoadOptions& options = {});
// A map_server map from its YAML text and the bytes of the PGM it names (the image is not
// read: `pgm_bytes` stands for it, and its resolved path is used in messages).
Result<LoadedMap> parse_ros_map(std::string_view yaml_text, const std::string& yaml_name,
                                std::string_view pgm_bytes);

// A PGM image (P5 binary or P2 ASCII), rows top first as in the file.
struct PgmImage {
  int width = 0;
  int height = 0;
  int maxval = 0;                     // 1..65535; P5 uses two bytes per pixel above 255
  std::vector<std::uint16_t> pixels;  // width * height, row-major, row 0 = top
};
Result<PgmImage> parse_pgm(std::string_view bytes, const std::string& name);

}  // namespace grip::sim
