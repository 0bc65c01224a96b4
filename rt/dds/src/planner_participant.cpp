#include "grip/rt/dds/planner_participant.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "goal.h"
#include "grip/exploration/exploration_target.hpp"
#include "grip/exploration/path_selector.hpp"
#include "grip/platform/clock.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/waitset.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/platform/thread.hpp"
#include "grip/platform/wakeup.hpp"
#include "grip/rt/dds/map_sync.hpp"
#include "grip/rt/dds/topics.hpp"
#include "grip/rt/periodic_loop.hpp"
#include "grip/rt/plan_ledger.hpp"
#include "grip/rt/replanning_cycle.hpp"
#include "grip/rt/spsc_ring.hpp"
#include "grip/rt/triple_buffer.hpp"
#include "grip/vehicles/default_vehicle.hpp"
#include "map_update.h"
#include "plan.h"
#include "planner_status.h"
#include "vehicle_state.h"

namespace grip::rt::dds {

namespace {

namespace pdds = platform::dds;

// Map tiles handed to the planning thread: 128 x 128 cells, so that a sensor sweep's change is
// one or a few tiles and a 300 x 300 map's first sync is nine.
constexpr int kTileSide = 128;
constexpr std::size_t kTileRing = 32;

struct MapTile {
  CellBox box;                     // inside the map, at most kTileSide on a side
  std::uint64_t map_sequence = 0;  // the receiver's last applied update when cut
  bool in_sync = false;            // the receiver's map was in sync when cut
  bool last_of_batch = false;      // no other tile was pending when this one was cut
  std::array<Cell, static_cast<std::size_t>(kTileSide) * kTileSide> cells{};
};

struct StateSample {
  std::array<double, 5> state{};
  std::uint64_t stamp_ns = 0;
  std::uint64_t sequence_number = 0;
  std::uint64_t plan_cycle = 0;
  std::uint64_t map_sequence = 0;
  double time_scale = 1.0;
  bool lockstep = false;
};

// What the planning thread's map updates changed since it last planned.
struct MapChanges {
  bool applied = false;   // some update was applied
  CellBox newly_blocked;  // cells that stopped being free
  CellBox changed;        // cells that became free or stopped being free
};

// The publish thread's record of the plans' way out (PlannerParticipantReport::plan_handoff).
struct PublishTiming {
  LatencyHistogram handoff;
  LatencyHistogram write;
};

struct PlanSlot {
  std::uint64_t cycle = 0;
  std::uint64_t start_time_ns = 0;
  std::array<double, 5> start_state{};
  std::uint32_t state_dim = 0;
  std::uint64_t state_sequence = 0;
  std::uint64_t committed_monotonic_ns = 0;
  std::uint32_t steps = 0;
  std::array<grip_msg_PlanStep, grip_msg_kMaxPlanSteps> step{};
};

struct CycleStatus {
  std::uint64_t cycle = 0;
  bool exploring = false;
  bool exploration_complete = false;
  std::uint32_t frontier_groups = 0;
  std::uint32_t frontier_groups_given_up = 0;
  double target_x_m = 0.0;
  double target_y_m = 0.0;
  std::uint64_t misses = 0;
  std::uint64_t tree_edges = 0;
  std::uint64_t edges_added = 0;
  double cycle_time_s = 0.0;
  std::uint64_t map_sequence = 0;
  std::uint64_t map_checksum = 0;
  bool map_in_sync = false;
};

// Counters of the receive thread, read by others.
struct ReceiveCounters {
  std::atomic<std::uint64_t> rejected_vehicle_state{0};
  std::atomic<std::uint64_t> rejected_map_update{0};
  std::atomic<std::uint64_t> rejected_goal{0};
  std::atomic<std::uint64_t> map_gaps{0};
  std::atomic<std::uint64_t> map_heals{0};
  std::atomic<std::uint64_t> vehicle_losses{0};
  std::atomic<bool> vehicle_alive{false};
};

// One log line per topic and second at most; the rest are counted and summarised.
class RateLimitedLog {
 public:
  void rejected(const char* topic, const Verdict& verdict, std::int64_t now_ns) {
    if (now_ns - last_ns_ < 1'000'000'000 && last_ns_ != 0) {
      ++suppressed_;
      return;
    }
    std::fprintf(stderr, "grip planner: rejected %s: %.*s (%s)", topic,
                 static_cast<int>(rejection_name(verdict.reason).size()),
                 rejection_name(verdict.reason).data(), verdict.field);
    if (suppressed_ > 0)
      std::fprintf(stderr, "; %llu more rejected in the last second",
                   static_cast<unsigned long long>(suppressed_));
    std::fprintf(stderr, "\n");
    suppressed_ = 0;
    last_ns_ = now_ns;
  }

 private:
  std::int64_t last_ns_ = 0;
  std::uint64_t suppressed_ = 0;
};

// The vehicle clock as seen from this computer: vehicle_ns = scale * local_ns + offset. A
// state stamped S and received at local time L gives S - scale * L, below the true offset by
// the delivery latency, so the largest of recent values is the best estimate.
class VehicleClock {
 public:
  void observe(std::uint64_t stamp_ns, std::int64_t local_ns, double scale) noexcept {
    const auto candidate = static_cast<std::int64_t>(static_cast<double>(stamp_ns) -
                                                     scale * static_cast<double>(local_ns));
    window_[next_++ % window_.size()] = candidate;
    filled_ = std::min<std::size_t>(filled_ + 1, window_.size());
    std::int64_t best = window_[0];
    for (std::size_t i = 1; i < filled_; ++i) best = std::max(best, window_[i]);
    offset_ns_.store(best, std::memory_order_relaxed);
  }
  std::int64_t vehicle_ns(std::int64_t local_ns, double scale) const noexcept {
    return static_cast<std::int64_t>(scale * static_cast<double>(local_ns)) +
           offset_ns_.load(std::memory_order_relaxed);
  }

 private:
  std::array<std::int64_t, 64> window_{};
  std::size_t next_ = 0;
  std::size_t filled_ = 0;
  std::atomic<std::int64_t> offset_ns_{0};
};

// The DDS time of a sample's source timestamp against now, for freshness checks.
Verdict check_sample_freshness(const dds_sample_info_t& info) {
  return check_freshness(info.source_timestamp, dds_time(), FreshnessLimits{});
}

std::int64_t ns_of(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }

template <VehicleModel V>
class PlannerParticipantFor final : public PlannerParticipant {
 public:
  using State = typename V::State;

  static Result<std::unique_ptr<PlannerParticipant>> create(const PlannerParticipantConfig& config,
                                                            const V& vehicle);
  ~PlannerParticipantFor() override;
  Result<PlannerParticipantReport> run() override;
  PlannerTreePicture last_tree() const override;

 private:
  struct Entities {
    pdds::Participant participant;
    pdds::Reader<grip_msg_VehicleState> states;
    pdds::Reader<grip_msg_MapUpdate> maps;
    pdds::Reader<grip_msg_Goal> goals;
    pdds::Writer<grip_msg_MapRequest> requests;
    pdds::Writer<grip_msg_Plan> plans;
    pdds::Writer<grip_msg_PlannerStatus> status;
    pdds::WaitSet waitset;
  };

  PlannerParticipantFor(const PlannerParticipantConfig& config, const V& vehicle, Entities entities,
                        platform::Wakeup wakeup, platform::Wakeup lockstep_inputs,
                        platform::Wakeup target_wanted);

