#include "grip/scenes/scenes.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <utility>

#include "grip/common/enum_names.hpp"

namespace grip {

namespace {

constexpr int kSceneCells = 300;
constexpr double kResolution = 0.1;                  // [m]
constexpr double kSide = kSceneCells * kResolution;  // [m] 30
constexpr double kWall = 0.3;                        // [m] thickness of every wall

constexpr std::array<SceneId, 3> kAllScenes = {SceneId::kMeandros, SceneId::kLabyrinth,
                                               SceneId::kRooms};

std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// splitmix64: a complete, tiny PRNG defined here so the maze never changes with the standard
// library or with the project's general-purpose generator.
class SceneRandom {
 public:
  explicit SceneRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // Uniform enough in [0, n) for n small; exactly reproducible.
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }

 private:
  std::uint64_t state_;
};

OccupancyGrid empty_walled_grid() {
  auto grid = OccupancyGrid::create(kSceneCells, kSceneCells, kResolution, 0.0, 0.0, Cell::kFree);
  GRIP_ASSERT(grid.ok());  // constant, valid parameters
  OccupancyGrid g = std::move(grid).value();
  g.fill_rect(0.0, 0.0, kSide, kWall, Cell::kObstacle);
  g.fill_rect(0.0, kSide - kWall, kSide, kSide, Cell::kObstacle);
  g.fill_rect(0.0, 0.0, kWall, kSide, Cell::kObstacle);
  g.fill_rect(kSide - kWall, 0.0, kSide, kSide, Cell::kObstacle);
  return g;
}

// Six corridors (4.7/4.6 m) stacked bottom to top between y = 0.3 and 29.7, separated by 0.3 m
// walls; each wall leaves a 3.5 m opening at its right end (even walls) or left end (odd).
Scene make_meandros() {
  OccupancyGrid grid = empty_walled_grid();
  constexpr std::array<double, 6> kCorridor = {4.7, 4.6, 4.7, 4.6, 4.7, 4.6};
  constexpr double kOpening = 3.5;
  double y = kWall;
  for (std::size_t k = 0; k + 1 < kCorridor.size(); ++k) {
    y += kCorridor[k];
    if (k % 2 == 0) {
      grid.fill_rect(kWall, y, kSide - kWall - kOpening, y + kWall, Cell::kObstacle);
    } else {
      grid.fill_rect(kWall + kOpening, y, kSide - kWall, y + kWall, Cell::kObstacle);
    }
    y += kWall;
  }
  // The top corridor is [25.1, 29.7]; it is entered from the right, so the goal is at its left.
  return Scene{
      .name = "meandros",
      .description =
          "Six horizontal corridors 4.6-4.7 m wide, separated by 0.3 m walls whose 3.5 m "
          "openings alternate between the right and left ends, form one serpentine about 150 m "
          "long. Start at the bottom-left heading east; goal at the far end, the left end of "
          "the top corridor.",
      .grid = std::move(grid),
      .start_x_m = 2.0,
      .start_y_m = kWall + kCorridor[0] / 2.0,
      .start_theta_rad = 0.0,
      .goal_x_m = 2.5,
      .goal_y_m = 27.4,
      .goal_radius_m = 1.0,
  };
}

// A perfect maze on 8 x 8 cells of pitch 3.7 m (3.4 m passages, 0.3 m walls), carved by a
// recursive backtracker with a fixed seed.
Scene make_labyrinth() {
  constexpr int kN = 8;
  constexpr double kPitch = 3.7;
  // Seed 5 of 1..12: the one whose start-to-goal route is longest (46 cell steps).
  constexpr std::uint64_t kSeed = 5;
  OccupancyGrid grid = empty_walled_grid();
  // Every wall line first (lines 0 and 8 double the border), then carve the passages.
  for (int k = 0; k <= kN; ++k) {
    const double at = k * kPitch;
    grid.fill_rect(at, 0.0, at + kWall, kSide, Cell::kObstacle);
    grid.fill_rect(0.0, at, kSide, at + kWall, Cell::kObstacle);
  }
  std::array<bool, kN * kN> visited{};
  std::array<bool, kN * kN> open_east{};
  std::array<bool, kN * kN> open_north{};
  std::vector<int> stack;
  SceneRandom random(kSeed);
  stack.push_back(0);
  visited[0] = true;
  while (!stack.empty()) {
    const int cell = stack.back();
    const int cx = cell % kN;
    const int cy = cell / kN;
    std::array<int, 4> choices{};
    std::size_t count = 0;
    constexpr std::array<std::array<int, 2>, 4> kSteps = {{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
    for (std::size_t d = 0; d < kSteps.size(); ++d) {
      const int nx = cx + kSteps[d][0];
      const int ny = cy + kSteps[d][1];
      if (nx >= 0 && ny >= 0 && nx < kN && ny < kN &&
          !visited[static_cast<std::size_t>(ny * kN + nx)]) {
        choices[count++] = static_cast<int>(d);
      }
    }
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    const auto d = static_cast<std::size_t>(choices[random.below(count)]);
    const int nx = cx + kSteps[d][0];
    const int ny = cy + kSteps[d][1];
    const int next = ny * kN + nx;
    switch (d) {
      case 0:
        open_east[static_cast<std::size_t>(cell)] = true;
        break;
      case 1:
        open_north[static_cast<std::size_t>(cell)] = true;
        break;
      case 2:
        open_east[static_cast<std::size_t>(next)] = true;
        break;
      default:
        open_north[static_cast<std::size_t>(next)] = true;
        break;
    }
    visited[static_cast<std::size_t>(next)] = true;
    stack.push_back(next);
  }
  for (int cy = 0; cy < kN; ++cy) {
    for (int cx = 0; cx < kN; ++cx) {
      const auto cell = static_cast<std::size_t>(cy * kN + cx);
      const double x0 = cx * kPitch + kWall;  // passage interior [x0, x0 + 3.4]
      const double y0 = cy * kPitch + kWall;
      if (open_east[cell]) {
        grid.fill_rect(x0 + kPitch - kWall, y0, x0 + kPitch, y0 + kPitch - kWall, Cell::kFree);
      }
      if (open_north[cell]) {
        grid.fill_rect(x0, y0 + kPitch - kWall, x0 + kPitch - kWall, y0 + kPitch, Cell::kFree);
      }
    }
  }
  const double centre0 = kWall + (kPitch - kWall) / 2.0;   // 2.0
  const double centre_last = (kN - 1) * kPitch + centre0;  // 27.9
  const double start_theta = open_east[0] ? 0.0 : std::numbers::pi / 2.0;
  return Scene{
      .name = "labyrinth",
      .description =
          "A perfect maze of 8 x 8 cells on a 3.7 m pitch (3.4 m passages, 0.3 m walls) carved "
          "by a fixed-seed recursive backtracker. Start in the bottom-left cell facing its "
          "opening; goal in the top-right cell.",
      .grid = std::move(grid),
      .start_x_m = centre0,
      .start_y_m = centre0,
      .start_theta_rad = start_theta,
      .goal_x_m = centre_last,
      .goal_y_m = centre_last,
      .goal_radius_m = 1.0,
  };
}

// 3 x 3 rooms of 9.6 m separated by 0.3 m walls at 9.9 and 19.8 m; 1.6 m doors join some
// adjacent rooms so that the way winds; furniture blocks stand inside the rooms.
Scene make_rooms() {
  OccupancyGrid grid = empty_walled_grid();
  constexpr std::array<double, 2> kWallAt = {9.9, 19.8};
  for (const double at : kWallAt) {
    grid.fill_rect(at, 0.0, at + kWall, kSide, Cell::kObstacle);
    grid.fill_rect(0.0, at, kSide, at + kWall, Cell::kObstacle);
  }
  constexpr double kDoor = 1.6;
  // Doors in the vertical walls: {wall x, door's lower y}.
  constexpr std::array<std::array<double, 2>, 6> kVerticalDoors = {{
      {9.9, 7.0},    // room (0,0) - (1,0)
      {19.8, 1.5},   // room (1,0) - (2,0)
      {19.8, 16.5},  // room (1,1) - (2,1)
      {9.9, 11.5},   // room (0,1) - (1,1)
      {9.9, 27.0},   // room (0,2) - (1,2)
      {19.8, 21.5},  // room (1,2) - (2,2)
  }};
  // Doors in the horizontal walls: {wall y, door's left x}.
  constexpr std::array<std::array<double, 2>, 3> kHorizontalDoors = {{
      {9.9, 26.5},  // room (2,0) - (2,1)
      {19.8, 1.8},  // room (0,1) - (0,2)
      {9.9, 14.2},  // room (1,0) - (1,1)
  }};
  for (const auto& door : kVerticalDoors) {
    grid.fill_rect(door[0], door[1], door[0] + kWall, door[1] + kDoor, Cell::kFree);
  }
  for (const auto& door : kHorizontalDoors) {
    grid.fill_rect(door[1], door[0], door[1] + kDoor, door[0] + kWall, Cell::kFree);
  }
  // Furniture: {x0, y0, x1, y1}.
  constexpr std::array<std::array<double, 4>, 8> kFurniture = {{
      {4.5, 3.5, 6.0, 5.0},      // room (0,0)
      {13.5, 4.0, 16.5, 5.5},    // room (1,0)
      {23.0, 5.0, 24.5, 8.0},    // room (2,0)
      {3.0, 15.5, 7.0, 16.5},    // room (0,1)
      {14.0, 14.0, 16.0, 16.0},  // room (1,1)
      {5.0, 22.0, 6.0, 26.0},    // room (0,2)
      {12.0, 23.0, 13.0, 24.0},  // room (1,2)
      {22.5, 23.0, 24.0, 24.5},  // room (2,2)
  }};
  for (const auto& block : kFurniture) {
    grid.fill_rect(block[0], block[1], block[2], block[3], Cell::kObstacle);
  }
  return Scene{
      .name = "rooms",
      .description =
          "Nine 9.6 m rooms in a 3 x 3 layout behind 0.3 m walls, joined by 1.6 m doors between "
          "only some neighbours so the way winds, with furniture blocks inside. Start in the "
          "bottom-left room; goal in the top-right room.",
      .grid = std::move(grid),
      .start_x_m = 2.0,
      .start_y_m = 2.0,
      .start_theta_rad = 0.0,
      .goal_x_m = 27.5,
      .goal_y_m = 27.5,
      .goal_radius_m = 1.0,
  };
}

}  // namespace

std::span<const SceneId> all_scenes() noexcept { return kAllScenes; }

namespace {
constexpr std::array<NamedValue<SceneId>, 3> kSceneNames{{
    {SceneId::kMeandros, "meandros"},
    {SceneId::kLabyrinth, "labyrinth"},
    {SceneId::kRooms, "rooms"},
}};
}  // namespace

std::string_view scene_name(SceneId id) noexcept { return name_in(kSceneNames, id); }

namespace {

Result<Scene> checked(Scene scene) {
  Status valid = validate_start_goal(scene.grid, scene.start_x_m, scene.start_y_m, scene.goal_x_m,
                                     scene.goal_y_m, scene.goal_radius_m);
  if (!valid.ok()) {
    return Error{valid.error().code, "scene " + scene.name + ": " + valid.error().message};
  }
  return scene;
}

}  // namespace

Result<Scene> make_scene(SceneId id) {
  switch (id) {
    case SceneId::kMeandros:
      return checked(make_meandros());
    case SceneId::kLabyrinth:
      return checked(make_labyrinth());
    case SceneId::kRooms:
      return checked(make_rooms());
  }
  return invalid_argument("make_scene: unknown SceneId " + std::to_string(static_cast<int>(id)));
}

Result<Scene> make_scene(std::string_view name) {
  auto id = value_named(kSceneNames, name, "scene");
  if (!id) return id.error();
  return make_scene(*id);
}

Status validate_start_goal(const OccupancyGrid& grid, double start_x_m, double start_y_m,
                           double goal_x_m, double goal_y_m, double goal_radius_m) {
  const std::pair<const char*, double> values[] = {
      {"start_x_m", start_x_m}, {"start_y_m", start_y_m},         {"goal_x_m", goal_x_m},
      {"goal_y_m", goal_y_m},   {"goal_radius_m", goal_radius_m},
  };
  for (const auto& [label, value] : values) {
    if (!std::isfinite(value)) {
      return invalid_argument(std::string(label) + " must be finite (got " + format_number(value) +
                              ")");
    }
  }
  if (!(goal_radius_m > 0.0)) {
    return invalid_argument("goal_radius_m must be > 0 (got " + format_number(goal_radius_m) + ")");
  }
  const auto check_point = [&grid](const char* what, double x, double y) -> Status {
    // Appended piecewise: "(" + std::string trips GCC 12's -Wrestrict false positive at -O3.
    std::string where = "(";
    where += format_number(x);
    where += ", ";
    where += format_number(y);
    where += ")";
    int cx = 0;
    int cy = 0;
    if (!grid.to_cell(x, y, cx, cy)) {
      return invalid_argument(std::string(what) + " " + where + " is outside the grid [" +
                              format_number(grid.origin_x()) + ", " +
                              format_number(grid.origin_x() + grid.width_m()) + "] x [" +
                              format_number(grid.origin_y()) + ", " +
                              format_number(grid.origin_y() + grid.height_m()) + "]");
    }
    const Cell cell = grid.at(cx, cy);
    if (cell != Cell::kFree) {
      return invalid_argument(std::string(what) + " " + where + " lies in " +
                              (cell == Cell::kObstacle ? "an obstacle" : "unknown space") +
                              " (cell " + std::to_string(cx) + ", " + std::to_string(cy) + ")");
    }
    return Ok{};
  };
  if (Status start = check_point("start", start_x_m, start_y_m); !start.ok()) {
    return start;
  }
  return check_point("goal", goal_x_m, goal_y_m);
}

std::vector<std::uint32_t> goal_cells(const OccupancyGrid& grid, double goal_x_m, double goal_y_m,
                                      double goal_radius_m) {
  std::vector<std::uint32_t> cells;
  if (!(std::isfinite(goal_x_m) && std::isfinite(goal_y_m) && goal_radius_m >= 0.0)) {
    return cells;
  }
  const double r2 = goal_radius_m * goal_radius_m;
  for (int cy = 0; cy < grid.height(); ++cy) {
    const double dy = grid.cell_center_y(cy) - goal_y_m;
    if (dy * dy > r2) {
      continue;
    }
    for (int cx = 0; cx < grid.width(); ++cx) {
      const double dx = grid.cell_center_x(cx) - goal_x_m;
      if (dx * dx + dy * dy <= r2 && grid.at(cx, cy) == Cell::kFree) {
        cells.push_back(grid.index(cx, cy));
      }
    }
  }
  return cells;
}

}  // namespace grip
