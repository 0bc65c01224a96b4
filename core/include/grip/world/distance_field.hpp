#pragma once
// The holonomic distance field behind the planner's metric rho_A* (the paper's Sec. III-B): one
// Dijkstra wavefront from a target set over the grid, then O(1) lookups of the shortest
// 8-connected path length from any cell to the nearest target.
//
// Costs are integers in units of resolution / 70: 70 for an orthogonal step, 99 for a diagonal
// one (99 / 70 = 1.414..., sqrt 2 to 0.01 %). A diagonal step must not cut a corner: both
// orthogonal cells beside it must be traversable. Traversable cells are kFree cells whose
// clearance (world/clearance_map.hpp, the same lower bound the collision checker uses) is at
// least inflation_m; inflation_m = 0 makes every free cell traversable. A path may start at a
// target that is not traversable (targets are always seeds) but never enters a non-traversable
// cell otherwise.
//
// Queue: Dial's algorithm, a cyclic bucket queue (a power of two of buckets above the largest
// edge cost: 128) threaded through per-cell next/prev arrays; O(cells reached) per wavefront,
// plus the box the previous one reached (cleared). The traversable set is rebuilt in O(cells), or
// within the window of a change (the windowed prepare()). All buffers are allocated
// by create(); compute() and the lookups never allocate and never throw.
//
// Blocks: a field may run its wavefront over blocks of b x b grid cells (create's `block`;
// block_for() picks b), so that it costs on a fine map what it costs on a coarse one of the same
// size in metres. A block is traversable when one of its cells is, and a step between blocks
// costs b grid cells' worth (70 b, 99 b). The interface stays the grid's: cells, indices and
// costs are the grid's, and every cell of a block reads the block's value. With b x resolution
// at most half the inflation, two traversable cells in neighbouring blocks lie less than the
// inflation apart, so the segment between them is free: a step between blocks never crosses a
// wall (it may pass a gap a little narrower than one the cells pass), and every path of
// traversable cells is a path of blocks.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "grip/common/assert.hpp"
#include "grip/common/result.hpp"
#include "grip/world/clearance_map.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

namespace detail {
// Where a resumable Dial search stands (distance_field.cpp): the cells queued, and the cost and
// bucket its scan of the buckets has reached.
struct DialQueue {
  std::uint32_t queued = 0;
  std::uint32_t cost = 0;
  std::uint32_t bucket = 0;
};
}  // namespace detail

class DistanceField {
 public:
  static constexpr std::uint32_t kOrthogonalCost = 70;
  static constexpr std::uint32_t kDiagonalCost = 99;
  static constexpr std::uint32_t kCostUnitsPerCell = kOrthogonalCost;
  static constexpr std::uint32_t kUnreachable = std::numeric_limits<std::uint32_t>::max();
  static constexpr std::uint32_t kNoCell = std::numeric_limits<std::uint32_t>::max();
  // The largest block: the bucket queue holds a power of two above a diagonal step (99 b).
  static constexpr int kMaxBlock = 1024;

  // Allocates every buffer for grids of exactly this size and resolution, the wavefront over
  // blocks of block x block of their cells (1: the cells themselves); errors as for
  // OccupancyGrid::create, and for a block outside [1, kMaxBlock].
  static Result<DistanceField> create(int width_cells, int height_cells, double resolution_m,
                                      int block = 1);
  // The block for a field on a grid of resolution_m with this inflation: the largest whose side
  // is at most max_cell_m and half the inflation, and at most kMaxBlock (1 when none is:
  // inflation 0, or cells already that large).
  static int block_for(double resolution_m, double max_cell_m, double inflation_m) noexcept;

  // Builds the traversable set from the grid, every free cell traversable (no inflation), and
  // runs the wavefront from target_cells (grid indices). Returns the number of reachable
  // cells (with blocks: blocks), targets included; 0 for an empty target set (everything then reads
  // unreachable). Asserts: the grid's size and resolution match create(), every target <
  // cell_count().
  std::uint32_t compute(const OccupancyGrid& grid,
                        std::span<const std::uint32_t> target_cells) noexcept;
  // Same with an inflation: the clearance map is computed from this grid at its current revision
  // (asserted), e.g. CollisionChecker::clearance() after refresh(); it is not the field's own,
  // so that the fields and checkers of one map share one (a map's worth of memory each).
  // Asserts inflation_m finite and >= 0.
  std::uint32_t compute(const OccupancyGrid& grid, const ClearanceMap& clearance,
                        std::span<const std::uint32_t> target_cells, double inflation_m) noexcept;

