// Two processes over the loopback interface (UDP on lo, no multicast): the test spawns the
// writer program (tests/dds/probe/plan_writer.cpp) as a child. Within one process Cyclone has
// one instance per domain and delivers locally, so only this test exercises the wire.
// The child also proves liveliness across processes: the parent kills it with SIGKILL and the
// reader must see the writer's lease expire.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "cross_process_plan.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "plan.h"
#include "private_topics.hpp"
#include "test_paths.hpp"

namespace grip::platform::dds {
namespace {

using namespace std::chrono_literals;

using namespace cross_process;

TEST(DdsCrossProcess, PlansCrossLoopbackAndAKilledWriterIsNoticed) {
  std::string writer_program = GRIP_BINARY_DIR "/bin/grip_dds_plan_writer";
  ASSERT_EQ(access(writer_program.c_str(), X_OK), 0) << writer_program;

  Result<Participant> participant = Participant::create(kDomain);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  auto reader = Reader<grip_msg_Plan>::create(
      *participant, &grip_msg_Plan_desc, ::grip::testing::private_topic("grip_plan"), plan_qos());
  ASSERT_TRUE(reader.ok()) << reader.error().message;

  auto child = grip::testing::ChildProcess::spawn({writer_program});
  ASSERT_TRUE(child.has_value()) << writer_program;

  ASSERT_TRUE(reader->wait_for_writers(1, 10s).ok()) << "child writer never matched";

  SampleBuffer<grip_msg_Plan, 8> buffer(&grip_msg_Plan_desc);
  std::size_t received = 0;
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (received < kPlans && std::chrono::steady_clock::now() < deadline) {
    Result<std::size_t> taken = reader->take(buffer);
    ASSERT_TRUE(taken.ok()) << taken.error().message;
    for (std::size_t i = 0; i < *taken; ++i, ++received) {
      const grip_msg_Plan& plan = buffer[i];
      ASSERT_EQ(plan.cycle, received) << "plans out of order";
      EXPECT_EQ(plan.start_time_ns, 5'000'000ULL * received);
      EXPECT_EQ(plan.kind, grip_msg_DD_ACCELERATION);
      EXPECT_EQ(plan.contingency, grip_msg_BRAKE_STRAIGHT);
      ASSERT_EQ(plan.steps._length, kSteps);
      for (std::size_t s = 0; s < kSteps; ++s) {
        ASSERT_EQ(plan.steps._buffer[s].control[0], control_value(received, s, 0));
        ASSERT_EQ(plan.steps._buffer[s].control[1], control_value(received, s, 1));
        ASSERT_EQ(plan.steps._buffer[s].duration_s, 0.02);
      }
    }
    if (*taken == 0) std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(received, kPlans);

  auto before = reader->liveliness_changed();
  ASSERT_TRUE(before.ok());
  EXPECT_EQ(before->alive_count, 1U);

  // Kill the writer's process: no goodbye messages, only the lease (500 ms) can tell.
  child->kill(SIGKILL);
  const auto killed_at = std::chrono::steady_clock::now();
  bool noticed = false;
  while (!noticed && std::chrono::steady_clock::now() - killed_at < 5s) {
    auto status = reader->liveliness_changed();
    ASSERT_TRUE(status.ok());
    noticed = status->alive_count == 0;
    if (!noticed) std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(noticed) << "killed writer not noticed through liveliness within 5 s";
}

}  // namespace
}  // namespace grip::platform::dds
