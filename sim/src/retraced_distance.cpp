#include "grip/sim/retraced_distance.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "grip/common/saturating_cast.hpp"

namespace grip::sim {

RetracedDistance retraced_distance(std::span<const std::array<double, 2>> trajectory, double cell_m,
                                   double away_m) {
  RetracedDistance out;
  if (trajectory.size() < 2 || !(cell_m > 0.0)) return out;
  const auto square_of = [cell_m](const std::array<double, 2>& p) {
    const auto ix =
        static_cast<std::uint64_t>(saturating_cast<std::int64_t>(std::floor(p[0] / cell_m)));
    const auto iy =
        static_cast<std::uint32_t>(saturating_cast<std::int64_t>(std::floor(p[1] / cell_m)));
    return (ix << 32) ^ iy;
  };
  // Per square the distance driven when the vehicle last left it.
  std::unordered_map<std::uint64_t, double> left_at;
  std::uint64_t square = square_of(trajectory[0]);
  bool retracing = false;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    const double move = std::hypot(trajectory[i][0] - trajectory[i - 1][0],
                                   trajectory[i][1] - trajectory[i - 1][1]);
    const std::uint64_t next = square_of(trajectory[i]);
    if (next != square) {
      left_at[square] = out.distance_m;  // the last sample in it
      const auto before = left_at.find(next);
      retracing = before != left_at.end() && out.distance_m + move - before->second >= away_m;
      square = next;
    }
    out.distance_m += move;
    if (retracing) out.retraced_m += move;
  }
  return out;
}

}  // namespace grip::sim
