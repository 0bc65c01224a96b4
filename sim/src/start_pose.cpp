#include "grip/sim/start_pose.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "grip/common/saturating_cast.hpp"
#include "grip/world/clearance_map.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip::sim {

namespace {

std::string number_text(double v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return ec == std::errc() ? std::string(buffer.data(), end) : std::to_string(v);
}

std::string pose_text(const StartPose& s) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  std::string text = "(";
  text += number_text(s.x_m) + ", " + number_text(s.y_m) + ", " + number_text(s.theta_rad) + ")";
  return text;
}

// Whether the closed chassis rectangle and the closed cell square intersect (separating axes:
// the square's two axes and the rectangle's two), with a tolerance on the touching side.
bool chassis_touches_cell(const OccupancyGrid& grid, const Footprint& f, const StartPose& s, int cx,
                          int cy) {
  const double c = std::cos(s.theta_rad);
  const double sn = std::sin(s.theta_rad);
  const std::array<std::array<double, 2>, 4> body{{{f.front_m, f.half_width_m},
                                                   {f.front_m, -f.half_width_m},
                                                   {-f.rear_m, f.half_width_m},
                                                   {-f.rear_m, -f.half_width_m}}};
  std::array<std::array<double, 2>, 4> rect{};
  for (std::size_t k = 0; k < 4; ++k) {
    rect[k] = {s.x_m + c * body[k][0] - sn * body[k][1], s.y_m + sn * body[k][0] + c * body[k][1]};
  }
  const double res = grid.resolution();
  const double x0 = grid.origin_x() + cx * res;
  const double y0 = grid.origin_y() + cy * res;
  const std::array<std::array<double, 2>, 4> square{
      {{x0, y0}, {x0 + res, y0}, {x0, y0 + res}, {x0 + res, y0 + res}}};
  const double tol = 1e-9 * res;
  const std::array<std::array<double, 2>, 4> axes{{{1.0, 0.0}, {0.0, 1.0}, {c, sn}, {-sn, c}}};
  for (const auto& axis : axes) {
    double a_lo = std::numeric_limits<double>::infinity();
    double a_hi = -a_lo;
    double b_lo = a_lo;
    double b_hi = -a_lo;
    for (std::size_t k = 0; k < 4; ++k) {
      const double pa = rect[k][0] * axis[0] + rect[k][1] * axis[1];
      const double pb = square[k][0] * axis[0] + square[k][1] * axis[1];
      a_lo = std::min(a_lo, pa);
      a_hi = std::max(a_hi, pa);
      b_lo = std::min(b_lo, pb);
      b_hi = std::max(b_hi, pb);
    }
    if (a_hi < b_lo - tol || b_hi < a_lo - tol) return false;
  }
  return true;
}

}  // namespace

