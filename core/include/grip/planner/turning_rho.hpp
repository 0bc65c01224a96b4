#pragma once
// rho for a vehicle with a minimum turning radius R (the car): how far its reference point has
// to go to F, knowing that it cannot turn in place. Hybrid A*'s heuristic (Dolgov et al. 2008)
// takes the larger of an obstacle-aware grid distance and an obstacle-free distance that
// respects the turning circle; its goal is a pose, F is a set of cells, so the second half is
// taken toward a lookahead point: the point `lookahead` ahead on the state's shortest grid path
// to F (DistanceField::descend), or the cell of F that path ends at when it is shorter. Then
//   rho(q) = max(rho_A*(q), rho_A*(a) + turning distance from q's pose to a)
// A state facing along its path keeps rho_A*; one facing away, or beside a corner it cannot
// turn into from where it stands, pays for the manoeuvre it needs (a U-turn, a reversal).
// The lookahead is three turning radii: a U-turn's span and the straight that lines it up.
//
// A cell counts as reached anywhere in it, so the lookahead cell is taken as its nearest point
// rather than its centre: rho is 0 in F's cells as it is for rho_A*.
//
// Descending the field costs a few dozen cell reads, and the tree asks for rho at every state
// it grows, mostly in the same few thousand cells: the lookahead cell of each cell asked for is
// kept in a small direct-mapped cache until forget(), which the owner calls whenever the field
// changes. So at() is const but not safe to call from two threads at once.
//
// create() allocates the table (TurningDistance) and the cache; at() and forget() never
// allocate and never throw.

#include <cmath>
#include <cstdint>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/planner/turning_distance.hpp"
#include "grip/world/distance_field.hpp"

namespace grip {

class TurningRho {
 public:
  // For a turning radius > 0 [m] and a grid of this resolution [m]; errors name the value.
  static Result<TurningRho> create(double turning_radius_m, double resolution_m);

  // [m] rho at the pose (x_m, y_m, theta) on `field` (rho_A* toward F, of the grid's
  // resolution); +infinity where rho_A* is.
  double at(const DistanceField& field, double x_m, double y_m, double theta) const noexcept;
  // The field at() reads has changed (a new wavefront, another field): the cached lookahead
  // cells are stale.
  void forget() noexcept;

  double lookahead_m() const noexcept { return lookahead_m_; }
  const TurningDistance& table() const noexcept { return table_; }

 private:
  TurningRho(TurningDistance table, double lookahead_m, double resolution_m);

  struct CachedLookahead {
    std::uint32_t cell = DistanceField::kNoCell;
    std::uint32_t generation = 0;
    std::uint32_t ahead = 0;
  };
  std::uint32_t lookahead_cell(const DistanceField& field, std::uint32_t cell) const noexcept;

  TurningDistance table_;
  mutable std::vector<CachedLookahead> cache_;  // by cell index modulo its size
  std::uint32_t generation_ = 1;
  double lookahead_m_;
  std::uint32_t lookahead_units_;  // lookahead_m in the field's cost units
  double half_cell_m_;
};

}  // namespace grip
