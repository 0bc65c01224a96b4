// The writer side of the cross-process DDS test: sends the agreed plans, then waits to be
// killed (the test checks that liveliness notices).

#include <cstdio>
#include <thread>
#include <vector>

#include "../cross_process_plan.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/writer.hpp"
#include "plan.h"
#include "private_topics.hpp"

int main() {
  using namespace grip::platform::dds;
  using namespace grip::platform::dds::cross_process;
  grip::Result<Participant> participant = Participant::create(kDomain);
  if (!participant) {
    std::fprintf(stderr, "plan_writer: %s\n", participant.error().message.c_str());
    return 1;
  }
  auto writer = Writer<grip_msg_Plan>::create(
      *participant, &grip_msg_Plan_desc, ::grip::testing::private_topic("grip_plan"), plan_qos());
  if (!writer || !writer->wait_for_readers(1, 10s).ok()) {
    std::fprintf(stderr, "plan_writer: no writer or no reader matched\n");
    return 1;
  }
  std::vector<grip_msg_PlanStep> steps(kSteps);
  for (std::size_t p = 0; p < kPlans; ++p) {
    for (std::size_t s = 0; s < kSteps; ++s) {
      steps[s] = grip_msg_PlanStep{{control_value(p, s, 0), control_value(p, s, 1)}, 0.02};
    }
    grip_msg_Plan plan{};
    plan.cycle = p;
    plan.start_time_ns = 5'000'000ULL * p;
    plan.kind = grip_msg_DD_ACCELERATION;
    plan.contingency = grip_msg_BRAKE_STRAIGHT;
    plan.steps._buffer = steps.data();
    plan.steps._length = static_cast<std::uint32_t>(kSteps);
    plan.steps._maximum = static_cast<std::uint32_t>(kSteps);
    if (!writer->write(plan).ok()) return 1;
  }
  // Stay alive until the test kills us (bounded, in case the test died).
  std::this_thread::sleep_for(30s);
  return 0;
}
