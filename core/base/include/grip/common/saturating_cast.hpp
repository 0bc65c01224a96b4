#pragma once
// Float-to-integer conversion that is defined for every input. A plain static_cast of a double
// outside the target's range (huge, infinite, NaN) is undefined behaviour, and in grid code the
// garbage it yields becomes an index: hostile input (a map with an extreme resolution, a state
// far outside the map) must never reach that. Every such conversion in the world code goes
// through here, or is range-checked just before it.

#include <cmath>
#include <concepts>
#include <limits>

namespace grip {

// `value` truncated toward zero like static_cast, then clamped to T's range; NaN gives
// `if_nan` (0 unless told). noexcept and allocation-free: usable on the planning path.
template <std::integral T>
inline T saturating_cast(double value, T if_nan = T{0}) noexcept {
  if (std::isnan(value)) return if_nan;
  // The bounds as doubles: lo is exact (a power of two or 0); hi rounds up to a power of two,
  // so `value >= hi` catches everything that does not fit.
  constexpr double lo = static_cast<double>(std::numeric_limits<T>::min());
  constexpr double hi = static_cast<double>(std::numeric_limits<T>::max());
  if (value <= lo) return std::numeric_limits<T>::min();
  if (value >= hi) return std::numeric_limits<T>::max();
  return static_cast<T>(value);
}

// floor(value) as an int clamped to [lo, hi] (NaN gives lo): a cell coordinate that cannot
// overflow, e.g. floor_to_cell(u, -1, width) for a traversal that may step one cell outside.
inline int floor_to_cell(double value, int lo, int hi) noexcept {
  if (!(value >= lo)) return lo;  // also NaN
  if (value >= hi) return hi;
  return static_cast<int>(std::floor(value));
}

// ceil(value) as an int clamped to [lo, hi] (NaN gives hi: the conservative side of a reach).
inline int ceil_to_count(double value, int lo, int hi) noexcept {
  if (std::isnan(value) || value >= hi) return hi;
  if (value <= lo) return lo;
  return static_cast<int>(std::ceil(value));
}

}  // namespace grip
