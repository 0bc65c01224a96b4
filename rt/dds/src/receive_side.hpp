#pragma once
// The planner participant's receive thread (participant_threads.hpp): waits on the readers of
// vehicle state, map updates, goals and the vehicle's description, validates every sample
// (link/messages.hpp), keeps the map in sync (link::MapReceiver, asking for snapshots after
// gaps), checks the vehicle's description (description_watch.hpp), watches the vehicle's
// liveliness and hands everything over to the planning thread (handoff.hpp). An ordinary
// thread: it may allocate, and a slow take delays nothing else.
//
// It follows one vehicle incarnation (link/incarnation.hpp): samples of another are rejected
// while the one followed speaks; once it has been silent for one liveliness lease, the next
// one is taken, and everything learned from the old one is forgotten: stamps, the map and its
// geometry, the clock and time scale, lockstep mode. The run loop then starts planning anew.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "description_watch.hpp"
#include "goal.h"
#include "grip/link/incarnation.hpp"
#include "grip/link/map_sync.hpp"
#include "grip/link/messages.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/waitset.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/platform/wakeup.hpp"
#include "grip/rt/vehicle_clock.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "handoff.hpp"
#include "map_update.h"
#include "vehicle_state.h"

namespace grip::rt::dds {

// What the receive thread counts, read by the others.
struct ReceiveCounters {
  std::atomic<std::uint64_t> rejected_vehicle_state{0};
  std::atomic<std::uint64_t> rejected_map_update{0};
  std::atomic<std::uint64_t> rejected_goal{0};
  std::atomic<std::uint64_t> map_gaps{0};
  std::atomic<std::uint64_t> map_heals{0};
  std::atomic<std::uint64_t> vehicle_losses{0};
  std::atomic<bool> vehicle_alive{false};
  // The vehicle incarnation followed (0: none yet), and how often a new one replaced it.
  std::atomic<std::uint64_t> vehicle_incarnation{0};
  std::atomic<std::uint64_t> vehicle_restarts{0};
};

// The entities the receive thread reads from and writes map requests with.
struct ReceiveEntities {
  platform::dds::Reader<grip_msg_VehicleState>& states;
  platform::dds::Reader<grip_msg_MapUpdate>& maps;
  platform::dds::Reader<grip_msg_Goal>& goals;
  platform::dds::Reader<grip_msg_VehicleDescription>& descriptions;
  platform::dds::Writer<grip_msg_MapRequest>& requests;
  platform::dds::WaitSet& waitset;
};

template <VehicleModel V>
class ReceiveSide {
 public:
  // `params` are the planner's own, which `vehicle` was built from: descriptions are checked
  // against them. `warn` takes each warning line (no trailing newline); unset, to stderr.
  // `takeover_ns`: a new vehicle incarnation is taken once the one followed has been silent
  // this long (the liveliness lease).
  ReceiveSide(const V& vehicle, const VehicleParams& params, ReceiveEntities entities,
              Handoffs& handoffs, platform::Wakeup& lockstep_inputs, std::uint32_t max_map_cells,
              std::int64_t takeover_ns, std::uint64_t planner_incarnation,
              std::function<void(const std::string&)> warn);

  // The receive thread's body: until `stop_threads`. `stopping` (planning was told to stop)
  // makes a vehicle that leaves the end of the run rather than a loss.
  void run(const std::atomic<bool>& stop_threads, const std::atomic<bool>& stopping);

  // Any thread: the map's geometry, once the first valid update came (geometry() valid then).
  bool geometry_ready() const noexcept { return geometry_ready_.load(std::memory_order_acquire); }
  link::MapGeometry geometry() const {
    const std::lock_guard<std::mutex> lock(geometry_mutex_);
    return geometry_;
  }
  // run()'s thread, start-up: the planner cannot plan on `geometry` (its planner refused it).
  // Updates with it are rejected and counted from now on, and the map is forgotten.
  void refuse_geometry(const link::MapGeometry& geometry);
  // run()'s thread: a new planning side replaces the one the tiles went to (a new vehicle):
  // the whole map is handed over again, or it would wait for tiles its predecessor consumed.
  void hand_over_map_again() { hand_over_again_.store(true, std::memory_order_release); }
  const ReceiveCounters& counters() const noexcept { return counters_; }
  const VehicleClock& clock() const noexcept { return clock_; }
  const DescriptionWatch& description() const noexcept { return description_; }

 private:
  void take_states(platform::dds::SampleBuffer<grip_msg_VehicleState, 8>& buffer);
  void hand_over_state(const grip_msg_VehicleState& msg);  // to the planning thread
  void take_maps(platform::dds::SampleBuffer<grip_msg_MapUpdate, 8>& buffer);
  void take_goals(platform::dds::SampleBuffer<grip_msg_Goal, 4>& buffer);
  void take_descriptions(platform::dds::SampleBuffer<grip_msg_VehicleDescription, 2>& buffer);
  void accept_goal(const grip_msg_Goal& goal);
  void mark_dirty(const CellBox& box);
  void hand_over_tiles();
  void check_liveliness(bool stopping);
  void rejected(const char* topic, const link::Verdict& verdict, std::int64_t now_ns);
  void too_large(const grip_msg_MapUpdate& msg);
  // Whether a sample of `incarnation` is from the vehicle followed (taking a new one over, and
  // forgetting the old one's, when it is due); else the reason to reject it.
  link::Verdict follow(std::uint64_t incarnation, std::int64_t now_ns);
  void forget_map();
  bool refused(const link::MapGeometry& geometry) const {
    const std::lock_guard<std::mutex> lock(geometry_mutex_);
    return refused_geometry_ && *refused_geometry_ == geometry;
  }
  void warn(const std::string& line) const;

  V vehicle_;
  ReceiveEntities dds_;
  Handoffs& handoffs_;
  platform::Wakeup& lockstep_inputs_;  // lockstep: a state or map tiles were handed over
  std::function<void(const std::string&)> warn_;
  std::uint32_t max_map_cells_;
  link::MapReceiver receiver_;
  std::vector<CellBox> dirty_;  // per tile
  int tiles_x_ = 0;
  int tiles_y_ = 0;
  link::IncarnationTracker vehicle_incarnation_;
  std::uint64_t planner_incarnation_;  // this planner's, as the vehicle names the one it follows
  std::uint64_t last_state_stamp_ = 0;
  std::uint64_t last_state_sequence_ = 0;
  std::int64_t last_state_local_ns_ = 0;       // when the last state was accepted
  bool lockstep_seen_ = false;                 // the vehicle's states ask for lockstep
  std::optional<grip_msg_Goal> pending_goal_;  // arrived before the map: checked once it exists
  bool was_alive_ = false;
  std::int64_t last_log_ns_ = 0;  // one rejection line per second at most; the rest counted
  std::uint64_t log_suppressed_ = 0;
  std::unique_ptr<MapTile> handover_tile_ = std::make_unique<MapTile>();

  std::atomic<bool> geometry_ready_{false};
  mutable std::mutex geometry_mutex_;  // run()'s thread reads the geometry at start-up
  link::MapGeometry geometry_;
  std::optional<link::MapGeometry> refused_geometry_;  // under geometry_mutex_
  std::optional<link::MapGeometry> too_large_reported_;
  std::atomic<bool> forget_map_{false};
  std::atomic<bool> hand_over_again_{false};
  ReceiveCounters counters_;
  VehicleClock clock_;
  DescriptionWatch description_;
};

extern template class ReceiveSide<DdVelocity>;
extern template class ReceiveSide<DdAcceleration>;
extern template class ReceiveSide<Car>;

}  // namespace grip::rt::dds