Result<StartPose> parse_start(std::string_view text) {
  StartPose pose;
  std::array<double*, 3> fields{&pose.x_m, &pose.y_m, &pose.theta_rad};
  std::string_view rest = text;
  std::size_t count = 0;
  while (true) {
    const std::size_t comma = rest.find(',');
    std::string_view part = rest.substr(0, comma);
    while (!part.empty() && part.front() == ' ') part.remove_prefix(1);
    while (!part.empty() && part.back() == ' ') part.remove_suffix(1);
    if (count == fields.size()) {
      return invalid_argument("start '" + std::string(text) +
                              "' has more than three numbers: expected X,Y or X,Y,THETA");
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() ||
        !std::isfinite(value)) {
      static constexpr std::array<const char*, 3> kNames{"X", "Y", "THETA"};
      return invalid_argument("start '" + std::string(text) + "': " + kNames[count] +
                              " is not a finite number (got '" + std::string(part) +
                              "'); expected X,Y or X,Y,THETA in metres and radians");
    }
    *fields[count++] = value;
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  if (count < 2) {
    return invalid_argument("start '" + std::string(text) +
                            "' has one number: expected X,Y or X,Y,THETA");
  }
  return pose;
}

Status check_start(const LoadedMap& map, const Footprint& footprint, double check_margin_m,
                   const StartPose& start) {
  const OccupancyGrid& grid = map.grid;
  int cx = 0;
  int cy = 0;
  if (!std::isfinite(start.theta_rad) || !grid.to_cell(start.x_m, start.y_m, cx, cy)) {
    return invalid_argument(map.path + ": start " + pose_text(start) +
                            " is outside the map, which spans x [" + number_text(grid.origin_x()) +
                            ", " + number_text(grid.origin_x() + grid.width_m()) + "] y [" +
                            number_text(grid.origin_y()) + ", " +
                            number_text(grid.origin_y() + grid.height_m()) + "] m");
  }
  auto checker = CollisionChecker::create(grid, footprint, check_margin_m);
  if (!checker) return checker.error();
  if (checker->is_free(start.x_m, start.y_m, start.theta_rad)) return Ok{};
  const Footprint grown = checker->checked_footprint();
  const std::string what = check_margin_m > 0.0
                               ? "the chassis, with the planner's collision margin of " +
                                     number_text(check_margin_m) + " m,"
                               : std::string("the chassis");
  // Name the first obstacle cell the grown chassis touches, scanning its bounding box.
  const int reach = ceil_to_count(grown.circumscribed_radius() / grid.resolution(), 0,
                                  OccupancyGrid::kMaxSideCells) +
                    1;
  for (int y = cy - reach; y <= cy + reach; ++y) {
    for (int x = cx - reach; x <= cx + reach; ++x) {
      if (!grid.in_bounds(x, y) || grid.at(x, y) == Cell::kFree) continue;
      if (!chassis_touches_cell(grid, grown, start, x, y)) continue;
      return invalid_argument(
          map.path + ": start " + pose_text(start) + " puts " + what + " on the obstacle cell (" +
          std::to_string(x) + ", " + std::to_string(y) + ") centred at (" +
          number_text(grid.cell_center_x(x)) + ", " + number_text(grid.cell_center_y(y)) +
          ") m, from " + map.describe_cell(x, y));
    }
  }
  return invalid_argument(map.path + ": start " + pose_text(start) + " puts " + what +
                          " across the edge of the map");
}

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// The start cell for clearance `needed` (see choose_start), or kNone when no cell has it.
std::uint32_t best_start_cell(const OccupancyGrid& grid, const ClearanceMap& clearance,
                              double needed) {
  const std::uint32_t n = grid.cell_count();
  std::vector<std::uint32_t> component(n, kNone);
  std::vector<std::uint32_t> stack;
  std::uint32_t best_root = kNone;
  std::uint32_t best_size = 0;
  std::uint32_t best_cell = kNone;
  // Components in index order (bottom row first), so ties keep the first one found.
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (component[seed] != kNone || clearance.clearance_m(seed) < needed) continue;
    std::uint32_t size = 0;
    std::uint32_t nearest = seed;
    double nearest_d2 = std::numeric_limits<double>::infinity();
    component[seed] = seed;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      ++size;
      const int x = grid.cell_x(i);
      const int y = grid.cell_y(i);
      const double d2 = (x + 0.5) * (x + 0.5) + (y + 0.5) * (y + 0.5);
      if (d2 < nearest_d2 || (d2 == nearest_d2 && i < nearest)) {
        nearest_d2 = d2;
        nearest = i;
      }
      const std::array<std::array<int, 2>, 4> steps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
      for (const auto& d : steps) {
        const int nx = x + d[0];
        const int ny = y + d[1];
        if (!grid.in_bounds(nx, ny)) continue;
        const std::uint32_t j = grid.index(nx, ny);
        if (component[j] != kNone || clearance.clearance_m(j) < needed) continue;
        component[j] = seed;
        stack.push_back(j);
      }
    }
    if (size > best_size) {
      best_size = size;
      best_root = seed;
      best_cell = nearest;
    }
  }
  return best_root == kNone ? kNone : best_cell;
}

}  // namespace

Result<StartPose> choose_start(const LoadedMap& map, const Footprint& footprint,
                               double check_margin_m, double roam_margin_m) {
  for (const double m : {check_margin_m, roam_margin_m}) {
    if (!std::isfinite(m) || m < 0.0) {
      return invalid_argument("start margins must be finite numbers >= 0 (got " + number_text(m) +
                              ")");
    }
  }
  const OccupancyGrid& grid = map.grid;
  auto clearance = ClearanceMap::create_for(grid);
  if (!clearance) return clearance.error();
  // Small arenas (a TurtleBot sandbox) may not hold the full margin: halve it, then drop it.
  const double needed = footprint.circumscribed_radius() + check_margin_m;
  for (const double roam : {roam_margin_m, 0.5 * roam_margin_m, 0.25 * roam_margin_m, 0.0}) {
    const std::uint32_t cell = best_start_cell(grid, *clearance, needed + roam);
    if (cell != kNone) {
      return StartPose{grid.cell_center_x(grid.cell_x(cell)), grid.cell_center_y(grid.cell_y(cell)),
                       0.0};
    }
  }
  // Nowhere does the chassis fit in every heading (a long car in a small arena): the most open
  // cell where it fits in some heading, tried every pi/8. Cells by clearance, largest first
  // (ties: the lower index); a cell nearer an obstacle than the chassis reaches in its
  // narrowest direction cannot hold it in any heading.
  auto checker = CollisionChecker::create(grid, footprint, check_margin_m);
  if (!checker) return checker.error();
  const Footprint grown = checker->checked_footprint();
  const double narrowest = std::min({grown.front_m, grown.rear_m, grown.half_width_m});
  std::vector<std::uint32_t> open;
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) {
    if (clearance->clearance_m(c) >= narrowest) open.push_back(c);
  }
  std::stable_sort(open.begin(), open.end(), [&](std::uint32_t a, std::uint32_t b) {
    return clearance->clearance_m(a) > clearance->clearance_m(b);
  });
  constexpr int kHeadings = 16;
  for (const std::uint32_t c : open) {
    const double x = grid.cell_center_x(grid.cell_x(c));
    const double y = grid.cell_center_y(grid.cell_y(c));
    for (int k = 0; k < kHeadings; ++k) {
      const double theta = 2.0 * std::numbers::pi * k / kHeadings;
      if (checker->is_free(x, y, theta)) return StartPose{x, y, theta};
    }
  }
  return invalid_argument(map.path + ": no place on the map where the chassis, with the " +
                          "planner's collision margin of " + number_text(check_margin_m) +
                          " m, fits in any heading");
}

}  // namespace grip::sim
