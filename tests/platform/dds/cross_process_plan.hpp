#pragma once
// What the two processes of the cross-process DDS test agree on: the domain, the QoS and the
// plans the writer (tests/dds/probe/plan_writer.cpp) sends and the reader checks.

#include <chrono>
#include <cstddef>

#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/qos.hpp"

namespace grip::platform::dds::cross_process {

using namespace std::chrono_literals;

constexpr DomainId kDomain = 62;
constexpr std::size_t kPlans = 20;
constexpr std::size_t kSteps = 300;

inline Qos plan_qos() {
  Qos qos;
  qos.max_blocking_time = 100ms;
  qos.history_depth = 32;
  qos.deadline = 10s;
  qos.liveliness_lease = 500ms;
  return qos;
}

inline double control_value(std::size_t plan, std::size_t step, std::size_t axis) {
  return static_cast<double>(plan) * 1000.0 + static_cast<double>(step) +
         0.5 * static_cast<double>(axis);
}

}  // namespace grip::platform::dds::cross_process
