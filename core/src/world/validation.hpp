#pragma once
// Start-up parameter checks shared by the world/ factories (private to core/src/world).
// They build error messages, so they allocate: never call them on the planning path.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "grip/common/result.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::detail {

// Shortest round-trip text of a double ("0.1", "-3", "nan", "inf").
inline std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// Checks the sizes every grid-shaped buffer shares with OccupancyGrid.
inline std::optional<Error> check_grid_size(const char* who, int width_cells, int height_cells,
                                            double resolution_m) {
  const auto side_error = [&](const char* name, int value) {
    return invalid_argument(std::string(who) + ": " + name + " must be in [1, " +
                            std::to_string(OccupancyGrid::kMaxSideCells) + "] (got " +
                            std::to_string(value) + ")");
  };
  if (width_cells < 1 || width_cells > OccupancyGrid::kMaxSideCells) {
    return side_error("width_cells", width_cells);
  }
  if (height_cells < 1 || height_cells > OccupancyGrid::kMaxSideCells) {
    return side_error("height_cells", height_cells);
  }
  const auto cells =
      static_cast<std::uint64_t>(width_cells) * static_cast<std::uint64_t>(height_cells);
  if (cells > OccupancyGrid::kMaxCells) {
    return invalid_argument(std::string(who) + ": width_cells * height_cells must be <= " +
                            std::to_string(OccupancyGrid::kMaxCells) + " (got " +
                            std::to_string(width_cells) + " * " + std::to_string(height_cells) +
                            " = " + std::to_string(cells) + ")");
  }
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
    return invalid_argument(std::string(who) + ": resolution_m must be finite and > 0 (got " +
                            format_number(resolution_m) + ")");
  }
  return std::nullopt;
}

}  // namespace grip::detail
