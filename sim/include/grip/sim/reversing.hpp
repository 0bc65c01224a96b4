#pragma once
// How much of a run the vehicle spent backing up: a car reverses at a fraction of its top speed,
// so time spent reversing is time its turns cost rather than time spent getting anywhere. Beside
// the braking and turning bounds it tells a reader whether a slow run backed up or drove slowly.

#include <array>
#include <cstddef>
#include <span>

#include "grip/common/result.hpp"

namespace grip::sim {

// The share of the last `ticks` ticks of a run in which the reference point moved against the
// chassis's heading. `route[k]` and `headings[k]` are the reference point's (x, y) and the
// heading at the end of tick k; tick k's move runs from route[k - 1] to route[k] (the first
// tick of the route has none and does not count as reversing). 0 when `ticks` is 0. Errors:
// `headings` not of the route's size, `ticks` more than the route's.
Result<double> reversing_fraction(std::span<const std::array<double, 2>> route,
                                  std::span<const double> headings, std::size_t ticks);

}  // namespace grip::sim