  // The two halves of compute(): prepare() fixes the traversable set (and the grid origin used
  // by distance_m) without touching the distances; propagate() runs the wavefront over it.
  void prepare(const OccupancyGrid& grid) noexcept;
  void prepare(const OccupancyGrid& grid, const ClearanceMap& clearance,
               double inflation_m) noexcept;
  // The same after a change confined to `window` since this field's last prepare() from this
  // grid (asserted: mask_source()) with this inflation: no cell outside it changed
  // traversability (with inflation: the windows ClearanceMap::update rewrote since). Rebuilds the
  // set there only.
  void prepare(const OccupancyGrid& grid, const ClearanceMap& clearance, double inflation_m,
               const CellBox& window) noexcept;
  // The wavefront, to the end; returns the number of cells (with blocks: blocks) it reached,
  // targets included.
  std::uint32_t propagate(std::span<const std::uint32_t> target_cells) noexcept;
  // The wavefront in steps, for a caller that needs only the cells up to some cost and does not
  // know that cost in advance (FrontierMap: the frontier nearest by score): start() seeds it
  // (the last one's labels cleared), settle(limit) runs it until every cell of cost <= limit is
  // settled and may be called again with a larger limit to go on; true once it has run to the
  // end. Labels up to settled_limit() are final; a cell labelled above it is reachable at most
  // at that cost (it is queued), and a cell not labelled yet reads kUnreachable.
  void start(std::span<const std::uint32_t> target_cells) noexcept;
  bool settle(std::uint32_t cost_limit) noexcept;
  // kUnreachable once the wavefront has run to the end (every label final).
  std::uint32_t settled_limit() const noexcept { return settled_limit_; }
  // The wavefront out to cost_limit only, for a caller that asks for costs near the targets and
  // needs only to know that the others are larger (ExplorationTarget: rho toward a target, read
  // by a tree around a vehicle whose own rho is known). Every traversable cell it did not settle
  // then reads cost_limit + 1 (a lower bound of its cost, the same for all of them; one cut off
  // from the targets too), every other as compute() would; a wavefront that ends within the
  // limit is exact. Returns the cells (blocks) settled, as propagate() does. The next start()
  // (or propagate()) reads exact costs again.
  std::uint32_t propagate_within(std::span<const std::uint32_t> target_cells,
                                 std::uint32_t cost_limit) noexcept;
  // What cells beyond the last propagate_within() read (kUnreachable: every cost is exact).
  std::uint32_t beyond_cost() const noexcept {
    return read_limit_ == kUnreachable ? kUnreachable : read_limit_ + 1;
  }

  // [m] path length from the cell containing (x_m, y_m) to the nearest target; +infinity when
  // unreachable, outside the grid or not finite. O(1).
  double distance_m(double x_m, double y_m) const noexcept;
  // [m] the same by grid index; asserts cell_index < cell_count().
  double at(std::uint32_t cell_index) const noexcept;
  // The same in cost units (resolution / 70), kUnreachable when unreachable.
  std::uint32_t cost_at(std::uint32_t cell_index) const noexcept {
    GRIP_ASSERT(cell_index < cell_count());
    return read(padded(cell_index));
  }
  bool reachable(std::uint32_t cell_index) const noexcept {
    return cost_at(cell_index) != kUnreachable;
  }
  // The cell a shortest path from `cell_index` to the target set reaches once its cost has
  // dropped by at least `cost_drop` (cost units), or the target it ends at when it is shorter:
  // steepest descent, each step to the neighbour with the least cost plus step (with blocks:
  // from block to block, ending at the centre cell of the last). `cell_index` itself when it is
  // unreachable or no step is taken; from beyond propagate_within()'s limit, itself or a cell
  // within it. O(steps); asserts cell_index < cell_count().
  std::uint32_t descend(std::uint32_t cell_index, std::uint32_t cost_drop) const noexcept;
  // The cell containing (x_m, y_m), or kNoCell outside the grid or not finite.
  std::uint32_t cell_at(double x_m, double y_m) const noexcept;

