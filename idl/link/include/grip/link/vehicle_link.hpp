#pragma once
// The vehicle controller's end of the contract (the simulator stands in for it; tests and tools
// use it too): describes the vehicle once, at creation (durable, for planners that start later);
// publishes vehicle state, map updates (answering the planner's map requests with snapshots) and
// goals; receives plans, validated, and the planner's status. Ordinary threads
// only: a writer here may block up to its QoS max_blocking_time.
//
// One plan source (idl/README.md): the link has an incarnation of its own, stamped on every
// state and map update, and follows one planner incarnation: the first that sends a plan, and
// another only once the one followed has sent nothing for one liveliness lease and DDS reports
// its plan writer lost (stopped, killed, cut off: failover to a standby), or has sent nothing for
// kHungLeases leases while alive (hung). A planner that is merely slow keeps the vehicle. Plans of
// any other planner, and plans made for an earlier incarnation of this vehicle, are rejected,
// counted and reported (the first of each kind as a warning).

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "goal.h"
#include "grip/common/result.hpp"
#include "grip/link/incarnation.hpp"
#include "grip/link/map_sync.hpp"
#include "grip/link/topics.hpp"
#include "grip/link/vehicle_description.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/waitset.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/platform/dds/writer_liveliness.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "map_update.h"
#include "plan.h"
#include "planner_status.h"
#include "vehicle_state.h"

namespace grip::link {

// How many liveliness leases a planner DDS still holds alive may stay silent before another is
// followed: long enough that a loaded machine's slow cycle is not a failover.
inline constexpr std::int64_t kHungLeases = 4;

struct VehicleLinkConfig {
  platform::dds::DomainId domain = 0;
  std::string dds_config;  // empty: the built-in loopback-only configuration
  std::optional<platform::dds::SecurityFiles> security;  // DDS Security; none: unauthenticated
  std::string topic_prefix;  // empty: the topics' own names (topics.hpp)
  // The vehicle: described once at creation (vehicle_description.hpp); plans of another kind
  // are rejected.
  VehicleParams vehicle = CarParams{};
  LinkTiming timing;
  // Warnings (a second plan source, plans for an earlier incarnation), one line each without a
  // trailing newline. Unset: printed to stderr.
  std::function<void(const std::string&)> on_warning;
};

class VehicleLink {
 public:
  // `map` is the mapping side's authoritative map (the sensed map, in the simulator). Refuses
  // a vehicle validate() refuses and a bad topic prefix (kInvalidArgument).
  static Result<std::unique_ptr<VehicleLink>> create(const VehicleLinkConfig& config,
                                                     OccupancyGrid map);

  Status publish_state(const grip_msg_VehicleState& state);
  Status publish_goal(const grip_msg_Goal& goal);
  // Sends the cells of `box` of map() as updates. `drop` (tests: a lossy link) decides for each
  // update whether it is withheld; a withheld update still consumes its sequence number.
  void publish_map_updates(const CellBox& box, std::uint64_t stamp_ns,
                           FunctionRef<bool(const grip_msg_MapUpdate&)> drop);
  void publish_map_updates(const CellBox& box, std::uint64_t stamp_ns);
  // Answers pending map requests with one snapshot (several requests, one snapshot).
  void answer_map_requests(std::uint64_t stamp_ns);

  // The newest valid plan received since the last call, if any; invalid plans are counted.
  // For a reader that wants only the latest (lockstep waits for the plan of its last state).
  const grip_msg_Plan* take_plan();
  // Every valid plan received since the last call, oldest first (invalid ones are counted), for
  // a controller: each plan governs from its start until the next one starts, so none may be
  // skipped. Returns how many were visited.
  std::size_t take_plans(FunctionRef<void(const grip_msg_Plan&)> visit);
  // Sleeps until a plan or a map request arrives, or `timeout` passes (whichever first).
  void wait_for_plan_or_request(std::chrono::nanoseconds timeout);
  // The newest valid status received since the last call (invalid ones are counted).
  std::optional<grip_msg_PlannerStatus> take_status();
  // The newest status, once one of cycle `min_cycle` or later has arrived or `timeout` passed
  // (then the newest older one, if any). Lockstep: the status that goes with a plan.
  std::optional<grip_msg_PlannerStatus> wait_for_status(std::uint64_t min_cycle,
                                                        std::chrono::nanoseconds timeout);

