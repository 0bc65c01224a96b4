#include "grip/link/vehicle_link.hpp"

#include <chrono>
#include <cstdio>
#include <utility>

namespace grip::link {

namespace pdds = platform::dds;

Result<VehicleLink::Entities> VehicleLink::Entities::create(const VehicleLinkConfig& config) {
  auto topics = TopicNames::create(config.topic_prefix);
  if (!topics) return topics.error();
  auto participant = pdds::Participant::create(config.domain, config.dds_config, config.security);
  if (!participant) return participant.error();
  const LinkTiming& timing = config.timing;
  auto description = publish_vehicle_description(*participant, *topics, timing, config.vehicle);
  if (!description) return description.error();
  auto states = pdds::Writer<grip_msg_VehicleState>::create(
      *participant, &grip_msg_VehicleState_desc, topics->vehicle_state,
      vehicle_state_qos(timing, Endpoint::kWriter));
  if (!states) return states.error();
  auto maps = pdds::Writer<grip_msg_MapUpdate>::create(*participant, &grip_msg_MapUpdate_desc,
                                                       topics->map_update, map_update_qos(timing));
  if (!maps) return maps.error();
  auto goals = pdds::Writer<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc, topics->goal,
                                                   goal_qos(timing));
  if (!goals) return goals.error();
  auto requests = pdds::Reader<grip_msg_MapRequest>::create(
      *participant, &grip_msg_MapRequest_desc, topics->map_request, map_request_qos(timing));
  if (!requests) return requests.error();
  auto plans = pdds::Reader<grip_msg_Plan>::create(*participant, &grip_msg_Plan_desc, topics->plan,
                                                   plan_qos(timing, Endpoint::kReader));
  if (!plans) return plans.error();
  auto status = pdds::Reader<grip_msg_PlannerStatus>::create(
      *participant, &grip_msg_PlannerStatus_desc, topics->planner_status,
      planner_status_qos(timing));
  if (!status) return status.error();
  auto waitset = pdds::WaitSet::create(*participant);
  if (!waitset) return waitset.error();
  for (const dds_entity_t reader : {plans->get(), requests->get()}) {
    if (Status s = waitset->attach_data_available(reader); !s) return s.error();
  }
  auto status_waitset = pdds::WaitSet::create(*participant);
  if (!status_waitset) return status_waitset.error();
  if (Status s = status_waitset->attach_data_available(status->get()); !s) return s.error();
  return Entities{std::move(participant).value(), std::move(description).value(),
                  std::move(states).value(),      std::move(maps).value(),
                  std::move(goals).value(),       std::move(requests).value(),
                  std::move(plans).value(),       std::move(status).value(),
                  std::move(waitset).value(),     std::move(status_waitset).value()};
}

Result<std::unique_ptr<VehicleLink>> VehicleLink::create(const VehicleLinkConfig& config,
                                                         OccupancyGrid map) {
  if (Status s = validate(config.vehicle); !s) return s.error();
  auto entities = Entities::create(config);
  if (!entities) return entities.error();
  auto planner_writer = pdds::WriterLiveliness::attach(entities->plans.get());
  if (!planner_writer) return planner_writer.error();
  return std::unique_ptr<VehicleLink>(new VehicleLink(
      config, std::move(map), std::move(entities).value(), std::move(planner_writer).value()));
}

VehicleLink::VehicleLink(const VehicleLinkConfig& config, OccupancyGrid map, Entities entities,
                         std::unique_ptr<pdds::WriterLiveliness> planner_writer)
    : kind_(vehicle_kind(config.vehicle)),
      dds_(std::move(entities)),
      sender_(std::move(map)),
      plan_buffer_(std::make_unique<pdds::SampleBuffer<grip_msg_Plan, kPlanHistoryDepth>>(
          &grip_msg_Plan_desc)),
      request_buffer_(
          std::make_unique<pdds::SampleBuffer<grip_msg_MapRequest, 8>>(&grip_msg_MapRequest_desc)),
      status_buffer_(std::make_unique<pdds::SampleBuffer<grip_msg_PlannerStatus, 4>>(
          &grip_msg_PlannerStatus_desc)),
      incarnation_(new_incarnation()),
      planner_(config.timing.liveliness_lease.count(),
               kHungLeases * config.timing.liveliness_lease.count()),
      planner_writer_(std::move(planner_writer)),
      warn_(config.on_warning) {}

Status VehicleLink::publish_state(const grip_msg_VehicleState& state) {
  grip_msg_VehicleState stamped = state;  // plain data
  stamped.incarnation = incarnation_;
  stamped.plan_incarnation = planner_.followed();
  return dds_.states.write(stamped);
}