  // Receive thread.
  void receive_main();
  void take_states(pdds::SampleBuffer<grip_msg_VehicleState, 8>& buffer);
  void take_maps(pdds::SampleBuffer<grip_msg_MapUpdate, 8>& buffer);
  void take_goals(pdds::SampleBuffer<grip_msg_Goal, 4>& buffer);
  void accept_goal(const grip_msg_Goal& goal);
  void mark_dirty(const CellBox& box);
  void hand_over_tiles();
  void check_liveliness();

  // Planning thread (and run() during start-up, before the planning thread exists).
  void apply_tiles(MapChanges& changes) noexcept;
  CycleOutcome cycle_body(std::int64_t release_ns, std::int64_t deadline_ns) noexcept;
  void chain_plan_start(std::int64_t release_ns) noexcept;
  CycleOutcome plan_cycle(std::int64_t started_ns, const MapChanges& changes,
                          std::int64_t deadline_ns) noexcept;
  Result<PlannerParticipantReport> run_lockstep();

  // Target thread.
  void target_main();

  // Publish thread.
  void publish_main();
  void publish_plan(const PlanSlot& slot, PublishTiming& timing);
  void publish_status(const CycleStatus& status);

  Status start_up();
  Status create_cycle(double time_scale, bool explore);
  void update_frontier_target(bool map_changed) noexcept;
  void choose_frontier_target_now() noexcept;
  void request_frontier_target() noexcept;
  void apply_frontier_target() noexcept;
  void note_vehicle_state(const StateSample& measured) noexcept;
  void check_vehicle_follows() noexcept;
  std::optional<typename PlanLedger<V>::Forecast> forecast(std::uint64_t until_ns) const noexcept;
  void follow_forecast(std::uint64_t until_ns) noexcept;
  PlannerParticipantReport final_report(PlannerParticipantReport report);
  std::string progress_line(const PlannerParticipantReport& report) const;
  static State state_of(const StateSample& sample) noexcept {
    State q;
    for (int i = 0; i < V::kStateDim; ++i) q[i] = sample.state[static_cast<std::size_t>(i)];
    return q;
  }

  PlannerParticipantConfig config_;
  V vehicle_;
  Entities dds_;
  platform::Wakeup wakeup_;
  platform::Wakeup lockstep_inputs_;  // lockstep: a state or map tiles were handed over
  platform::Wakeup target_wanted_;    // real time: a frontier target was requested
  std::atomic<bool> threads_stop_{false};

  // Receive thread only.
  MapReceiver receiver_;
  std::vector<CellBox> dirty_;  // per tile
  int tiles_x_ = 0;
  int tiles_y_ = 0;
  std::uint64_t last_state_stamp_ = 0;
  std::uint64_t last_state_sequence_ = 0;
  bool lockstep_seen_ = false;                 // the vehicle's states ask for lockstep
  std::optional<grip_msg_Goal> pending_goal_;  // arrived before the map: checked once it exists
  RateLimitedLog log_;
  bool was_alive_ = false;
  std::unique_ptr<MapTile> handover_tile_ = std::make_unique<MapTile>();  // 16 KiB

  // Shared, lock-free.
  std::atomic<bool> geometry_ready_{false};
  MapGeometry geometry_;  // written once before geometry_ready_ (release)
  std::unique_ptr<SpscRing<MapTile, kTileRing>> tiles_ =
      std::make_unique<SpscRing<MapTile, kTileRing>>();
  std::unique_ptr<TripleBuffer<StateSample>> states_ =
      std::make_unique<TripleBuffer<StateSample>>();
  std::unique_ptr<TripleBuffer<GoalRegion>> goals_ = std::make_unique<TripleBuffer<GoalRegion>>();
  std::unique_ptr<TripleBuffer<PlanSlot>> plans_ = std::make_unique<TripleBuffer<PlanSlot>>();
  std::unique_ptr<TripleBuffer<CycleStatus>> statuses_ =
      std::make_unique<TripleBuffer<CycleStatus>>();
  ReceiveCounters counters_;
  VehicleClock clock_;
  std::atomic<std::uint64_t> plans_published_{0};
  // The publish thread's timing, copied out after every plan for final_report().
  std::unique_ptr<TripleBuffer<PublishTiming>> publish_timing_ =
      std::make_unique<TripleBuffer<PublishTiming>>();
  std::string publish_policy_;  // written by the publish thread before publish_policy_set_
  std::atomic<bool> publish_policy_set_{false};
  std::atomic<std::uint64_t> write_failures_{0};
  // The frontier target's hand-over. kIdle: the planning thread owns target_ (it copies its map
  // in and notes the robot's position); kRequested: the target thread chooses; kChosen: the
  // planning thread reads the choice, then makes it kIdle again.
  enum TargetStage : std::uint8_t { kIdle, kRequested, kChosen };
  std::atomic<std::uint8_t> target_stage_{kIdle};
  std::optional<ExplorationTarget> target_;  // created at start-up, before any request
  double target_robot_x_m_ = 0.0;            // the request: where the robot will be, and when
  double target_robot_y_m_ = 0.0;
  std::int64_t target_robot_ns_ = 0;

  // Planning thread only (after start-up).
  std::optional<OccupancyGrid> grid_;
  std::optional<ReplanningCycle<V>> cycle_;
  // Exploration (section 3), while no goal was given.
  bool exploring_ = false;
  bool explored_ = false;
  std::optional<PathSelector> selector_;
  double target_x_m_ = 0.0;
  double target_y_m_ = 0.0;
  std::uint32_t frontier_groups_ = 0;
  std::uint32_t frontier_groups_given_up_ = 0;
  bool target_requested_ = false;  // a frontier target has been requested at least once
  std::uint32_t cycles_since_target_ = 0;
  bool map_changed_since_target_ = true;  // target_ holds the map of its creation
  std::unique_ptr<MapTile> tile_ = std::make_unique<MapTile>();
  double time_scale_ = 1.0;
  bool lockstep_ = false;  // from the first state: plan once per state, by edge count
  std::uint64_t lockstep_edges_ = 0;
  StateSample first_state_;                      // the state start-up planned from
  std::atomic<std::int64_t> period_wall_ns_{0};  // set at start-up, read by the publish thread
  // Set by the planning thread once the plan's end is settled, before it extracts the plan:
  // the publish thread wakes meanwhile and is running when the plan is handed over.
  std::atomic<bool> plan_coming_{false};
  std::uint64_t state_sequence_ = 0;
  std::uint64_t plan_start_ns_ = 0;        // vehicle time at which this cycle's plan starts
  std::optional<StateSample> last_state_;  // the last measured state
  std::uint64_t resyncs_ = 0;
  // The plans sent, to forecast where the vehicle will be (check_vehicle_follows, and where
  // the plan it goes on with leads when a cycle has none).
  std::optional<PlanLedger<V>> ledger_;
  std::uint64_t cycles_ = 0;
  std::uint64_t misses_ = 0;          // cycles that ended after their deadline, or were skipped
  std::int64_t last_release_ns_ = 0;  // real time: the release of the last cycle run
  std::uint64_t plans_committed_ = 0;
  std::uint64_t map_sequence_ = 0;
  std::uint64_t map_checksum_ = 0;
  bool map_in_sync_ = false;

