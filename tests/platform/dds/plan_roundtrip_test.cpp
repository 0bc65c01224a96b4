// Two participants in one process, loopback configuration: plans arrive intact and in order.

#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "plan.h"
#include "private_topics.hpp"

namespace grip::platform::dds {
namespace {

using namespace std::chrono_literals;
constexpr DomainId kDomain = 51;

Qos plan_qos() {
  Qos qos;
  qos.reliable = true;
  qos.max_blocking_time = 100ms;
  qos.history_depth = 32;
  qos.deadline = 10s;
  qos.liveliness_lease = 2s;
  return qos;
}

double control_value(std::size_t plan, std::size_t step, std::size_t axis) {
  return static_cast<double>(plan) * 1000.0 + static_cast<double>(step) +
         0.25 * static_cast<double>(axis);
}

TEST(DdsPlanRoundTrip, TwentyPlansOf300StepsArriveIntactAndInOrder) {
  Result<Participant> sender = Participant::create(kDomain);
  ASSERT_TRUE(sender.ok()) << sender.error().message;
  Result<Participant> receiver = Participant::create(kDomain);
  ASSERT_TRUE(receiver.ok()) << receiver.error().message;

  Result<Reader<grip_msg_Plan>> reader = Reader<grip_msg_Plan>::create(
      *receiver, &grip_msg_Plan_desc, ::grip::testing::private_topic("grip_plan"), plan_qos());
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  Result<Writer<grip_msg_Plan>> writer = Writer<grip_msg_Plan>::create(
      *sender, &grip_msg_Plan_desc, ::grip::testing::private_topic("grip_plan"), plan_qos());
  ASSERT_TRUE(writer.ok()) << writer.error().message;

  Status matched = writer->wait_for_readers(1, 5s);
  ASSERT_TRUE(matched.ok()) << matched.error().message;
  ASSERT_TRUE(reader->wait_for_writers(1, 5s).ok());

  constexpr std::size_t kPlans = 20;
  constexpr std::size_t kSteps = 300;
  std::vector<grip_msg_PlanStep> steps(kSteps);
  for (std::size_t p = 0; p < kPlans; ++p) {
    for (std::size_t s = 0; s < kSteps; ++s) {
      steps[s].control[0] = control_value(p, s, 0);
      steps[s].control[1] = control_value(p, s, 1);
      steps[s].duration_s = 0.01 + 0.001 * static_cast<double>(s);
    }
    grip_msg_Plan plan{};
    plan.cycle = 100 + p;
    plan.start_time_ns = 1'000'000'000ULL * (p + 1);
    plan.kind = grip_msg_CAR;
    plan.contingency = grip_msg_BRAKE_ON_CURVE;
    plan.steps._buffer = steps.data();
    plan.steps._length = static_cast<std::uint32_t>(kSteps);
    plan.steps._maximum = static_cast<std::uint32_t>(kSteps);
    plan.steps._release = false;
    Status written = writer->write(plan);
    ASSERT_TRUE(written.ok()) << written.error().message;
  }

  SampleBuffer<grip_msg_Plan, 8> buffer(&grip_msg_Plan_desc);
  std::size_t received = 0;
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (received < kPlans && std::chrono::steady_clock::now() < deadline) {
    Result<std::size_t> taken = reader->take(buffer);
    ASSERT_TRUE(taken.ok()) << taken.error().message;
    for (std::size_t i = 0; i < *taken; ++i) {
      const grip_msg_Plan& plan = buffer[i];
      const std::size_t p = received;
      ASSERT_LT(p, kPlans);
      EXPECT_EQ(plan.cycle, 100 + p) << "plans out of order";
      EXPECT_EQ(plan.start_time_ns, 1'000'000'000ULL * (p + 1));
      EXPECT_EQ(plan.kind, grip_msg_CAR);
      EXPECT_EQ(plan.contingency, grip_msg_BRAKE_ON_CURVE);
      ASSERT_EQ(plan.steps._length, kSteps);
      for (std::size_t s = 0; s < kSteps; ++s) {
        ASSERT_EQ(plan.steps._buffer[s].control[0], control_value(p, s, 0));
        ASSERT_EQ(plan.steps._buffer[s].control[1], control_value(p, s, 1));
        ASSERT_EQ(plan.steps._buffer[s].duration_s, 0.01 + 0.001 * static_cast<double>(s));
      }
      ++received;
    }
    if (*taken == 0) std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(received, kPlans);
}

TEST(DdsPlanRoundTrip, TakeOnEmptyReaderReturnsZeroWithoutBlocking) {
  Result<Participant> participant = Participant::create(kDomain + 10);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  Result<Reader<grip_msg_Plan>> reader = Reader<grip_msg_Plan>::create(
      *participant, &grip_msg_Plan_desc, ::grip::testing::private_topic("grip_plan"), plan_qos());
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  SampleBuffer<grip_msg_Plan, 4> buffer(&grip_msg_Plan_desc);
  Result<std::size_t> taken = reader->take(buffer);
  ASSERT_TRUE(taken.ok()) << taken.error().message;
  EXPECT_EQ(*taken, 0U);
}

}  // namespace
}  // namespace grip::platform::dds
