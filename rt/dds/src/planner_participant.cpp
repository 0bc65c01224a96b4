#include "grip/rt/dds/planner_participant.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <thread>
#include <utility>

#include "description_watch.hpp"
#include "goal.h"
#include "grip/link/incarnation.hpp"
#include "grip/link/topics.hpp"
#include "grip/platform/clock.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/waitset.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/platform/thread.hpp"
#include "grip/platform/wakeup.hpp"
#include "grip/rt/liveness_beat.hpp"
#include "grip/rt/periodic_loop.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "handoff.hpp"
#include "map_update.h"
#include "participant_threads.hpp"
#include "plan.h"
#include "planner_status.h"
#include "planning_side.hpp"
#include "publish_side.hpp"
#include "receive_side.hpp"
#include "vehicle_description.h"
#include "vehicle_state.h"

namespace grip::rt::dds {

namespace {

namespace pdds = platform::dds;

std::int64_t ns_of(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }

// The participant's DDS entities; the participant is their one owner.
struct Entities {
  pdds::Participant participant;
  pdds::Reader<grip_msg_VehicleState> states;
  pdds::Reader<grip_msg_MapUpdate> maps;
  pdds::Reader<grip_msg_Goal> goals;
  pdds::Reader<grip_msg_VehicleDescription> descriptions;
  pdds::Writer<grip_msg_MapRequest> requests;
  pdds::Writer<grip_msg_Plan> plans;
  pdds::Writer<grip_msg_PlannerStatus> status;
  pdds::WaitSet waitset;

  static Result<Entities> create(const PlannerParticipantConfig& config) {
    link::LinkTiming timing;
    timing.cycle = std::chrono::nanoseconds(ns_of(config.cycle_s));
    timing.liveliness_lease = config.liveliness_lease;
    auto topics = link::TopicNames::create(config.topic_prefix);
    if (!topics) return topics.error();
    auto participant = pdds::Participant::create(config.domain, config.dds_config, config.security);
    if (!participant) return participant.error();
    auto states = pdds::Reader<grip_msg_VehicleState>::create(
        *participant, &grip_msg_VehicleState_desc, topics->vehicle_state,
        link::vehicle_state_qos(timing, link::Endpoint::kReader));
    if (!states) return states.error();
    auto maps = pdds::Reader<grip_msg_MapUpdate>::create(
        *participant, &grip_msg_MapUpdate_desc, topics->map_update, link::map_update_qos(timing));
    if (!maps) return maps.error();
    auto goals = pdds::Reader<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc,
                                                     topics->goal, link::goal_qos(timing));
    if (!goals) return goals.error();
    auto descriptions = pdds::Reader<grip_msg_VehicleDescription>::create(
        *participant, &grip_msg_VehicleDescription_desc, topics->vehicle_description,
        link::vehicle_description_qos(timing));
    if (!descriptions) return descriptions.error();
    auto requests = pdds::Writer<grip_msg_MapRequest>::create(
        *participant, &grip_msg_MapRequest_desc, topics->map_request,
        link::map_request_qos(timing));
    if (!requests) return requests.error();
    auto plans =
        pdds::Writer<grip_msg_Plan>::create(*participant, &grip_msg_Plan_desc, topics->plan,
                                            link::plan_qos(timing, link::Endpoint::kWriter));
    if (!plans) return plans.error();
    auto status = pdds::Writer<grip_msg_PlannerStatus>::create(
        *participant, &grip_msg_PlannerStatus_desc, topics->planner_status,
        link::planner_status_qos(timing));
    if (!status) return status.error();
    auto waitset = pdds::WaitSet::create(*participant);
    if (!waitset) return waitset.error();
    for (const dds_entity_t reader :
         {states->get(), maps->get(), goals->get(), descriptions->get()}) {
      if (Status s = waitset->attach_data_available(reader); !s) return s.error();
    }
    return Entities{std::move(participant).value(),  std::move(states).value(),
                    std::move(maps).value(),         std::move(goals).value(),
                    std::move(descriptions).value(), std::move(requests).value(),
                    std::move(plans).value(),        std::move(status).value(),
                    std::move(waitset).value()};
  }
};

// The wake-ups between threads: the publish thread's, lockstep inputs (a state or map tiles
// were handed over), a frontier target requested.
struct Wakeups {
  platform::Wakeup publish;
  platform::Wakeup lockstep_inputs;
  platform::Wakeup target_wanted;

