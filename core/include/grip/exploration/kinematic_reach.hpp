#pragma once
// Where a vehicle with a minimum turning radius (the car) can take its chassis on the known map,
// driving forward and in reverse: the frontier groups a point with the chassis' clearance could
// approach but the car cannot turn into (a side corridor too narrow to swing into, a door at
// the wrong angle) are recognised from it instead of chased until the give-up clock runs out.
//
// The search is Hybrid A*'s lattice (Dolgov et al. 2008) without a goal: states are (cell,
// heading bin), a move from a state drives one heading bin's arc at the turning radius left or
// right, or straight as far, forward or in reverse, and ends at the nearest cell centre. A move
// is taken when the exact chassis (no margin: the vehicle at rest) is free at every half cell
// along it. Cells the reference point passes are marked passed(): that is what a frontier
// group's approach is tested against.
//
// The search is kept between updates and grows with the map. Known free space only grows in a
// static world, and a car that can reverse can drive any of its moves backwards, so the states
// reachable from where the vehicle stands now are those reachable from where it stood before:
// after a change, only states near the cells that changed whose moves were blocked where unknown
// cells lay are expanded again. A sensor that turns a free cell into an obstacle leaves passed()
// too generous, which errs toward "reachable" (the give-up clock still applies).
//
// Each update() expands at most max_expansions states: complete() says whether the search has
// run out of states to expand, and only then does a group out of passed()'s reach count as
// unreachable.
//
// Memory, fixed by create(): 6 bytes per cell (visited, blocked and pending bits for 16 heading
// bins), a bit per cell for passed(), the collision checker's clearance map and bit grids, and a
// queue of at most 2^20 states (a state that does not fit stays pending and is found again by a
// scan). update() never allocates and never throws.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/collision_checker.hpp"
#include "grip/world/footprint.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip {

struct KinematicReachConfig {
  double turning_radius_m = 0.0;  // > 0: the rear axle's circle at full lock
  Footprint footprint{0.0, 0.0, 0.0};
  std::uint32_t max_expansions = 50'000;  // states expanded per update() at most
  // Errors name the bad value: turning_radius_m not finite or not > 0, a footprint the collision
  // checker refuses, max_expansions 0.
  Status validate() const;
};

class KinematicReach {
 public:
  static constexpr int kHeadingBins = 16;

  // For `grid`, which must outlive the object at the same address and be the one every
  // update() is given. Errors as for validate() and CollisionChecker::create.
  static Result<KinematicReach> create(const OccupancyGrid& grid,
                                       const KinematicReachConfig& config);

  // The grid changed between free and not free within `changed` since the last update (the
  // cells of the whole grid on the first). Then goes on searching from the states found so far
  // and from the vehicle's pose (x_m, y_m, theta), which is reachable whatever the search says.
  void update(const CellBox& changed, double x_m, double y_m, double theta) noexcept;

  // No state is left to expand: passed() holds every cell the search can reach.
  bool complete() const noexcept { return ring_size_ == 0 && !overflow_; }
  // A bit per cell, row-major (cell c is bit c & 63 of word c >> 6): the reference point of a
  // reachable state has passed through it.
  std::span<const std::uint64_t> passed() const noexcept { return passed_; }
  bool passed(std::uint32_t cell) const noexcept;
  std::uint64_t states_reached() const noexcept { return states_reached_; }

 private:
  // One move from a state of some heading bin, relative to the cell it starts in.
  struct Move {
    int end_dx = 0;  // [cells] the cell it ends in
    int end_dy = 0;
    int end_bin = 0;
    int samples = 0;
    // Poses checked along it (the last is the end pose, before rounding to a cell centre).
    static constexpr int kMaxSamples = 32;
    std::array<double, kMaxSamples> dx_m{};
    std::array<double, kMaxSamples> dy_m{};
    std::array<double, kMaxSamples> theta{};
  };
  static constexpr int kMovesPerBin = 6;  // forward and reverse, each left, straight, right

  KinematicReach(const OccupancyGrid& grid, const KinematicReachConfig& config,
                 CollisionChecker checker);
  void build_moves() noexcept;
  void seed(std::uint32_t cell, int bin) noexcept;
  void schedule(std::uint32_t cell, std::uint16_t bins) noexcept;
  void expand(std::uint32_t cell, int bin) noexcept;
  void mark_passed(int cx, int cy) noexcept;
  bool unknown_near(double x_m, double y_m) const noexcept;
  bool pop(std::uint32_t& state) noexcept;
  void refill_from_pending() noexcept;

  const OccupancyGrid* grid_;
  KinematicReachConfig config_;
  CollisionChecker checker_;
  int reach_cells_ = 0;  // how far from its start cell a move's chassis reaches
  std::vector<Move> moves_;
  std::vector<std::uint16_t> visited_;  // per cell, a bit per heading bin
  std::vector<std::uint16_t> blocked_;  // per cell: a move was blocked where unknown cells lay
  std::vector<std::uint16_t> pending_;  // per cell: the state is to be expanded
  std::vector<std::uint64_t> passed_;
  std::vector<std::uint32_t> ring_;  // states (cell * kHeadingBins + bin) to expand
  std::size_t ring_head_ = 0;
  std::size_t ring_size_ = 0;
  bool overflow_ = false;  // pending states not in the ring
  std::uint64_t states_reached_ = 0;
};

}  // namespace grip