  std::thread receive_thread_;
  std::thread publish_thread_;
  std::thread target_thread_;
};

template <VehicleModel V>
Result<std::unique_ptr<PlannerParticipant>> PlannerParticipantFor<V>::create(
    const PlannerParticipantConfig& config, const V& vehicle) {
  LinkTiming timing;
  timing.cycle = std::chrono::nanoseconds(ns_of(config.cycle_s));
  timing.liveliness_lease = config.liveliness_lease;
  auto participant = pdds::Participant::create(config.domain, config.dds_config);
  if (!participant) return participant.error();
  auto states = pdds::Reader<grip_msg_VehicleState>::create(
      *participant, &grip_msg_VehicleState_desc, kVehicleStateTopic,
      vehicle_state_qos(timing, Endpoint::kReader));
  if (!states) return states.error();
  auto maps = pdds::Reader<grip_msg_MapUpdate>::create(*participant, &grip_msg_MapUpdate_desc,
                                                       kMapUpdateTopic, map_update_qos(timing));
  if (!maps) return maps.error();
  auto goals = pdds::Reader<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc, kGoalTopic,
                                                   goal_qos(timing));
  if (!goals) return goals.error();
  auto requests = pdds::Writer<grip_msg_MapRequest>::create(
      *participant, &grip_msg_MapRequest_desc, kMapRequestTopic, map_request_qos(timing));
  if (!requests) return requests.error();
  auto plans = pdds::Writer<grip_msg_Plan>::create(*participant, &grip_msg_Plan_desc, kPlanTopic,
                                                   plan_qos(timing, Endpoint::kWriter));
  if (!plans) return plans.error();
  auto status = pdds::Writer<grip_msg_PlannerStatus>::create(
      *participant, &grip_msg_PlannerStatus_desc, kPlannerStatusTopic, planner_status_qos(timing));
  if (!status) return status.error();
  auto waitset = pdds::WaitSet::create(*participant);
  if (!waitset) return waitset.error();
  for (const dds_entity_t reader : {states->get(), maps->get(), goals->get()}) {
    if (Status s = waitset->attach_data_available(reader); !s) return s.error();
  }
  auto wakeup = platform::Wakeup::create();
  if (!wakeup) return wakeup.error();
  auto lockstep_inputs = platform::Wakeup::create();
  if (!lockstep_inputs) return lockstep_inputs.error();
  auto target_wanted = platform::Wakeup::create();
  if (!target_wanted) return target_wanted.error();
  std::unique_ptr<PlannerParticipantFor> self(new PlannerParticipantFor(
      config, vehicle,
      Entities{std::move(participant).value(), std::move(states).value(), std::move(maps).value(),
               std::move(goals).value(), std::move(requests).value(), std::move(plans).value(),
               std::move(status).value(), std::move(waitset).value()},
      std::move(wakeup).value(), std::move(lockstep_inputs).value(),
      std::move(target_wanted).value()));
  // Service threads start now: before any SCHED_DEADLINE thread, which could not create them.
  self->receive_thread_ = std::thread([raw = self.get()] { raw->receive_main(); });
  self->publish_thread_ = std::thread([raw = self.get()] { raw->publish_main(); });
  self->target_thread_ = std::thread([raw = self.get()] { raw->target_main(); });
  return std::unique_ptr<PlannerParticipant>(std::move(self));
}

template <VehicleModel V>
PlannerParticipantFor<V>::PlannerParticipantFor(const PlannerParticipantConfig& config,
                                                const V& vehicle, Entities entities,
                                                platform::Wakeup wakeup,
                                                platform::Wakeup lockstep_inputs,
                                                platform::Wakeup target_wanted)
    : config_(config),
      vehicle_(vehicle),
      dds_(std::move(entities)),
      wakeup_(std::move(wakeup)),
      lockstep_inputs_(std::move(lockstep_inputs)),
      target_wanted_(std::move(target_wanted)),
      receiver_(config.max_map_cells) {}

template <VehicleModel V>
PlannerParticipantFor<V>::~PlannerParticipantFor() {
  threads_stop_.store(true, std::memory_order_release);
  static_cast<void>(dds_.waitset.wake());
  wakeup_.signal();
  target_wanted_.signal();
  if (receive_thread_.joinable()) receive_thread_.join();
  if (publish_thread_.joinable()) publish_thread_.join();
  if (target_thread_.joinable()) target_thread_.join();
}

// ---- Receive thread ----

template <VehicleModel V>
void PlannerParticipantFor<V>::receive_main() {
  // Sample storage reused for every take: after the first few, takes no longer allocate.
  auto state_buffer =
      std::make_unique<pdds::SampleBuffer<grip_msg_VehicleState, 8>>(&grip_msg_VehicleState_desc);
  auto map_buffer =
      std::make_unique<pdds::SampleBuffer<grip_msg_MapUpdate, 8>>(&grip_msg_MapUpdate_desc);
  auto goal_buffer = std::make_unique<pdds::SampleBuffer<grip_msg_Goal, 4>>(&grip_msg_Goal_desc);
  while (!threads_stop_.load(std::memory_order_acquire)) {
    // The timeout paces the periodic work: snapshot requests, tiles the ring had no room for,
    // liveliness.
    static_cast<void>(dds_.waitset.wait(std::chrono::milliseconds(20)));
    take_states(*state_buffer);
    take_maps(*map_buffer);
    take_goals(*goal_buffer);
    const std::int64_t now = platform::now_ns();
    if (receiver_.should_request(now, 500'000'000)) {
      grip_msg_MapRequest request{};
      request.from_sequence = receiver_.next_expected();
      request.stamp_ns = static_cast<std::uint64_t>(clock_.vehicle_ns(now, 1.0));
      if (dds_.requests.write(request).ok()) receiver_.note_requested(now);
    }
    hand_over_tiles();
    check_liveliness();
    if (lockstep_seen_) lockstep_inputs_.signal();
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::take_states(pdds::SampleBuffer<grip_msg_VehicleState, 8>& buffer) {
  for (;;) {
    const Result<std::size_t> taken = dds_.states.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) {
      const grip_msg_VehicleState& msg = buffer[i];
      // A lockstep simulator repeats the state it waits on (for a planner that joins late):
      // a repeat is neither new nor an error.
      if (msg.stamp_ns == last_state_stamp_ && msg.sequence_number == last_state_sequence_) {
        continue;
      }
      Verdict verdict = check_sample_freshness(buffer.info(i));
      if (verdict.ok()) verdict = check_vehicle_state(msg, vehicle_, last_state_stamp_);
      const std::int64_t now = platform::now_ns();
      if (!verdict.ok()) {
        counters_.rejected_vehicle_state.fetch_add(1, std::memory_order_relaxed);
        log_.rejected("vehicle state", verdict, now);
        continue;
      }
      last_state_stamp_ = msg.stamp_ns;
      last_state_sequence_ = msg.sequence_number;
      lockstep_seen_ = msg.lockstep;
      clock_.observe(msg.stamp_ns, now, msg.time_scale);
      StateSample& sample = states_->write_buffer();
      std::copy(std::begin(msg.state), std::end(msg.state), sample.state.begin());
      sample.stamp_ns = msg.stamp_ns;
      sample.sequence_number = msg.sequence_number;
      sample.plan_cycle = msg.plan_cycle;
      sample.map_sequence = msg.map_sequence;
      sample.time_scale = msg.time_scale;
      sample.lockstep = msg.lockstep;
      states_->publish();
    }
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::take_maps(pdds::SampleBuffer<grip_msg_MapUpdate, 8>& buffer) {
  for (;;) {
    const Result<std::size_t> taken = dds_.maps.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) {
      const std::int64_t now = platform::now_ns();
      const Verdict fresh = check_sample_freshness(buffer.info(i));
      const bool had_map = receiver_.has_map();
      const MapApplied applied =
          fresh.ok() ? receiver_.apply(buffer[i]) : MapApplied{fresh, false, false, false, {}};
      if (!applied.verdict.ok()) {
        counters_.rejected_map_update.fetch_add(1, std::memory_order_relaxed);
        log_.rejected("map update", applied.verdict, now);
        continue;
      }
      if (!had_map) {
        geometry_ = geometry_of(receiver_.map());
        tiles_x_ = (receiver_.map().width() + kTileSide - 1) / kTileSide;
        tiles_y_ = (receiver_.map().height() + kTileSide - 1) / kTileSide;
        dirty_.assign(static_cast<std::size_t>(tiles_x_ * tiles_y_), CellBox{});
        geometry_ready_.store(true, std::memory_order_release);
        if (pending_goal_) accept_goal(*pending_goal_);
        pending_goal_.reset();
      }
      if (applied.gap) {
        counters_.map_gaps.fetch_add(1, std::memory_order_relaxed);
        std::fprintf(stderr,
                     "grip planner: map update gap before sequence %llu; requesting a snapshot\n",
                     static_cast<unsigned long long>(buffer[i].sequence_number));
      }
      if (applied.healed) counters_.map_heals.fetch_add(1, std::memory_order_relaxed);
      mark_dirty(applied.changed);
    }
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::take_goals(pdds::SampleBuffer<grip_msg_Goal, 4>& buffer) {
  for (;;) {
    const Result<std::size_t> taken = dds_.goals.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) {
      const Verdict fresh = check_sample_freshness(buffer.info(i));
      if (!fresh.ok()) {
        counters_.rejected_goal.fetch_add(1, std::memory_order_relaxed);
        log_.rejected("goal", fresh, platform::now_ns());
      } else if (!receiver_.has_map()) {
        pending_goal_ = buffer[i];
      } else {
        accept_goal(buffer[i]);
      }
    }
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::accept_goal(const grip_msg_Goal& goal) {
  const Verdict verdict = check_goal(goal, receiver_.map());
  if (!verdict.ok()) {
    counters_.rejected_goal.fetch_add(1, std::memory_order_relaxed);
    log_.rejected("goal", verdict, platform::now_ns());
    return;
  }
  goals_->write(goal_from_wire(goal));
}

template <VehicleModel V>
void PlannerParticipantFor<V>::mark_dirty(const CellBox& box) {
  for (int ty = box.y0 / kTileSide; ty <= box.y1 / kTileSide; ++ty) {
    for (int tx = box.x0 / kTileSide; tx <= box.x1 / kTileSide; ++tx) {
      const CellBox tile{tx * kTileSide, ty * kTileSide, tx * kTileSide + kTileSide - 1,
                         ty * kTileSide + kTileSide - 1};
      const CellBox part{std::max(box.x0, tile.x0), std::max(box.y0, tile.y0),
                         std::min(box.x1, tile.x1), std::min(box.y1, tile.y1)};
      dirty_[static_cast<std::size_t>(ty * tiles_x_ + tx)].add(part);
    }
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::hand_over_tiles() {
  // Tiles carry the receiver's map as it is now, so a tile cut later is never older; a tile
  // the ring has no room for stays dirty and goes next time.
  const OccupancyGrid* map = receiver_.has_map() ? &receiver_.map() : nullptr;
  if (map == nullptr) return;
  std::size_t pending = 0;
  for (const CellBox& box : dirty_) pending += box.empty() ? 0U : 1U;
  MapTile* tile = handover_tile_.get();
  for (CellBox& box : dirty_) {
    if (box.empty()) continue;
    tile->box = box;
    tile->map_sequence = receiver_.last_sequence();
    tile->in_sync = receiver_.in_sync();
    tile->last_of_batch = --pending == 0;
    const int w = box.x1 - box.x0 + 1;
    for (int y = box.y0; y <= box.y1; ++y) {
      for (int x = box.x0; x <= box.x1; ++x) {
        tile->cells[static_cast<std::size_t>((y - box.y0) * w + (x - box.x0))] = map->at(x, y);
      }
    }
    if (!tiles_->try_push(*tile)) return;
    box = CellBox{};
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::check_liveliness() {
  const auto live = dds_.states.liveliness_changed();
  if (!live.ok()) return;
  const bool alive = live->alive_count > 0;
  // Once planning has been told to stop, the vehicle leaving is the end of the run, not a loss.
  if (was_alive_ && !alive && !stop_.load(std::memory_order_acquire)) {
    counters_.vehicle_losses.fetch_add(1, std::memory_order_relaxed);
    std::fprintf(stderr,
                 "grip planner: vehicle controller lost (liveliness); planning goes on with the "
                 "last map and state\n");
  }
  was_alive_ = alive;
  counters_.vehicle_alive.store(alive, std::memory_order_relaxed);
}

// ---- Planning thread ----

template <VehicleModel V>
void PlannerParticipantFor<V>::apply_tiles(MapChanges& changes) noexcept {
  bool applied = false;  // by this call (changes.applied may come from an earlier one)
  bool batch_complete = false;
  OccupancyGrid& grid = *grid_;
  while (tiles_->try_pop(*tile_)) {
    const MapTile& t = *tile_;
    const int w = t.box.x1 - t.box.x0 + 1;
    auto cells = grid.mutable_cells();
    for (int y = t.box.y0; y <= t.box.y1; ++y) {
      for (int x = t.box.x0; x <= t.box.x1; ++x) {
        const Cell value = t.cells[static_cast<std::size_t>((y - t.box.y0) * w + (x - t.box.x0))];
        Cell& cell = cells[grid.index(x, y)];
        if ((cell == Cell::kFree) != (value == Cell::kFree)) {
          // Clearance changes only near cells that became free or stopped being free; only the
          // latter can cut the tree (retain's contract).
          changes.changed.add(CellBox{x, y, x, y});
          if (cell == Cell::kFree) changes.newly_blocked.add(CellBox{x, y, x, y});
        }
        cell = value;
      }
    }
    map_sequence_ = t.map_sequence;
    map_in_sync_ = t.in_sync;
    batch_complete = t.last_of_batch;
    applied = true;
    changes.applied = true;
  }
  // The checksum describes a whole hand-over, not a map half way through one.
  if (applied && batch_complete) map_checksum_ = map_checksum(grid);
}

// Real time: one cycle per period of the PeriodicLoop, growth until the deadline.
template <VehicleModel V>
CycleOutcome PlannerParticipantFor<V>::cycle_body(std::int64_t release_ns,
                                                  std::int64_t deadline_ns) noexcept {
  const std::int64_t start = platform::now_ns();
  // Releases the loop skipped after a stall (PeriodicLoop) were missed too.
  const std::int64_t period = period_wall_ns_.load(std::memory_order_relaxed);
  if (last_release_ns_ != 0 && release_ns - last_release_ns_ > period) {
    misses_ += static_cast<std::uint64_t>((release_ns - last_release_ns_) / period - 1);
  }
  last_release_ns_ = release_ns;
  MapChanges changes;
  apply_tiles(changes);
  const bool new_state = states_->update();
  if (new_state) note_vehicle_state(states_->read_buffer());
  chain_plan_start(release_ns);
  if (new_state) check_vehicle_follows();
  return plan_cycle(start, changes, deadline_ns);
}

template <VehicleModel V>
void PlannerParticipantFor<V>::chain_plan_start(std::int64_t release_ns) noexcept {
  // The plan starts at t[i], in vehicle time, at or after the next release: committed before
  // the deadline, it reaches the vehicle before it is due (a late plan is refused). Consecutive
  // plans start exactly T apart, on the vehicle's own integration grid (the stamps of its
  // states), so that each starts where the one before put the vehicle. The chain is re-anchored
  // only when a plan would start too early (more than T/8 before the release: the clock
  // estimate moved) or needlessly late (more than 1.5 T after it); the forecast of
  // check_vehicle_follows then moves the tree to the new start.
  const auto cycle_ns = static_cast<std::uint64_t>(ns_of(config_.cycle_s));
  const auto wanted = static_cast<std::uint64_t>(
      clock_.vehicle_ns(release_ns + period_wall_ns_.load(std::memory_order_relaxed), time_scale_));
  plan_start_ns_ += cycle_ns;
  const bool too_early = plan_start_ns_ + cycle_ns / 8 < wanted;
  const bool too_late = plan_start_ns_ > wanted + cycle_ns + cycle_ns / 2;
  if ((too_early || too_late) && last_state_) {
    const std::uint64_t stamp_ns = last_state_->stamp_ns;
    const double cycles =
        std::ceil(static_cast<double>(static_cast<std::int64_t>(wanted - stamp_ns)) /
                  static_cast<double>(cycle_ns));
    plan_start_ns_ = stamp_ns + static_cast<std::uint64_t>(std::max(0.0, cycles)) * cycle_ns;
  }
}

// Both modes: the cycle's inputs, growth (until the deadline, or by edge count in lockstep),
// and the hand-over of its plan and status to the publish thread.
template <VehicleModel V>
CycleOutcome PlannerParticipantFor<V>::plan_cycle(std::int64_t start, const MapChanges& changes,
                                                  std::int64_t deadline_ns) noexcept {
  if (changes.applied) {
    cycle_->note_newly_blocked(changes.newly_blocked);
    cycle_->note_changed(changes.changed);
  }
  if (goals_->update()) {
    const GoalRegion& goal = goals_->read_buffer();
    cycle_->set_goal(goal);  // a goal ends exploration
    exploring_ = false;
    target_x_m_ = goal.x_m;
    target_y_m_ = goal.y_m;
  }
  if (exploring_) update_frontier_target(changes.applied);
  const auto now = [] { return platform::now_ns(); };
  const auto choose = [this](const Planner<V>& planner) {
    if (!exploring_) return planner.best_state();
    return explored_ ? planner.root_state()
                     : selector_->select(planner, cycle_->cycle_steps()).state;
  };
  const auto announce_plan = [this] {
    plan_coming_.store(true, std::memory_order_release);
    wakeup_.signal();
  };
  const std::int64_t prepared = platform::now_ns();
  CycleOutcome out = lockstep_ ? cycle_->run_for_edges(now, lockstep_edges_, choose, announce_plan)
                               : cycle_->run(now, deadline_ns, choose, announce_plan);
  out.prepare_ns = prepared - start;
  ++cycles_;
  const std::int64_t end = platform::now_ns();
  misses_ += !lockstep_ && end > deadline_ns ? 1 : 0;

  {
    // Planned during (t[i-1], t[i]) for execution from t[i], the next release. Without a plan
    // an empty one is sent: the vehicle drives the plan it executes to its end, where its
    // braking was checked (idl/plan.idl), and the next cycle starts a fresh tree where the
    // ledger forecasts it then.
    std::span<const PlanStep> sent;
    if (out.plan_available) {
      sent = std::span<const PlanStep>(cycle_->plan().data(), cycle_->plan().size());
    }
    sent = sent.first(std::min<std::size_t>(sent.size(), grip_msg_kMaxPlanSteps));
    const State from = cycle_->plan_start();
    PlanSlot& slot = plans_->write_buffer();
    slot.cycle = cycles_;
    slot.start_time_ns = plan_start_ns_;
    state_to_wire<V>(from, slot.start_state.data(), slot.state_dim);
    slot.state_sequence = state_sequence_;
    slot.steps = static_cast<std::uint32_t>(sent.size());
    for (std::uint32_t i = 0; i < slot.steps; ++i) {
      slot.step[i].control[0] = sent[i].control[0];
      slot.step[i].control[1] = sent[i].control[1];
      slot.step[i].duration_s = sent[i].duration_s;
    }
    slot.committed_monotonic_ns = static_cast<std::uint64_t>(platform::now_ns());
    ledger_->record(cycles_, plan_start_ns_, from, sent);
    if (!out.plan_available) {
      follow_forecast(plan_start_ns_ + static_cast<std::uint64_t>(ns_of(config_.cycle_s)));
    }
    plans_->publish();
    plans_committed_ += out.plan_available ? 1 : 0;
  }
  CycleStatus& status = statuses_->write_buffer();
  status.cycle = cycles_;
  status.exploring = exploring_;
  status.exploration_complete = explored_;
  status.frontier_groups = frontier_groups_;
  status.frontier_groups_given_up = frontier_groups_given_up_;
  status.target_x_m = target_x_m_;
  status.target_y_m = target_y_m_;
  status.misses = misses_;
  status.tree_edges = out.tree_edges;
  status.edges_added = out.edges_added;
  status.cycle_time_s = static_cast<double>(end - start) * 1e-9;
  status.map_sequence = map_sequence_;
  status.map_checksum = map_checksum_;
  status.map_in_sync = map_in_sync_;
  statuses_->publish();
  wakeup_.signal();
  return out;
}

template <VehicleModel V>
void PlannerParticipantFor<V>::note_vehicle_state(const StateSample& measured) noexcept {
  state_sequence_ = measured.sequence_number;
  last_state_ = measured;
}

// Where the vehicle will be at until_ns, from the last measured state and the plans sent since.
template <VehicleModel V>
std::optional<typename PlanLedger<V>::Forecast> PlannerParticipantFor<V>::forecast(
    std::uint64_t until_ns) const noexcept {
  if (!last_state_ || until_ns < last_state_->stamp_ns) return std::nullopt;
  return ledger_->forecast(state_of(*last_state_), last_state_->stamp_ns, last_state_->plan_cycle,
                           until_ns);
}

// The next tree starts where the vehicle will be at until_ns when that is not where the cycle
// puts it (counted in resyncs_).
template <VehicleModel V>
void PlannerParticipantFor<V>::follow_forecast(std::uint64_t until_ns) noexcept {
  const auto there = forecast(until_ns);
  if (!there) return;  // it executes a plan older than the ledger: nothing to go by
  if (states_match(there->state, cycle_->next_plan_start())) return;
  cycle_->resynchronise(there->state);
  ++resyncs_;
}

template <VehicleModel V>
void PlannerParticipantFor<V>::check_vehicle_follows() noexcept {
  // Where the vehicle will be when this cycle's plan starts, from the plan it reports executing
  // and the plans sent since (PlanLedger). When that is not where the tree puts the plan's
  // start (a plan came late or was refused, the vehicle brakes off its plans, the chain of
  // start times was re-anchored), every plan from this tree would be refused: this cycle
  // starts a fresh tree there.
  follow_forecast(plan_start_ns_);
}

// The frontier target is chosen again every target_refresh_cycles cycles, from where the plan
// starts (the robot moves even when the map does not change). In real time the target thread
// chooses it while the planning thread goes on growing toward the previous target, and the
// first cycle after the choice takes it over. In lockstep the choice is made at once, in the
// cycle, so that a seed reproduces a run.
template <VehicleModel V>
void PlannerParticipantFor<V>::update_frontier_target(bool map_changed) noexcept {
  map_changed_since_target_ = map_changed_since_target_ || map_changed;
  if (lockstep_) {
    if (target_requested_ && ++cycles_since_target_ < config_.target_refresh_cycles) return;
    choose_frontier_target_now();
    return;
  }
  const std::uint8_t stage = target_stage_.load(std::memory_order_acquire);
  if (stage == kChosen) {
    apply_frontier_target();
    target_stage_.store(kIdle, std::memory_order_release);
  } else if (stage == kIdle &&
             (!target_requested_ || ++cycles_since_target_ >= config_.target_refresh_cycles)) {
    request_frontier_target();
    target_stage_.store(kRequested, std::memory_order_release);
    target_wanted_.signal();
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::choose_frontier_target_now() noexcept {
  request_frontier_target();
  target_->choose(target_robot_x_m_, target_robot_y_m_, target_robot_ns_);
  apply_frontier_target();
}

// Planning thread (or start-up), with target_ its own: kIdle, or lockstep.
template <VehicleModel V>
void PlannerParticipantFor<V>::request_frontier_target() noexcept {
  target_requested_ = true;
  cycles_since_target_ = 0;
  if (std::exchange(map_changed_since_target_, false)) target_->copy_map(*grid_);
  const State& here = cycle_->plan_start();
  target_robot_x_m_ = state_x(here);
  target_robot_y_m_ = state_y(here);
  target_robot_ns_ = static_cast<std::int64_t>(plan_start_ns_);
}

// Planning thread, with target_ its own (kChosen, or lockstep).
template <VehicleModel V>
void PlannerParticipantFor<V>::apply_frontier_target() noexcept {
  ExplorationTarget& target = *target_;
  frontier_groups_ = target.groups();
  frontier_groups_given_up_ = target.given_up_groups();
  const ExplorationStatus status = target.status();
  if (status != ExplorationStatus::kTarget) {
    // No reachable frontier is left (or the robot is off the map): stop where it stands.
    explored_ = status == ExplorationStatus::kComplete;
    const State& here = cycle_->plan_start();
    cycle_->set_goal(GoalRegion{state_x(here), state_y(here), 0.5});
    return;
  }
  explored_ = false;
  target_x_m_ = target.target_x_m();
  target_y_m_ = target.target_y_m();
  cycle_->set_goal(GoalCells{target.approach_cells()}, target.rho());
  selector_->set_target(*grid_, target.target_cells());
}

// ---- Target thread ----

template <VehicleModel V>
void PlannerParticipantFor<V>::target_main() {
  while (!threads_stop_.load(std::memory_order_acquire)) {
    static_cast<void>(target_wanted_.wait(std::chrono::milliseconds(100)));
    if (target_stage_.load(std::memory_order_acquire) != kRequested) continue;
    target_->choose(target_robot_x_m_, target_robot_y_m_, target_robot_ns_);
    target_stage_.store(kChosen, std::memory_order_release);
  }
}

// ---- Publish thread ----

template <VehicleModel V>
void PlannerParticipantFor<V>::publish_main() {
  // A plan is worth most when fresh: the publish thread takes a low SCHED_FIFO priority where
  // the machine grants one, so that it is not queued behind ordinary work when a plan is ready.
  // Refused (no CAP_SYS_NICE), it stays SCHED_OTHER; the report says which.
  platform::SchedulingRequest request;
  request.request = platform::PolicyRequest::kFifo;
  request.fifo_priority = 10;
  const auto applied = platform::apply_scheduling(request);
  publish_policy_ = applied.ok() ? "fifo" : "other (" + applied.error().message + ")";
  publish_policy_set_.store(true, std::memory_order_release);
  // A plan is announced (plan_coming_) once its end is settled, before it is extracted and handed
  // over: the thread's wake-up latency (40-65 us median here, far more in the VM's tail) then
  // overlaps that work instead of adding to the plan's delivery, and the thread, running, watches
  // the hand-off for the plan, at most kPlanComingWatchNs (the extraction takes tens of us).
  constexpr std::int64_t kPlanComingWatchNs = 1'000'000;
  PublishTiming timing;
  while (!threads_stop_.load(std::memory_order_acquire)) {
    static_cast<void>(wakeup_.wait(std::chrono::milliseconds(100)));
    if (plan_coming_.exchange(false, std::memory_order_acquire)) {
      const std::int64_t watch_until = platform::now_ns() + kPlanComingWatchNs;
      while (!plans_->fresh() && platform::now_ns() < watch_until) platform::cpu_relax();
    }
    if (plans_->update()) {
      publish_plan(plans_->read_buffer(), timing);
      publish_timing_->write(timing);
    }
    if (statuses_->update()) publish_status(statuses_->read_buffer());
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::publish_plan(const PlanSlot& slot, PublishTiming& timing) {
  grip_msg_Plan msg{};
  msg.cycle = slot.cycle;
  msg.start_time_ns = slot.start_time_ns;
  std::copy(slot.start_state.begin(), slot.start_state.end(), std::begin(msg.start_state));
  msg.state_dim = slot.state_dim;
  msg.state_sequence = slot.state_sequence;
  msg.committed_monotonic_ns = slot.committed_monotonic_ns;
  msg.kind = to_wire(V::kKind);
  msg.contingency = contingency_of(V::kKind);
  // Borrowed, not copied: DDS serialises during dds_write.
  msg.steps._buffer = const_cast<grip_msg_PlanStep*>(slot.step.data());
  msg.steps._length = slot.steps;
  msg.steps._maximum = slot.steps;
  msg.steps._release = false;
  const std::int64_t write_start = platform::now_ns();
  const bool written = dds_.plans.write(msg).ok();
  const std::int64_t write_end = platform::now_ns();
  if (written) {
    timing.handoff.record(write_start - static_cast<std::int64_t>(slot.committed_monotonic_ns));
    timing.write.record(write_end - write_start);
    plans_published_.fetch_add(1, std::memory_order_relaxed);
  } else {
    write_failures_.fetch_add(1, std::memory_order_relaxed);
  }
}

template <VehicleModel V>
void PlannerParticipantFor<V>::publish_status(const CycleStatus& s) {
  grip_msg_PlannerStatus msg{};
  msg.cycle = s.cycle;
  msg.stamp_ns = static_cast<std::uint64_t>(clock_.vehicle_ns(platform::now_ns(), time_scale_));
  std::snprintf(msg.policy, sizeof msg.policy, "%s", "grip at T, contingency at T");
  msg.misses = s.misses;
  msg.tree_edges = s.tree_edges;
  msg.edges_added = s.edges_added;
  msg.cycle_time_s = s.cycle_time_s;
  msg.rejected_vehicle_state = counters_.rejected_vehicle_state.load(std::memory_order_relaxed);
  msg.rejected_map_update = counters_.rejected_map_update.load(std::memory_order_relaxed);
  msg.rejected_goal = counters_.rejected_goal.load(std::memory_order_relaxed);
  msg.map_gaps = counters_.map_gaps.load(std::memory_order_relaxed);
  msg.map_heals = counters_.map_heals.load(std::memory_order_relaxed);
  msg.map_sequence = s.map_sequence;
  msg.map_checksum = s.map_checksum;
  msg.map_in_sync = s.map_in_sync;
  msg.plans_published = plans_published_.load(std::memory_order_relaxed);
  msg.plans_dropped = write_failures_.load(std::memory_order_relaxed);
  const auto matched = dds_.plans.publication_matched();
  msg.plan_subscribers = matched.ok() ? matched->current_count : 0;
  msg.vehicle_alive = counters_.vehicle_alive.load(std::memory_order_relaxed);
  msg.exploring = s.exploring;
  msg.exploration_complete = s.exploration_complete;
  msg.frontier_groups = s.frontier_groups;
  msg.frontier_groups_given_up = s.frontier_groups_given_up;
  msg.target_x_m = s.target_x_m;
  msg.target_y_m = s.target_y_m;
  static_cast<void>(dds_.status.write(msg));
}

// ---- Start-up and the run ----

template <VehicleModel V>
Status PlannerParticipantFor<V>::start_up() {
  const std::int64_t started = platform::now_ns();
  const std::int64_t timeout = config_.startup_timeout.count();
  std::optional<StateSample> state;
  std::optional<GoalRegion> goal;
  std::optional<std::int64_t> synced_at;  // when the map was first in sync
  std::string refusal;
  while (!stop_.load(std::memory_order_acquire)) {
    if (!grid_ && geometry_ready_.load(std::memory_order_acquire)) {
      auto grid = OccupancyGrid::create(
          static_cast<int>(geometry_.width_cells), static_cast<int>(geometry_.height_cells),
          geometry_.resolution_m, geometry_.origin_x_m, geometry_.origin_y_m, Cell::kUnknown);
      if (!grid) return grid.error();
      grid_.emplace(std::move(grid).value());
    }
    if (grid_) {
      MapChanges ignored;    // no tree yet
      apply_tiles(ignored);  // this thread is the tiles' consumer until planning starts
    }
    if (states_->update()) state = states_->read_buffer();
    if (goals_->update()) goal = goals_->read_buffer();
    if (grid_ && map_in_sync_ && !synced_at) synced_at = platform::now_ns();
    // Without a goal within the grace period after the map, the planner explores.
    const bool explore = !goal && config_.explore_without_goal && synced_at &&
                         platform::now_ns() - *synced_at >= config_.goal_grace.count();
    if (grid_ && map_in_sync_ && state && (goal || explore)) {
      if (!cycle_) {
        lockstep_ = state->lockstep;
        if (Status s = create_cycle(state->time_scale, explore); !s) return s;
      }
      const State q0 = state_of(*state);
      exploring_ = !goal;
      // Exploring, the first target is where the vehicle stands; the first cycle picks a frontier.
      const GoalRegion first = goal ? *goal : GoalRegion{state_x(q0), state_y(q0), 0.5};
      target_x_m_ = first.x_m;
      target_y_m_ = first.y_m;
      Status started_cycle = cycle_->start(q0, first);
      if (started_cycle.ok()) {
        note_vehicle_state(*state);
        first_state_ = *state;
        return Ok{};
      }
      refusal = started_cycle.error().message;  // e.g. the start is not known free yet
    }
    if (timeout > 0 && platform::now_ns() - started > timeout) {
      std::string missing;
      if (!grid_ || !map_in_sync_) missing += " a map in sync,";
      if (!state) missing += " a vehicle state,";
      if (!goal && !config_.explore_without_goal) missing += " a goal,";
      if (missing.empty()) missing = " a start the planner accepts (" + refusal + "),";
      missing.pop_back();
      return Error{ErrorCode::kIo, "start-up timed out waiting for" + missing};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return Error{ErrorCode::kIo, "stopped during start-up"};
}

template <VehicleModel V>
Status PlannerParticipantFor<V>::create_cycle(double time_scale, bool explore) {
  time_scale_ = time_scale;
  const double wall_budget_ms = config_.budget_s * 1e3 / time_scale;
  period_wall_ns_.store(ns_of(config_.cycle_s / time_scale), std::memory_order_relaxed);
  PlannerConfig planner_config;
  // Whole fractions of T, at most 50 ms per integration step (as `grip stress`).
  planner_config.integration_step_s = integration_step_for_cycle(config_.cycle_s);
  planner_config.seed = config_.seed;
  if (config_.no_safety) planner_config.safety = SafetyCheck::kNone;
  // Lockstep grows a fixed number of edges per cycle; the pools hold a few cycles' growth.
  lockstep_edges_ = config_.lockstep_edges;
  const double default_edges =
      lockstep_ ? 4.0 * static_cast<double>(lockstep_edges_) : 400.0 * wall_budget_ms;
  planner_config.max_edges =
      config_.max_edges != 0 ? config_.max_edges
                             : static_cast<std::uint32_t>(std::clamp(default_edges, 2000.0, 2e5));
  planner_config.max_trajectories = planner_config.max_edges / 2;
  CycleConfig cycle_config;
  cycle_config.cycle_s = config_.cycle_s;
  const double margin_ms = config_.margin_s >= 0.0 ? config_.margin_s * 1e3 / time_scale
                                                   : default_safety_margin_ms(wall_budget_ms);
  if (margin_ms >= wall_budget_ms && !lockstep_) {
    return invalid_argument(
        "the budget (" + std::to_string(wall_budget_ms) +
        " ms of wall clock) leaves no time to grow the tree after a margin of " +
        std::to_string(margin_ms) + " ms");
  }
  // Exploring, committing chooses the plan by a pass over the whole tree (PathSelector); the
  // cycle learns what committing costs, and until it has measured one, takes 1 us per pool
  // edge (the reserve of the sessions before: committing took 2 to 3 ms at time scale 2).
  if (explore) {
    cycle_config.commit_reserve_prior_ns =
        static_cast<std::int64_t>(planner_config.max_edges) * 1'000;
  }
  cycle_config.safety_margin_ns = static_cast<std::int64_t>(margin_ms * 1e6);
  // Exploring, rho comes with each target (ExplorationTarget::rho); in real time the target
  // thread takes a cycle, so the planner's own refresh is only a fallback for a late target.
  cycle_config.rho_refresh_cycles =
      explore && !lockstep_ ? 2 * config_.target_refresh_cycles + 1 : config_.target_refresh_cycles;
  auto cycle = ReplanningCycle<V>::create(vehicle_, *grid_, planner_config, cycle_config);
  if (!cycle) return cycle.error();
  cycle_.emplace(std::move(cycle).value());
  ledger_.emplace(vehicle_, planner_config.integration_step_s, grip_msg_kMaxPlanSteps);

  // Exploration's fixed memory, sized from the map, also at start-up (a goal may never come).
  const OccupancyGrid& grid = *grid_;
  ExplorationTargetConfig target_config;
  target_config.frontier.clearance_m = planner_config.rho_clearance_m;
  target_config.give_up_after_s = config_.frontier_give_up_s;
  auto target = ExplorationTarget::create(grid, target_config);
  if (!target) return target.error();
  target_.emplace(std::move(target).value());
  PathSelectionConfig selection;
  selection.sensing_radius_m =
      config_.sensing_radius_m > 0.0 ? config_.sensing_radius_m : grid.width_m() / 10.0;
  auto selector = PathSelector::create(grid.width(), grid.height(), grid.resolution(),
                                       planner_config.max_edges, selection);
  if (!selector) return selector.error();
  selector_.emplace(std::move(selector).value());
  return Ok{};
}

template <VehicleModel V>
Result<PlannerParticipantReport> PlannerParticipantFor<V>::run() {
  if (Status s = start_up(); !s) return s.error();
  if (lockstep_) return run_lockstep();
  // The first target is chosen before the first cycle, which would otherwise plan toward the
  // start while the target thread chooses.
  if (exploring_) choose_frontier_target_now();

  PeriodicLoopConfig loop_config;
  const std::int64_t period_wall = period_wall_ns_.load(std::memory_order_relaxed);
  loop_config.period = std::chrono::nanoseconds(period_wall);
  loop_config.budget = std::chrono::nanoseconds(ns_of(config_.budget_s / time_scale_));
  loop_config.policy = config_.policy;
  loop_config.lock_memory = config_.lock_memory;
  loop_config.reference_timer = false;
  loop_config.cycles = config_.duration_s > 0.0
                           ? static_cast<std::uint64_t>(std::llround(
                                 config_.duration_s * 1e9 / static_cast<double>(period_wall)))
                           : std::numeric_limits<std::uint64_t>::max();
  auto loop = PeriodicLoop::start(loop_config, [this](std::int64_t release, std::int64_t deadline) {
    return cycle_body(release, deadline);
  });
  if (!loop) return loop.error();

  PlannerParticipantReport report;
  report.time_scale = time_scale_;
  CycleRecord record;
  std::int64_t next_progress = platform::now_ns();
  while (true) {
    if (stop_.load(std::memory_order_acquire)) (*loop)->request_stop();
    const bool done = (*loop)->finished();
    while ((*loop)->poll(record)) {
      ++report.cycles;
      report.misses += record.missed ? 1 : 0;
      report.wake_latency.record(record.wake_latency_ns);
      report.compute.record(record.compute_ns);
      if (config_.on_cycle) config_.on_cycle(record);
    }
    if (done) break;
    if (config_.on_progress && platform::now_ns() >= next_progress) {
      next_progress += 250'000'000;
      config_.on_progress(progress_line(report));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const PeriodicLoopResult& result = (*loop)->join();
  report.policy = std::string(platform::policy_name(result.planner_thread.scheduling.policy));
  report.policy_fallback = result.planner_thread.scheduling.fallback_reason;
  report.allocations_counted = result.allocations_counted;
  report.heap_allocations_in_loop = result.heap_allocations_in_loop;
  report.usage_in_loop = result.usage_in_loop;
  return final_report(std::move(report));
}

// Lockstep: a cycle for each state the vehicle sends, once the map has every update sensed up
// to it, on this (ordinary) thread: there is no deadline to keep, and none is missed.
template <VehicleModel V>
Result<PlannerParticipantReport> PlannerParticipantFor<V>::run_lockstep() {
  PlannerParticipantReport report;
  report.policy = "lockstep";
  report.time_scale = time_scale_;
  const std::int64_t run_until = config_.duration_s > 0.0
                                     ? platform::now_ns() + ns_of(config_.duration_s)
                                     : std::numeric_limits<std::int64_t>::max();
  const auto cycle_ns = static_cast<std::uint64_t>(ns_of(config_.cycle_s));
  StateSample state = first_state_;  // start-up's state: the first cycle plans for it
  bool have_state = true;
  std::int64_t next_progress = platform::now_ns();
  while (!stop_.load(std::memory_order_acquire) && platform::now_ns() < run_until) {
    if (!have_state) {
      if (!states_->update()) {
        static_cast<void>(lockstep_inputs_.wait(std::chrono::milliseconds(50)));
        continue;
      }
      state = states_->read_buffer();
    }
    have_state = false;
    const std::int64_t start = platform::now_ns();
    MapChanges changes;
    apply_tiles(changes);
    while (map_sequence_ < state.map_sequence && !stop_.load(std::memory_order_acquire)) {
      static_cast<void>(lockstep_inputs_.wait(std::chrono::milliseconds(50)));
      apply_tiles(changes);
    }
    note_vehicle_state(state);
    plan_start_ns_ = state.stamp_ns + cycle_ns;  // t[i] = the state's time + T
    check_vehicle_follows();
    CycleRecord record;
    record.outcome = plan_cycle(start, changes, 0);
    record.cycle = report.cycles++;
    record.release_ns = start;
    record.compute_ns = platform::now_ns() - start;
    report.compute.record(record.compute_ns);
    if (config_.on_cycle) config_.on_cycle(record);
    if (config_.on_progress && platform::now_ns() >= next_progress) {
      next_progress += 250'000'000;
      config_.on_progress(progress_line(report));
    }
  }
  return final_report(std::move(report));
}

template <VehicleModel V>
PlannerParticipantReport PlannerParticipantFor<V>::final_report(PlannerParticipantReport report) {
  if (publish_policy_set_.load(std::memory_order_acquire)) report.publish_policy = publish_policy_;
  report.plans_committed = plans_committed_;
  report.plans_superseded = plans_->published() - plans_published_.load() - write_failures_.load();
  report.plans_published = plans_published_.load();
  report.write_failures = write_failures_.load();
  if (publish_timing_->update()) {
    report.plan_handoff = publish_timing_->read_buffer().handoff;
    report.plan_write = publish_timing_->read_buffer().write;
  }
  report.rejected_vehicle_state = counters_.rejected_vehicle_state.load();
  report.rejected_map_update = counters_.rejected_map_update.load();
  report.rejected_goal = counters_.rejected_goal.load();
  report.map_gaps = counters_.map_gaps.load();
  report.map_heals = counters_.map_heals.load();
  report.vehicle_losses = counters_.vehicle_losses.load();
  report.map_sequence = map_sequence_;
  report.explored = explored_;
  report.resyncs = resyncs_;
  report.map_checksum = map_checksum(*grid_);
  return report;
}

template <VehicleModel V>
PlannerTreePicture PlannerParticipantFor<V>::last_tree() const {
  PlannerTreePicture picture;
  if (!cycle_) return picture;
  const Planner<V>& planner = cycle_->planner();
  const auto& tree = planner.tree();
  planner.visit_edges([&](EdgeHandle, const Edge& edge) {
    auto& line = picture.edges.emplace_back();
    for (int k = edge.first; k <= edge.last; ++k) {
      const auto& q = tree.state(edge.trajectory, static_cast<std::uint32_t>(k));
      line.push_back({state_x(q), state_y(q)});
    }
  });
  planner.visit_path(cycle_->committed(), [&](const State& q) {
    picture.plan.push_back({state_x(q), state_y(q)});
  });
  return picture;
}

template <VehicleModel V>
std::string PlannerParticipantFor<V>::progress_line(const PlannerParticipantReport& r) const {
  char line[256];
  std::snprintf(line, sizeof line,
                "cycles %llu, misses %llu, plans %llu, map seq %llu%s, rejected %llu, vehicle %s",
                static_cast<unsigned long long>(r.cycles),
                static_cast<unsigned long long>(r.misses),
                static_cast<unsigned long long>(plans_published_.load()),
                static_cast<unsigned long long>(map_sequence_), map_in_sync_ ? "" : " (healing)",
                static_cast<unsigned long long>(counters_.rejected_vehicle_state.load() +
                                                counters_.rejected_map_update.load() +
                                                counters_.rejected_goal.load()),
                counters_.vehicle_alive.load() ? "alive" : "lost");
  return line;
}

}  // namespace

Result<std::unique_ptr<PlannerParticipant>> PlannerParticipant::create(
    const PlannerParticipantConfig& config) {
  return with_default_vehicle(config.robot, [&](const auto& vehicle) {
    using V = std::remove_cvref_t<decltype(vehicle)>;
    return PlannerParticipantFor<V>::create(config, vehicle);
  });
}

}  // namespace grip::rt::dds
