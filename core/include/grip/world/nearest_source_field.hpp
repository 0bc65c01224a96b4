#pragma once
// The geodesic Voronoi diagram of a growing set of source cells: for every cell, the nearest
// source under the same 8-connected metric as a DistanceField (same costs, corner rule and
// traversable cells). Adding a source runs a decrease-only Dijkstra from it, touching only the
// cells it now reaches first, so growing the set costs in total about one wavefront, and a
// query is O(1). The RRT baselines use it for "the tree state nearest to a sample under rho_A*".
//
// Memory is reserved by create(); reset() and add_source() never allocate.

#include <cstdint>
#include <memory>

#include "grip/common/result.hpp"
#include "grip/memory/indexed_min_heap.hpp"
#include "grip/world/distance_field.hpp"

namespace grip {

class NearestSourceField {
 public:
  static constexpr std::uint32_t kNoCell = DistanceField::kNoCell;

  static Result<NearestSourceField> create(int width_cells, int height_cells);

  // Removes every source.
  void reset() noexcept;
  // Makes `cell` a source if it is traversable in `metric` (whose last compute()/prepare()
  // decides); other cells are ignored. Every call of
  // one field must pass the same metric, of the field's size.
  void add_source(const DistanceField& metric, std::uint32_t cell) noexcept;
  // The source nearest to `cell`, or kNoCell when none reaches it.
  std::uint32_t nearest_source(std::uint32_t cell) const noexcept { return source_[cell]; }
  // Path length to it in cost units (DistanceField's), DistanceField::kUnreachable if none.
  std::uint32_t cost_to_source(std::uint32_t cell) const noexcept { return cost_[cell]; }

 private:
  NearestSourceField(int width_cells, int height_cells);

  int width_;
  int height_;
  std::unique_ptr<std::uint32_t[]> cost_;
  std::unique_ptr<std::uint32_t[]> source_;
  IndexedMinHeap open_;
};

}  // namespace grip
