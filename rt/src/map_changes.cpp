#include "grip/rt/map_changes.hpp"

#include <algorithm>
#include <cstddef>

#include "grip/common/assert.hpp"

namespace grip::rt {

namespace {

// One write of a whole box: the grid's revision moves once, as for any mapper's write.
template <typename ValueAt>
void write_box(OccupancyGrid& grid, const CellBox& box, ValueAt value_at, MapChanges& changes) {
  auto cells = grid.mutable_cells();
  for (int y = box.y0; y <= box.y1; ++y) {
    for (int x = box.x0; x <= box.x1; ++x) {
      const Cell value = value_at(x, y);
      Cell& cell = cells[grid.index(x, y)];
      if ((cell == Cell::kFree) != (value == Cell::kFree)) {
        changes.changed.add(CellBox{x, y, x, y});
        if (cell == Cell::kFree) changes.newly_blocked.add(CellBox{x, y, x, y});
      }
      cell = value;
    }
  }
  changes.applied = true;
  changes.written.add(box);
}

}  // namespace

void MapChanges::apply(OccupancyGrid& grid, const CellBox& box,
                       std::span<const Cell> cells) noexcept {
  GRIP_ASSERT(!box.empty() && box.x0 >= 0 && box.y0 >= 0 && box.x1 < grid.width() &&
              box.y1 < grid.height());
  const int w = box.x1 - box.x0 + 1;
  GRIP_ASSERT(cells.size() ==
              static_cast<std::size_t>(w) * static_cast<std::size_t>(box.y1 - box.y0 + 1));
  write_box(
      grid, box,
      [&](int x, int y) {
        return cells[static_cast<std::size_t>((y - box.y0) * w + (x - box.x0))];
      },
      *this);
}

void MapChanges::apply(OccupancyGrid& grid, const CellBox& box, Cell value) noexcept {
  const CellBox inside{std::max(box.x0, 0), std::max(box.y0, 0), std::min(box.x1, grid.width() - 1),
                       std::min(box.y1, grid.height() - 1)};
  if (inside.empty()) return;
  write_box(
      grid, inside, [value](int, int) { return value; }, *this);
}

}  // namespace grip::rt