  // Whether the last prepare()/compute() made this cell traversable.
  bool traversable(std::uint32_t cell_index) const noexcept;

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  double resolution() const noexcept { return resolution_; }
  // Grid cells per side of the wavefront's blocks.
  int block() const noexcept { return block_; }
  // The grid's origin [m] as of the last prepare()/compute() (its cell (0, 0)'s lower corner).
  double origin_x_m() const noexcept { return origin_x_m_; }
  double origin_y_m() const noexcept { return origin_y_m_; }
  std::uint32_t cell_count() const noexcept {
    return static_cast<std::uint32_t>(width_) * static_cast<std::uint32_t>(height_);
  }
  // The inflation and grid revision of the last prepare()/compute().
  double inflation() const noexcept { return inflation_m_; }
  std::uint64_t source_revision() const noexcept { return source_revision_; }
  // The grid the traversable set was last built from (nullptr before), and a tag of the
  // caller's that moves with the field: a caller that hands fields to another and gets others
  // back (Planner::adopt_goal) tells its own, and what they were built from, apart.
  const OccupancyGrid* mask_source() const noexcept { return mask_source_; }
  std::uint32_t tag() const noexcept { return tag_; }
  void set_tag(std::uint32_t tag) noexcept { tag_ = tag; }

 private:
  static constexpr std::uint32_t kNil = std::numeric_limits<std::uint32_t>::max();

  // Dijkstra's queue and labels over the padded blocks (a ring of never-traversable blocks
  // around the real ones, so neighbours need no bounds tests); buckets: the power of two above
  // the largest step (99 b).
  struct Search {
    std::vector<std::uint32_t> cost;
    std::vector<std::uint32_t> next;
    std::vector<std::uint32_t> prev;
    std::vector<std::uint32_t> head;
    detail::DialQueue queue;
  };

  DistanceField(int width_cells, int height_cells, double resolution_m, int block);
  void build_mask(const OccupancyGrid& grid, const ClearanceMap* clearance, double inflation_m,
                  const CellBox& window) noexcept;
  CellBox whole() const noexcept { return CellBox{0, 0, width_ - 1, height_ - 1}; }
  void note_reached(std::uint32_t padded_index) noexcept;
  // The padded block holding a cell, and a block's cell (its centre one, within the grid).
  std::uint32_t padded(std::uint32_t cell_index) const noexcept {
    const auto w = static_cast<std::uint32_t>(width_);
    return padded(cell_index % w, cell_index / w);
  }
  std::uint32_t padded(std::uint32_t x, std::uint32_t y) const noexcept {
    if (block_ != 1) {  // a division on every lookup only where there are blocks
      x /= static_cast<std::uint32_t>(block_);
      y /= static_cast<std::uint32_t>(block_);
    }
    return (y + 1) * padded_width_ + x + 1;
  }
  std::uint32_t unpadded(std::uint32_t padded_index) const noexcept;
  // A padded block's cost as the lookups read it (see propagate_within()).
  std::uint32_t read(std::uint32_t padded_index) const noexcept {
    const std::uint32_t cost = field_.cost[padded_index];
    if (cost <= read_limit_) return cost;  // always, unless the wavefront was cut off
    return traversable_[padded_index] != 0 ? read_limit_ + 1 : kUnreachable;
  }

  int width_;
  int height_;
  double resolution_;
  double inv_resolution_;
  double metres_per_unit_;
  int block_;
  std::uint32_t orthogonal_cost_;  // of a step between blocks: 70 b, 99 b
  std::uint32_t diagonal_cost_;
  std::uint32_t padded_width_;
  double origin_x_m_ = 0.0;
  double origin_y_m_ = 0.0;
  double inflation_m_ = 0.0;
  std::uint64_t source_revision_ = 0;
  std::vector<std::uint8_t> traversable_;       // padded
  const OccupancyGrid* mask_source_ = nullptr;  // traversable_ built from it, whole first
  std::uint32_t tag_ = 0;
  // The padded columns and rows of the blocks the last wavefront settled, and of its seeds
  // (empty: x0 > x1).
  struct ReachedBox {
    std::uint32_t x0 = kNil;
    std::uint32_t x1 = 0;
    std::uint32_t y0 = kNil;
    std::uint32_t y1 = 0;
  };
  ReachedBox reached_;
  std::uint32_t settled_ = 0;  // blocks the wavefront has settled
  std::uint32_t settled_limit_ = kUnreachable;
  std::uint32_t read_limit_ = kUnreachable;  // propagate_within()'s limit; else every cost reads
  Search field_;                             // the wavefront's labels are the field
};

}  // namespace grip
