#pragma once
// The target set F of the paper's Sec. II, as a caller states it: a disk of the workspace (the
// reference point within a radius of a point) or a set of grid cells (e.g. the approach cells of
// a frontier group, exploration/frontier.hpp). A small value type; the planner turns it into
// its own bounded copy (TargetSet) when it takes it.

#include <cstdint>
#include <span>

#include "grip/common/assert.hpp"

namespace grip {

class Goal {
 public:
  // A disk of radius 1 m at the origin, so that a Goal can fill a preallocated buffer slot.
  Goal() noexcept = default;

  // The reference point within radius_m of (x_m, y_m).
  static Goal disk(double x_m, double y_m, double radius_m) noexcept {
    Goal g;
    g.x_m_ = x_m;
    g.y_m_ = y_m;
    g.radius_m_ = radius_m;
    return g;
  }
  // The reference point in one of `cells` (indices cell_y * width + cell_x); cells that are not
  // free are ignored. The Goal only views the span: it is valid while the caller's cells are,
  // and whoever takes it (Planner, ReplanningCycle) copies the cells during that call. So a
  // cells goal must not cross threads.
  static Goal cells(std::span<const std::uint32_t> cells) noexcept {
    Goal g;
    g.is_disk_ = false;
    g.cells_ = cells;
    return g;
  }

  bool is_disk() const noexcept { return is_disk_; }
  // The disk's centre and radius [m]; a cells goal has none (asserted).
  double x_m() const noexcept { return disk_part(x_m_); }
  double y_m() const noexcept { return disk_part(y_m_); }
  double radius_m() const noexcept { return disk_part(radius_m_); }
  // Whether (x, y) [m] lies in the disk; for a cells goal, ask the planner's TargetSet.
  bool contains(double x, double y) const noexcept {
    GRIP_ASSERT(is_disk_);
    const double dx = x - x_m_;
    const double dy = y - y_m_;
    return dx * dx + dy * dy <= radius_m_ * radius_m_;
  }
  // The cells of a cells goal; empty for a disk.
  std::span<const std::uint32_t> cells() const noexcept { return cells_; }

 private:
  double disk_part(double value) const noexcept {
    GRIP_ASSERT(is_disk_);
    return value;
  }

  bool is_disk_ = true;
  double x_m_ = 0.0;
  double y_m_ = 0.0;
  double radius_m_ = 1.0;
  std::span<const std::uint32_t> cells_;
};

}  // namespace grip