  static Result<Wakeups> create() {
    auto publish = platform::Wakeup::create();
    if (!publish) return publish.error();
    auto lockstep_inputs = platform::Wakeup::create();
    if (!lockstep_inputs) return lockstep_inputs.error();
    auto target_wanted = platform::Wakeup::create();
    if (!target_wanted) return target_wanted.error();
    return Wakeups{std::move(publish).value(), std::move(lockstep_inputs).value(),
                   std::move(target_wanted).value()};
  }
};

// A service thread from the table (participant_threads.hpp), named before its body runs.
template <typename Body>
std::thread start_service_thread(const ParticipantThread& spec, Body body) {
  return std::thread([name = spec.name, body]() mutable {
    static_cast<void>(platform::set_thread_name(name));
    body();
  });
}

template <VehicleModel V>
class PlannerParticipantFor final : public PlannerParticipant {
 public:
  PlannerParticipantFor(const PlannerParticipantConfig& config, const V& vehicle, Entities entities,
                        Wakeups wakeups)
      : config_(config),
        dds_(std::move(entities)),
        wakeups_(std::move(wakeups)),
        vehicle_(vehicle),
        receive_(
            vehicle, config.vehicle,
            {dds_.states, dds_.maps, dds_.goals, dds_.descriptions, dds_.requests, dds_.waitset},
            handoffs_, wakeups_.lockstep_inputs, config.max_map_cells,
            config.liveliness_lease.count(), incarnation_, config.on_warning),
        publish_(V::kKind, incarnation_, {dds_.plans, dds_.status}, handoffs_, wakeups_.publish,
                 receive_.counters(), receive_.clock()),
        planning_(new_planning_side()),
        alive_(config.on_alive ? config.alive_interval.count() : 0) {}
  ~PlannerParticipantFor() override;

  // Service threads start now: before any SCHED_DEADLINE thread, which could not create them.
  void start_service_threads();
  Result<PlannerParticipantReport> run() override;
  PlannerTreePicture last_tree() const override { return planning_->tree_picture(); }

 private:
  Status start_up();
  std::unique_ptr<PlanningSide<V>> new_planning_side() {
    return std::make_unique<PlanningSide<V>>(config_, vehicle_, handoffs_, wakeups_.publish,
                                             wakeups_.target_wanted, receive_.clock());
  }
  // The vehicle planned for was replaced by a new incarnation (a restarted vehicle side).
  bool vehicle_replaced() const noexcept {
    const std::uint64_t followed =
        receive_.counters().vehicle_incarnation.load(std::memory_order_acquire);
    return planning_->vehicle_incarnation() != 0 && followed != planning_->vehicle_incarnation();
  }
  // Planning anew (a new vehicle, or a map the planner refused): a fresh planning side, the
  // target thread paused meanwhile, since it serves the planning side's requests.
  void reset_planning();
  void start_target_thread();
  // Start-up: the planner cannot plan on the vehicle's map (`why`): refused and counted, and
  // start-up waits for another.
  void refuse_map(const link::MapGeometry& geometry, const Error& why);
  // Ok while the vehicle has not described itself differently from config_.vehicle.
  Status vehicle_accepted() const {
    const DescriptionWatch& description = receive_.description();
    if (description.verdict() != Described::kDiffers) return Ok{};
    return Error{ErrorCode::kInvalidArgument, description.mismatch()};
  }
  Result<PlannerParticipantReport> run_real_time();
  Result<PlannerParticipantReport> run_lockstep();
  void target_main();
  PlannerParticipantReport final_report(PlannerParticipantReport report);
  std::string progress_line(const PlannerParticipantReport& report) const;
  // Run loops: tells the watchdog planning is alive when cycles completed (liveness_beat.hpp).
  void beat(std::uint64_t cycles) {
    if (alive_.due(platform::now_ns(), cycles)) config_.on_alive();
  }

