#pragma once
// The planner participant's receive thread (participant_threads.hpp): waits on the readers of
// vehicle state, map updates, goals and the vehicle's description, validates every sample
// (link/messages.hpp), keeps the map in sync (link::MapReceiver, asking for snapshots after
// gaps), checks the vehicle's description (description_watch.hpp), watches the vehicle's
// liveliness and hands everything over to the planning thread (handoff.hpp). An ordinary
// thread: it may allocate, and a slow take delays nothing else.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "description_watch.hpp"
#include "goal.h"
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
  ReceiveSide(const V& vehicle, const VehicleParams& params, ReceiveEntities entities,
              Handoffs& handoffs, platform::Wakeup& lockstep_inputs, std::uint32_t max_map_cells,
              std::function<void(const std::string&)> warn);

  // The receive thread's body: until `stop_threads`. `stopping` (planning was told to stop)
  // makes a vehicle that leaves the end of the run rather than a loss.
  void run(const std::atomic<bool>& stop_threads, const std::atomic<bool>& stopping);

  // Any thread: the map's geometry, once the first valid update came (geometry() valid then).
  bool geometry_ready() const noexcept { return geometry_ready_.load(std::memory_order_acquire); }
  const link::MapGeometry& geometry() const noexcept { return geometry_; }
  const ReceiveCounters& counters() const noexcept { return counters_; }
  // Start-up: the planner cannot build its map from geometry() (`why`). Counted as a rejected
  // map update and said once; the planner keeps waiting rather than exiting.
  void refuse_geometry(const std::string& why);
  const VehicleClock& clock() const noexcept { return clock_; }
  const DescriptionWatch& description() const noexcept { return description_; }

 private:
  void take_states(platform::dds::SampleBuffer<grip_msg_VehicleState, 8>& buffer);
  void take_maps(platform::dds::SampleBuffer<grip_msg_MapUpdate, 8>& buffer);
  void take_goals(platform::dds::SampleBuffer<grip_msg_Goal, 4>& buffer);
  void take_descriptions(platform::dds::SampleBuffer<grip_msg_VehicleDescription, 2>& buffer);
  void accept_goal(const grip_msg_Goal& goal);
  void mark_dirty(const CellBox& box);
  void hand_over_tiles();
  void check_liveliness(bool stopping);
  void rejected(const char* topic, const link::Verdict& verdict, std::int64_t now_ns);
  void warn(const std::string& line) const;

  V vehicle_;
  ReceiveEntities dds_;
  Handoffs& handoffs_;
  platform::Wakeup& lockstep_inputs_;  // lockstep: a state or map tiles were handed over
  std::function<void(const std::string&)> warn_;
  link::MapReceiver receiver_;
  std::vector<CellBox> dirty_;  // per tile
  int tiles_x_ = 0;
  int tiles_y_ = 0;
  std::uint64_t last_state_stamp_ = 0;
  std::uint64_t last_state_sequence_ = 0;
  bool lockstep_seen_ = false;                 // the vehicle's states ask for lockstep
  std::optional<grip_msg_Goal> pending_goal_;  // arrived before the map: checked once it exists
  bool was_alive_ = false;
  std::int64_t last_log_ns_ = 0;  // one rejection line per second at most; the rest counted
  std::uint64_t log_suppressed_ = 0;
  std::unique_ptr<MapTile> handover_tile_ = std::make_unique<MapTile>();

  std::atomic<bool> geometry_ready_{false};
  link::MapGeometry geometry_;  // written once before geometry_ready_ (release)
  ReceiveCounters counters_;
  VehicleClock clock_;
  DescriptionWatch description_;
};

extern template class ReceiveSide<DdVelocity>;
extern template class ReceiveSide<DdAcceleration>;
extern template class ReceiveSide<Car>;

}  // namespace grip::rt::dds