bool VehicleLink::from_followed_planner(const grip_msg_Plan& plan, dds_instance_handle_t writer) {
  if (!check_plan(plan, kind_).ok() || plan.incarnation == 0) {
    ++plans_rejected_;
    return false;
  }
  const std::uint64_t before = planner_.followed();
  const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                  std::chrono::steady_clock::now().time_since_epoch())
                                  .count();
  const bool followed_alive = planner_writer_->alive();
  const Peer peer = planner_.observe(plan.incarnation, now_ns, followed_alive);
  if (peer == Peer::kOther) {
    if (plans_other_planner_++ == 0) {
      warn("plans from a second planner (incarnation " + std::to_string(plan.incarnation) +
           ") rejected: following planner " + std::to_string(before));
    }
    return false;
  }
  if (peer == Peer::kNew) planner_writer_->watch(writer);
  if (peer == Peer::kNew && before != 0) {
    warn("planner " + std::to_string(before) +
         (followed_alive ? " hung (alive, silent)" : " gone") + ": following planner " +
         std::to_string(plan.incarnation));
  }
  if (plan.vehicle_incarnation != incarnation_) {
    if (plans_other_vehicle_++ == 0) {
      warn("plans made for an earlier incarnation of this vehicle rejected");
    }
    return false;
  }
  return true;
}

void VehicleLink::warn(const std::string& line) const {
  if (warn_) {
    warn_(line);
  } else {
    std::fprintf(stderr, "grip vehicle link: %s\n", line.c_str());
  }
}

Status VehicleLink::publish_goal(const grip_msg_Goal& goal) { return dds_.goals.write(goal); }

void VehicleLink::send(const grip_msg_MapUpdate& update) {
  grip_msg_MapUpdate stamped = update;  // the cells stay borrowed
  stamped.incarnation = incarnation_;
  if (!dds_.maps.write(stamped).ok()) ++map_writes_failed_;  // a gap to the planner, which heals it
}

void VehicleLink::publish_map_updates(const CellBox& box, std::uint64_t stamp_ns,
                                      FunctionRef<bool(const grip_msg_MapUpdate&)> drop) {
  sender_.send_updates(box, stamp_ns, [&](const grip_msg_MapUpdate& update) {
    if (!drop(update)) send(update);
  });
}

void VehicleLink::publish_map_updates(const CellBox& box, std::uint64_t stamp_ns) {
  const auto keep_all = [](const grip_msg_MapUpdate&) { return false; };
  publish_map_updates(box, stamp_ns, keep_all);
}

void VehicleLink::answer_map_requests(std::uint64_t stamp_ns) {
  bool requested = false;
  for (;;) {
    const Result<std::size_t> taken = dds_.requests.take(*request_buffer_);
    if (!taken.ok() || *taken == 0) break;
    requested = true;
  }
  if (requested) {
    sender_.send_snapshot(stamp_ns, [&](const grip_msg_MapUpdate& update) { send(update); });
  }
}

const grip_msg_Plan* VehicleLink::take_plan() {
  const grip_msg_Plan* newest = nullptr;
  for (;;) {
    const Result<std::size_t> taken = dds_.plans.take(*plan_buffer_);
    if (!taken.ok() || *taken == 0) break;
    for (std::size_t i = 0; i < *taken; ++i) {
      if (from_followed_planner((*plan_buffer_)[i], plan_buffer_->info(i).publication_handle))
        newest = &(*plan_buffer_)[i];
    }
    if (newest != nullptr) break;  // the next take would reuse the buffer under it
  }
  return newest;
}

std::size_t VehicleLink::take_plans(FunctionRef<void(const grip_msg_Plan&)> visit) {
  std::size_t visited = 0;
  for (;;) {
    const Result<std::size_t> taken = dds_.plans.take(*plan_buffer_);
    if (!taken.ok() || *taken == 0) break;
    for (std::size_t i = 0; i < *taken; ++i) {
      if (from_followed_planner((*plan_buffer_)[i], plan_buffer_->info(i).publication_handle)) {
        visit((*plan_buffer_)[i]);
        ++visited;
      }
    }
  }
  return visited;
}

void VehicleLink::wait_for_plan_or_request(std::chrono::nanoseconds timeout) {
  static_cast<void>(dds_.waitset.wait(timeout));
}

std::optional<grip_msg_PlannerStatus> VehicleLink::take_status() {
  std::optional<grip_msg_PlannerStatus> newest;
  for (;;) {
    const Result<std::size_t> taken = dds_.status.take(*status_buffer_);
    if (!taken.ok() || *taken == 0) break;
    // Only the planner followed, about this incarnation: a planner still busy with an earlier
    // run of this vehicle (or a standby) says nothing about this one.
    for (std::size_t i = 0; i < *taken; ++i) {
      const grip_msg_PlannerStatus& s = (*status_buffer_)[i];
      if (!check_planner_status(s).ok()) {
        ++statuses_rejected_;
        continue;
      }
      const bool followed = planner_.followed() == 0 || s.incarnation == planner_.followed();
      if (followed && s.vehicle_incarnation == incarnation_) newest = s;  // plain data
    }
  }
  return newest;
}

std::optional<grip_msg_PlannerStatus> VehicleLink::wait_for_status(
    std::uint64_t min_cycle, std::chrono::nanoseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  std::optional<grip_msg_PlannerStatus> newest;
  for (;;) {
    if (auto s = take_status()) newest = s;
    const auto now = std::chrono::steady_clock::now();
    if ((newest && newest->cycle >= min_cycle) || now >= until) return newest;
    static_cast<void>(dds_.status_waitset.wait(until - now));
  }
}

bool VehicleLink::planner_alive() const {
  const auto live = dds_.plans.liveliness_changed();
  return live.ok() && live->alive_count > 0;
}

}  // namespace grip::link