  PlannerParticipantConfig config_;
  Entities dds_;
  Wakeups wakeups_;
  Handoffs handoffs_;
  std::atomic<bool> threads_stop_{false};
  V vehicle_;
  const std::uint64_t incarnation_ = link::new_incarnation();  // stamped on plans and status
  ReceiveSide<V> receive_;
  PublishSide publish_;
  std::unique_ptr<PlanningSide<V>> planning_;
  std::atomic<bool> target_stop_{false};
  VehicleSample first_state_;  // the state start-up planned from
  // The first start-up's: from its beginning to the map in sync, and to planning.
  std::int64_t map_sync_ns_ = -1;
  std::int64_t startup_ns_ = -1;
  LivenessBeat alive_;
  std::thread receive_thread_;
  std::thread publish_thread_;
  std::thread target_thread_;
};

template <VehicleModel V>
void PlannerParticipantFor<V>::start_service_threads() {
  receive_thread_ =
      start_service_thread(kReceiveThread, [this] { receive_.run(threads_stop_, stop_); });
  publish_thread_ = start_service_thread(kPublishThread, [this] { publish_.run(threads_stop_); });
  start_target_thread();
}

template <VehicleModel V>
void PlannerParticipantFor<V>::start_target_thread() {
  target_stop_.store(false, std::memory_order_release);
  target_thread_ = start_service_thread(kTargetThread, [this] { target_main(); });
}

template <VehicleModel V>
void PlannerParticipantFor<V>::reset_planning() {
  target_stop_.store(true, std::memory_order_release);
  wakeups_.target_wanted.signal();
  if (target_thread_.joinable()) target_thread_.join();
  planning_ = new_planning_side();
  receive_.hand_over_map_again();
  start_target_thread();
}

template <VehicleModel V>
void PlannerParticipantFor<V>::refuse_map(const link::MapGeometry& geometry, const Error& why) {
  receive_.refuse_geometry(geometry);
  reset_planning();
  const std::string line = "rejected map update: the planner cannot plan on its geometry (" +
                           std::to_string(geometry.width_cells) + " x " +
                           std::to_string(geometry.height_cells) + " cells of " +
                           std::to_string(geometry.resolution_m) + " m): " + why.message;
  if (config_.on_warning) {
    config_.on_warning(line);
  } else {
    std::fprintf(stderr, "grip planner: %s\n", line.c_str());
  }
}

template <VehicleModel V>
PlannerParticipantFor<V>::~PlannerParticipantFor() {
  threads_stop_.store(true, std::memory_order_release);
  static_cast<void>(dds_.waitset.wake());
  wakeups_.publish.signal();
  wakeups_.target_wanted.signal();
  if (receive_thread_.joinable()) receive_thread_.join();
  if (publish_thread_.joinable()) publish_thread_.join();
  if (target_thread_.joinable()) target_thread_.join();
}

template <VehicleModel V>
void PlannerParticipantFor<V>::target_main() {
  while (!threads_stop_.load(std::memory_order_acquire) &&
         !target_stop_.load(std::memory_order_acquire)) {
    static_cast<void>(wakeups_.target_wanted.wait(std::chrono::milliseconds(100)));
    static_cast<void>(planning_->serve_target_request());
  }
}

// The planner waits for the vehicle's description to match its own parameters (a mismatch ends
// start-up with it), the map to be in sync, a vehicle state and a goal (or, without a goal
// within the grace period after the map, explores), then sizes the planner: all allocation
// happens here. run()'s thread is the tiles' consumer until planning starts.
template <VehicleModel V>
Status PlannerParticipantFor<V>::start_up() {
  const std::int64_t started = platform::now_ns();
  const std::int64_t timeout = config_.startup_timeout.count();
  std::optional<VehicleSample> state;
  std::optional<Goal> goal;
  std::int64_t synced_at = -1;  // when the map was first in sync; -1: not yet
  std::string refusal;
  std::string map_refusal;  // why the map's geometry was refused
  std::int64_t next_report = started;
  while (!stop_.load(std::memory_order_acquire)) {
    if (Status s = vehicle_accepted(); !s) return s;
    const bool described = receive_.description().verdict() == Described::kMatches;
    // The vehicle planned for: the one the receive side follows; a new one starts over.
    const std::uint64_t vehicle =
        receive_.counters().vehicle_incarnation.load(std::memory_order_acquire);
    if (vehicle != planning_->vehicle_incarnation()) {
      if (planning_->vehicle_incarnation() != 0) {
        reset_planning();
        state.reset();
        synced_at = -1;
      }
      planning_->set_vehicle(vehicle);
    }
    // The map once the vehicle it is of is known: tiles of another are dropped.
    if (!planning_->has_map() && planning_->vehicle_incarnation() != 0 &&
        receive_.geometry_ready()) {
      const link::MapGeometry geometry = receive_.geometry();
      if (Status s = planning_->create_map(geometry); !s) {
        map_refusal = s.error().message;
        refuse_map(geometry, s.error());
        planning_->set_vehicle(vehicle);
        continue;
      }
    }
    if (planning_->has_map()) {
      MapChanges ignored;  // no tree yet
      planning_->apply_tiles(ignored);
    }
    if (handoffs_.states->update() &&
        handoffs_.states->read_buffer().incarnation == planning_->vehicle_incarnation()) {
      state = handoffs_.states->read_buffer();
    }
    if (handoffs_.goals->update()) goal = handoffs_.goals->read_buffer();
    const bool in_sync = planning_->has_map() && planning_->map_in_sync();
    if (in_sync && synced_at < 0) synced_at = platform::now_ns();
    const bool explore = !goal && config_.explore_without_goal && synced_at >= 0 &&
                         platform::now_ns() - synced_at >= config_.goal_grace.count();
    if (described && in_sync && state && (goal || explore)) {
      if (!planning_->prepared()) {
        if (Status s = planning_->prepare(*state, explore); !s) {
          map_refusal = s.error().message;
          refuse_map(receive_.geometry(), s.error());
          planning_->set_vehicle(vehicle);
          synced_at = -1;
          continue;
        }
        publish_.set_time_scale(planning_->time_scale());
      }
      const Status s = planning_->start(*state, goal);
      if (s.ok()) {
        first_state_ = *state;
        if (startup_ns_ < 0) {
          map_sync_ns_ = synced_at - started;
          startup_ns_ = platform::now_ns() - started;
        }
        return Ok{};
      }
      refusal = s.error().message;  // e.g. the start is not known free yet
    }
    const auto missing = [&] {
      std::string what;
      if (!described) what += " a vehicle description (the vehicle did not describe itself),";
      if (!in_sync) {
        what += map_refusal.empty()
                    ? " a map in sync,"
                    : " a map it can use (its geometry was refused: " + map_refusal + "),";
      }
      if (!state) what += " a vehicle state,";
      if (!goal && !config_.explore_without_goal) what += " a goal,";
      if (!goal && config_.explore_without_goal && !explore) {
        what += " a goal or the end of the goal's grace period (then it explores),";
      }
      if (what.empty()) {
        what = refusal.empty() ? " the planner to start,"
                               : " a start the planner accepts (" + refusal + "),";
      }
      what.pop_back();
      return what;
    };
    const std::int64_t now = platform::now_ns();
    if (timeout > 0 && now - started > timeout) {
      return Error{ErrorCode::kIo, "start-up timed out waiting for" + missing()};
    }
    // A start-up that takes long says what it waits for (an operator sees why), every 10 s.
    if (config_.on_progress && now >= next_report) {
      if (next_report > started) config_.on_progress("start-up: waiting for" + missing());
      next_report = now + 10'000'000'000;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return Error{ErrorCode::kIo, "stopped during start-up"};
}

template <VehicleModel V>
Result<PlannerParticipantReport> PlannerParticipantFor<V>::run() {
  // Start-up, then planning, again for each new vehicle incarnation (a restarted vehicle side).
  for (;;) {
    if (Status s = start_up(); !s) return s.error();
    if (config_.on_ready) {
      config_.on_ready(std::string("planning (") +
                       (planning_->lockstep() ? "lockstep" : "real time") +
                       "): vehicle described as configured, map in sync, vehicle state received");
    }
    planning_->choose_first_target();
    auto report = planning_->lockstep() ? run_lockstep() : run_real_time();
    if (!report || stop_.load(std::memory_order_acquire) || !vehicle_replaced()) return report;
    reset_planning();
  }
}

// Real time: one cycle per period on the planning thread (rt::PeriodicLoop), whose records this
// thread collects.
template <VehicleModel V>
Result<PlannerParticipantReport> PlannerParticipantFor<V>::run_real_time() {
  PeriodicLoopConfig loop_config;
  const std::int64_t period_wall = planning_->period_wall_ns();
  loop_config.name = kPlanningThread.name;
  loop_config.period = std::chrono::nanoseconds(period_wall);
  loop_config.budget = std::chrono::nanoseconds(ns_of(config_.budget_s / planning_->time_scale()));
  loop_config.policy = config_.policy;
  loop_config.fifo_priority = config_.fifo_priority;
  loop_config.cpu = config_.cpu;
  loop_config.lock_memory = config_.lock_memory;
  loop_config.reference_timer = false;
  loop_config.cycles = config_.duration_s > 0.0
                           ? static_cast<std::uint64_t>(std::llround(
                                 config_.duration_s * 1e9 / static_cast<double>(period_wall)))
                           : std::numeric_limits<std::uint64_t>::max();
  auto loop = PeriodicLoop::start(loop_config, [this](std::int64_t release, std::int64_t deadline) {
    return planning_->cycle_body(release, deadline);
  });
  if (!loop) return loop.error();

  PlannerParticipantReport report;
  report.time_scale = planning_->time_scale();
  CycleRecord record;
  std::int64_t next_progress = platform::now_ns();
  Status accepted = Ok{};
  while (true) {
    accepted = vehicle_accepted();  // a new vehicle, described otherwise: planning stops
    if (stop_.load(std::memory_order_acquire) || !accepted || vehicle_replaced()) {
      (*loop)->request_stop();
    }
    const bool done = (*loop)->finished();
    while ((*loop)->poll(record)) {
      ++report.cycles;
      report.misses += record.missed ? 1 : 0;
      report.wake_latency.record(record.wake_latency_ns);
      report.compute.record(record.compute_ns);
      if (config_.on_cycle) config_.on_cycle(record);
    }
    if (done) break;
    beat(report.cycles);
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
  if (!accepted) return accepted.error();
  return final_report(std::move(report));
}

// Lockstep: a cycle for each state the vehicle sends, once the map has every update sensed up
// to it, on this (ordinary) thread: there is no deadline to keep, and none is missed.
template <VehicleModel V>
Result<PlannerParticipantReport> PlannerParticipantFor<V>::run_lockstep() {
  PlannerParticipantReport report;
  report.policy = "lockstep";
  report.time_scale = planning_->time_scale();
  const std::int64_t run_until = config_.duration_s > 0.0
                                     ? platform::now_ns() + ns_of(config_.duration_s)
                                     : std::numeric_limits<std::int64_t>::max();
  VehicleSample state = first_state_;  // start-up's state: the first cycle plans for it
  bool have_state = true;
  std::int64_t next_progress = platform::now_ns();
  while (!stop_.load(std::memory_order_acquire) && platform::now_ns() < run_until &&
         !vehicle_replaced()) {
    // A new vehicle, described otherwise: planning stops.
    if (Status s = vehicle_accepted(); !s) return s.error();
    beat(report.cycles);  // no state from the vehicle, no cycle, no beat
    if (!have_state) {
      if (!handoffs_.states->update()) {
        static_cast<void>(wakeups_.lockstep_inputs.wait(std::chrono::milliseconds(50)));
        continue;
      }
      state = handoffs_.states->read_buffer();
      if (state.incarnation != planning_->vehicle_incarnation()) continue;  // replaced: ends
    }
    have_state = false;
    // Released by the state; woken once the map holds every update sensed up to it. The time
    // blocked for tiles still on their way is the simulator's and the link's, not the cycle's.
    const std::int64_t release = platform::now_ns();
    std::int64_t blocked = 0;
    MapChanges changes;
    planning_->apply_tiles(changes);
    while (planning_->map_sequence() < state.map_sequence &&
           !stop_.load(std::memory_order_acquire) && !vehicle_replaced()) {
      const std::int64_t waiting = platform::now_ns();
      static_cast<void>(wakeups_.lockstep_inputs.wait(std::chrono::milliseconds(50)));
      blocked += platform::now_ns() - waiting;
      planning_->apply_tiles(changes);
    }
    const std::int64_t start = release + blocked;
    CycleRecord record;
    record.outcome = planning_->lockstep_cycle(state, changes, start);
    record.cycle = report.cycles++;
    record.release_ns = release;
    record.wake_latency_ns = blocked;
    record.compute_ns = platform::now_ns() - start;
    report.wake_latency.record(record.wake_latency_ns);
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
  const PublishCounts publish = publish_.counts();
  report.publish_policy = publish.policy;
  report.plans_superseded =
      handoffs_.plans->published() - publish.published - publish.write_failures;
  report.plans_published = publish.published;
  report.write_failures = publish.write_failures;
  report.plans_rewritten = publish.rewritten;
  if (handoffs_.publish_timing->update()) {
    report.plan_handoff = handoffs_.publish_timing->read_buffer().handoff;
    report.plan_write = handoffs_.publish_timing->read_buffer().write;
  }
  const ReceiveCounters& counters = receive_.counters();
  report.rejected_vehicle_state = counters.rejected_vehicle_state.load();
  report.rejected_map_update = counters.rejected_map_update.load();
  report.rejected_goal = counters.rejected_goal.load();
  report.map_gaps = counters.map_gaps.load();
  report.map_heals = counters.map_heals.load();
  report.vehicle_losses = counters.vehicle_losses.load();
  report.vehicle_restarts = counters.vehicle_restarts.load();
  report.map_sync_s = static_cast<double>(map_sync_ns_) * 1e-9;
  report.startup_s = static_cast<double>(startup_ns_) * 1e-9;
  planning_->fill_report(report);
  return report;
}

template <VehicleModel V>
std::string PlannerParticipantFor<V>::progress_line(const PlannerParticipantReport& r) const {
  const ReceiveCounters& counters = receive_.counters();
  char line[256];
  std::snprintf(line, sizeof line,
                "cycles %llu, misses %llu, plans %llu, map seq %llu%s, rejected %llu, vehicle %s",
                static_cast<unsigned long long>(r.cycles),
                static_cast<unsigned long long>(r.misses),
                static_cast<unsigned long long>(publish_.published()),
                static_cast<unsigned long long>(planning_->map_sequence()),
                planning_->map_in_sync() ? "" : " (healing)",
                static_cast<unsigned long long>(counters.rejected_vehicle_state.load() +
                                                counters.rejected_map_update.load() +
                                                counters.rejected_goal.load()),
                counters.vehicle_alive.load() ? "alive" : "lost");
  return line;
}

}  // namespace

Result<std::unique_ptr<PlannerParticipant>> PlannerParticipant::create(
    const PlannerParticipantConfig& config) {
  if (Status s = validate(config.vehicle); !s) return s.error();
  auto entities = Entities::create(config);
  if (!entities) return entities.error();
  auto wakeups = Wakeups::create();
  if (!wakeups) return wakeups.error();
  return with_vehicle(
      config.vehicle, [&](const auto& vehicle) -> Result<std::unique_ptr<PlannerParticipant>> {
        using V = std::remove_cvref_t<decltype(vehicle)>;
        auto self = std::make_unique<PlannerParticipantFor<V>>(
            config, vehicle, std::move(entities).value(), std::move(wakeups).value());
        self->start_service_threads();
        return std::unique_ptr<PlannerParticipant>(std::move(self));
      });
}

}  // namespace grip::rt::dds
