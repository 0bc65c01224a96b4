#include "grip/sim/reversing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace grip::sim {

Result<double> reversing_fraction(std::span<const std::array<double, 2>> route,
                                  std::span<const double> headings, std::size_t ticks) {
  if (headings.size() != route.size()) {
    return invalid_argument("reversing_fraction: " + std::to_string(headings.size()) +
                            " headings for a route of " + std::to_string(route.size()) + " ticks");
  }
  if (ticks > route.size()) {
    return invalid_argument("reversing_fraction: the last " + std::to_string(ticks) +
                            " ticks of a route of " + std::to_string(route.size()));
  }
  if (ticks == 0) return 0.0;
  std::size_t reversing = 0;
  for (std::size_t k = std::max<std::size_t>(route.size() - ticks, 1); k < route.size(); ++k) {
    const double dx = route[k][0] - route[k - 1][0];
    const double dy = route[k][1] - route[k - 1][1];
    if (dx * std::cos(headings[k]) + dy * std::sin(headings[k]) < 0.0) ++reversing;
  }
  return static_cast<double>(reversing) / static_cast<double>(ticks);
}

}  // namespace grip::sim
