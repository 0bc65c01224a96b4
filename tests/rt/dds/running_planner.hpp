#pragma once
// The planner participant as its tests run it: a configuration for loopback tests, the
// participant running on a thread of its own, and waiting for a condition while the vehicle's
// side does its periodic duties.

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include "grip/rt/dds/planner_participant.hpp"
#include "private_topics.hpp"
#include "vehicle_side.hpp"

namespace grip::rt::dds::testing {

inline PlannerParticipantConfig planner_config(platform::dds::DomainId domain, double duration_s) {
  PlannerParticipantConfig config;
  config.domain = domain;
  config.topic_prefix = ::grip::testing::private_topic_prefix();
  config.vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
  config.cycle_s = 0.05;
  config.budget_s = 0.02;
  config.duration_s = duration_s;
  config.startup_timeout = std::chrono::seconds(20);
  config.lock_memory = false;  // a test does not pin the whole test binary in RAM
  config.liveliness_lease = std::chrono::milliseconds(500);
  return config;
}

// Runs the participant on its own thread; its report (or error) is there after join().
struct RunningPlanner {
  std::unique_ptr<PlannerParticipant> planner;
  std::optional<Result<PlannerParticipantReport>> result;
  std::atomic<bool> returned{false};  // run() has returned: result is set
  std::thread thread;

  explicit RunningPlanner(const PlannerParticipantConfig& config) {
    auto created = PlannerParticipant::create(config);
    if (!created) {
      result = created.error();
      returned = true;
      return;
    }
    planner = std::move(created).value();
    thread = std::thread([this] {
      result = planner->run();
      returned = true;
    });
  }
  const Result<PlannerParticipantReport>& join() {
    if (thread.joinable()) thread.join();
    return *result;
  }
  // Asks the participant to stop and waits for its report.
  const Result<PlannerParticipantReport>& stop() {
    if (planner) planner->request_stop();
    return join();
  }
  ~RunningPlanner() {
    if (planner) planner->request_stop();
    if (thread.joinable()) thread.join();
  }
};

// Whether `done` came true within `timeout`, the vehicle (if any) serviced every 10 ms.
template <typename Predicate>
bool eventually(Predicate done, std::chrono::milliseconds timeout,
                link::testing::VehicleSide* vehicle = nullptr) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    if (vehicle != nullptr) vehicle->service();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

}  // namespace grip::rt::dds::testing
