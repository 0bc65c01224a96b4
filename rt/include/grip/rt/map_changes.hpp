#pragma once
// The one way map updates reach a planner's grid: written cell by cell, with a record of where
// cells stopped being free (only those can cut the tree: ReplanningCycle::note_newly_blocked)
// and where any cell changed between free and not free (the planner's clearance is refreshed
// near those only: ReplanningCycle::note_changed). Never allocates; planning thread.

#include <span>

#include "grip/rt/replanning_cycle.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::rt {

struct MapChanges {
  bool applied = false;   // some update was written
  CellBox written;        // every cell written, whatever it held before
  CellBox newly_blocked;  // cells that stopped being free
  CellBox changed;        // cells that became free or stopped being free

  // Writes `cells`, row-major over `box` (inside the grid, cells.size() its area).
  void apply(OccupancyGrid& grid, const CellBox& box, std::span<const Cell> cells) noexcept;
  // Sets every cell of `box` that lies in the grid to `value`.
  void apply(OccupancyGrid& grid, const CellBox& box, Cell value) noexcept;
};

// Tells the cycle what changed since it last ran; nothing when nothing was written.
template <VehicleModel V>
void note_map_changes(ReplanningCycle<V>& cycle, const MapChanges& changes) noexcept {
  if (!changes.applied) return;
  cycle.note_newly_blocked(changes.newly_blocked);
  cycle.note_changed(changes.changed);
}

}  // namespace grip::rt
