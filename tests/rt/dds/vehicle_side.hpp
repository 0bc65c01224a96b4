#pragma once
// The vehicle controller's side for the planner participant's tests (in-process and as the
// child process tests/rt/dds/probe/vehicle_controller.cpp): a vehicle at rest at the start of
// the "rooms" scene, whose map is known in full, asking for the way to the scene's goal.

#include <cstdint>
#include <memory>
#include <string>

#include "grip/link/vehicle_link.hpp"
#include "grip/platform/clock.hpp"
#include "grip/scenes/scenes.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "private_topics.hpp"

namespace grip::link::testing {

class VehicleSide {
 public:
  // The vehicle `vehicle` describes itself as, on topics with `topic_prefix`.
  static std::unique_ptr<VehicleSide> create(
      platform::dds::DomainId domain, const VehicleParams& vehicle,
      const std::string& topic_prefix = ::grip::testing::private_topic_prefix()) {
    Scene scene = make_scene("rooms").value();
    VehicleLinkConfig config;
    config.domain = domain;
    config.topic_prefix = topic_prefix;
    config.vehicle = vehicle;
    auto link = VehicleLink::create(config, scene.grid);
    if (!link) return nullptr;
    return std::unique_ptr<VehicleSide>(
        new VehicleSide(std::move(scene), vehicle_kind(vehicle), std::move(*link)));
  }
  // The paper's vehicle of `kind`.
  static std::unique_ptr<VehicleSide> create(platform::dds::DomainId domain, VehicleKind kind) {
    return create(domain, default_vehicle_params(kind));
  }

  grip_msg_VehicleState state() const {
    grip_msg_VehicleState msg{};
    msg.stamp_ns = static_cast<std::uint64_t>(platform::now_ns());
    msg.sequence_number = state_sequence_ + 1;
    msg.kind = to_wire(kind_);
    msg.state[0] = scene_.start_x_m;
    msg.state[1] = scene_.start_y_m;
    msg.state[2] = scene_.start_theta_rad;
    msg.state_dim = kind_ == VehicleKind::kDdVelocity ? 3U : 5U;
    msg.time_scale = 1.0;
    return msg;
  }
  // plan_cycle: the plan the vehicle claims to execute, 0 for none (it rests).
  bool publish_state(std::uint64_t plan_cycle = 0) {
    grip_msg_VehicleState msg = state();
    msg.plan_cycle = plan_cycle;
    state_sequence_ = msg.sequence_number;
    return link_->publish_state(msg).ok();
  }
  bool publish_goal() {
    grip_msg_Goal goal{};
    goal.sequence_number = 1;
    goal.stamp_ns = static_cast<std::uint64_t>(platform::now_ns());
    goal.x_m = scene_.goal_x_m;
    goal.y_m = scene_.goal_y_m;
    goal.radius_m = scene_.goal_radius_m;
    return link_->publish_goal(goal).ok();
  }
  // Periodic duties: the state, and snapshots for whoever asked.
  void service(std::uint64_t plan_cycle = 0) {
    publish_state(plan_cycle);
    link_->answer_map_requests(static_cast<std::uint64_t>(platform::now_ns()));
  }

  VehicleLink& link() { return *link_; }
  const Scene& scene() const { return scene_; }

 private:
  VehicleSide(Scene scene, VehicleKind kind, std::unique_ptr<VehicleLink> link)
      : scene_(std::move(scene)), kind_(kind), link_(std::move(link)) {}

  Scene scene_;
  VehicleKind kind_;
  std::unique_ptr<VehicleLink> link_;
  std::uint64_t state_sequence_ = 0;
};

}  // namespace grip::link::testing