  OccupancyGrid& map() noexcept { return sender_.map(); }
  const MapSender& map_sender() const noexcept { return sender_; }
  std::uint64_t plans_rejected() const noexcept { return plans_rejected_; }
  std::uint64_t statuses_rejected() const noexcept { return statuses_rejected_; }
  std::uint64_t map_writes_failed() const noexcept { return map_writes_failed_; }
  std::uint64_t snapshots_sent() const noexcept { return sender_.snapshots_sent(); }
  // Liveliness of the planner as seen from here (its plan writer).
  bool planner_alive() const;
  // This vehicle side's incarnation (non-zero), and the planner's it follows (0: none yet).
  std::uint64_t incarnation() const noexcept { return incarnation_; }
  std::uint64_t planner_incarnation() const noexcept { return planner_.followed(); }
  // Valid plans rejected because another planner incarnation is followed; plans made for an
  // earlier incarnation of this vehicle; times a standby planner was taken over.
  std::uint64_t plans_from_other_planner() const noexcept { return plans_other_planner_; }
  std::uint64_t plans_for_other_vehicle() const noexcept { return plans_other_vehicle_; }
  std::uint64_t planner_failovers() const noexcept { return planner_.switches(); }
  const platform::dds::Reader<grip_msg_Plan>& plan_reader() const noexcept { return dds_.plans; }

 private:
  // The DDS entities; the link is their one owner.
  struct Entities {
    platform::dds::Participant participant;
    platform::dds::Writer<grip_msg_VehicleDescription> description;
    platform::dds::Writer<grip_msg_VehicleState> states;
    platform::dds::Writer<grip_msg_MapUpdate> maps;
    platform::dds::Writer<grip_msg_Goal> goals;
    platform::dds::Reader<grip_msg_MapRequest> requests;
    platform::dds::Reader<grip_msg_Plan> plans;
    platform::dds::Reader<grip_msg_PlannerStatus> status;
    platform::dds::WaitSet waitset;         // plans and map requests
    platform::dds::WaitSet status_waitset;  // the planner's status

    static Result<Entities> create(const VehicleLinkConfig& config);
  };

  VehicleLink(const VehicleLinkConfig& config, OccupancyGrid map, Entities entities,
              std::unique_ptr<platform::dds::WriterLiveliness> planner_writer);
  void send(const grip_msg_MapUpdate& update);
  // A valid plan of the planner followed, made for this incarnation; counts the rest.
  bool from_followed_planner(const grip_msg_Plan& plan, dds_instance_handle_t writer);
  void warn(const std::string& line) const;

  VehicleKind kind_;
  Entities dds_;
  MapSender sender_;
  std::unique_ptr<platform::dds::SampleBuffer<grip_msg_Plan, kPlanHistoryDepth>> plan_buffer_;
  std::unique_ptr<platform::dds::SampleBuffer<grip_msg_MapRequest, 8>> request_buffer_;
  std::unique_ptr<platform::dds::SampleBuffer<grip_msg_PlannerStatus, 4>> status_buffer_;
  std::uint64_t plans_rejected_ = 0;
  std::uint64_t statuses_rejected_ = 0;  // invalid statuses (check_planner_status), dropped
  std::uint64_t map_writes_failed_ = 0;
  std::uint64_t incarnation_;
  IncarnationTracker planner_;
  std::unique_ptr<platform::dds::WriterLiveliness> planner_writer_;  // the followed one's
  std::uint64_t plans_other_planner_ = 0;
  std::uint64_t plans_other_vehicle_ = 0;
  std::function<void(const std::string&)> warn_;
};

}  // namespace grip::link
