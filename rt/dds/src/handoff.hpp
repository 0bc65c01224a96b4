#pragma once
// What crosses between the planner participant's threads (participant_threads.hpp), all through
// bounded, lock-free hand-offs:
//   receive -> planning: map tiles (SpscRing: every tile applied, in order), the vehicle's
//     states and goals (TripleBuffer: the latest wins);
//   planning -> publish: the cycle's plan and status (TripleBuffer: a plan not yet written when
//     the next one comes is superseded), the publish thread's timing back to the report.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "grip/rt/latency_histogram.hpp"
#include "grip/rt/replanning_session.hpp"
#include "grip/rt/spsc_ring.hpp"
#include "grip/rt/triple_buffer.hpp"
#include "plan.h"

namespace grip::rt::dds {

// Map tiles of 128 x 128 cells: a sensor sweep's change is one or a few tiles, and a 300 x 300
// map's first sync is nine.
inline constexpr int kTileSide = 128;
inline constexpr std::size_t kTileRing = 32;

struct MapTile {
  CellBox box;                            // inside the map, at most kTileSide on a side
  std::uint64_t map_sequence = 0;         // the receiver's last applied update when cut
  bool in_sync = false;                   // the receiver's map was in sync when cut
  std::uint64_t vehicle_incarnation = 0;  // the mapping side's incarnation: another is not ours
  bool last_of_batch = false;             // no other tile was pending when this one was cut
  std::array<Cell, static_cast<std::size_t>(kTileSide) * kTileSide> cells{};
};

struct PlanSlot {
  std::uint64_t cycle = 0;
  std::uint64_t start_time_ns = 0;
  std::array<double, 5> start_state{};
  std::uint32_t state_dim = 0;
  std::uint64_t state_sequence = 0;
  std::uint64_t committed_monotonic_ns = 0;
  std::uint64_t vehicle_incarnation = 0;  // the vehicle planned for
  std::uint32_t steps = 0;
  std::array<grip_msg_PlanStep, grip_msg_kMaxPlanSteps> step{};
};

struct CycleStatus {
  std::uint64_t cycle = 0;
  bool exploring = false;
  bool exploration_complete = false;
  std::uint32_t frontier_groups = 0;
  std::uint32_t frontier_groups_given_up = 0;
  std::uint32_t frontier_groups_unreachable = 0;
  double target_x_m = 0.0;
  double target_y_m = 0.0;
  std::uint64_t misses = 0;
  std::uint64_t tree_edges = 0;
  std::uint64_t edges_added = 0;
  double cycle_time_s = 0.0;
  std::uint64_t map_sequence = 0;
  std::uint64_t map_checksum = 0;
  bool map_in_sync = false;
  std::uint64_t vehicle_incarnation = 0;  // the vehicle planned for
};

// The publish thread's record of the plans' way out (PlannerParticipantReport::plan_handoff).
struct PublishTiming {
  LatencyHistogram handoff;
  LatencyHistogram write;
};

// Every hand-off of one participant, allocated once at creation.
struct Handoffs {
  std::unique_ptr<SpscRing<MapTile, kTileRing>> tiles =
      std::make_unique<SpscRing<MapTile, kTileRing>>();
  std::unique_ptr<TripleBuffer<VehicleSample>> states =
      std::make_unique<TripleBuffer<VehicleSample>>();
  // Disk goals only (link::goal_from_wire): a cells Goal views memory of the thread that made
  // it, so it must not cross to the planning thread.
  std::unique_ptr<TripleBuffer<Goal>> goals = std::make_unique<TripleBuffer<Goal>>();
  std::unique_ptr<TripleBuffer<PlanSlot>> plans = std::make_unique<TripleBuffer<PlanSlot>>();
  std::unique_ptr<TripleBuffer<CycleStatus>> statuses =
      std::make_unique<TripleBuffer<CycleStatus>>();
  std::unique_ptr<TripleBuffer<PublishTiming>> publish_timing =
      std::make_unique<TripleBuffer<PublishTiming>>();
  // Set by the planning thread once a plan's end is settled, before it extracts the plan: the
  // publish thread wakes meanwhile and is running when the plan is handed over.
  std::atomic<bool> plan_coming{false};
  // Set by the receive thread when a lockstep vehicle repeats the state of this sequence number
  // (0: none): it still waits for its plan. The publish thread writes the last plan again if that
  // plan answered it: a plan written before the vehicle's reader matched (a secured handshake
  // completes per endpoint), or lost while the vehicle's participant was rediscovered, is
  // otherwise never seen, and the lockstep run stands still.
  std::atomic<std::uint64_t> plan_wanted_for{0};
};

}  // namespace grip::rt::dds
