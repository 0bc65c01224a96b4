// Two processes over the loopback interface (UDP on lo, no multicast): the parent test spawns
// this test binary again as a child that runs the writer role. Within one process Cyclone has
// one instance per domain and delivers locally, so only this test exercises the wire.
// The child also proves liveliness across processes: the parent kills it with SIGKILL and the
// reader must see the writer's lease expire.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "plan.h"

extern char** environ;

namespace grip::platform::dds {
namespace {

using namespace std::chrono_literals;

constexpr DomainId kDomain = 62;
constexpr std::size_t kPlans = 20;
constexpr std::size_t kSteps = 300;
constexpr const char* kRoleVariable = "GRIP_DDS_TEST_ROLE";

Qos plan_qos() {
  Qos qos;
  qos.max_blocking_time = 100ms;
  qos.history_depth = 32;
  qos.deadline = 10s;
  qos.liveliness_lease = 500ms;
  return qos;
}

double control_value(std::size_t plan, std::size_t step, std::size_t axis) {
  return static_cast<double>(plan) * 1000.0 + static_cast<double>(step) +
         0.5 * static_cast<double>(axis);
}

// The child's role: only runs when the parent test started this binary with the role set.
TEST(DdsCrossProcessRole, PlanWriter) {
  const char* role = std::getenv(kRoleVariable);
  if (role == nullptr || std::strcmp(role, "plan_writer") != 0) {
    GTEST_SKIP() << "child role of DdsCrossProcess, run by it";
  }
  Result<Participant> participant = Participant::create(kDomain);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  auto writer =
      Writer<grip_msg_Plan>::create(*participant, &grip_msg_Plan_desc, "grip_plan", plan_qos());
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, 10s).ok());
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
    ASSERT_TRUE(writer->write(plan).ok());
  }
  // Stay alive until the parent kills us (bounded, in case the parent died).
  std::this_thread::sleep_for(30s);
}

TEST(DdsCrossProcess, PlansCrossLoopbackAndAKilledWriterIsNoticed) {
  std::string self(4096, '\0');
  const ssize_t length = readlink("/proc/self/exe", self.data(), self.size() - 1);
  ASSERT_GT(length, 0);
  self.resize(static_cast<std::size_t>(length));

  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) env_strings.emplace_back(*e);
  env_strings.emplace_back(std::string(kRoleVariable) + "=plan_writer");
  std::vector<char*> envp;
  for (std::string& s : env_strings) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::string filter = "--gtest_filter=DdsCrossProcessRole.PlanWriter";
  std::vector<char*> argv{self.data(), filter.data(), nullptr};

  Result<Participant> participant = Participant::create(kDomain);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  auto reader =
      Reader<grip_msg_Plan>::create(*participant, &grip_msg_Plan_desc, "grip_plan", plan_qos());
  ASSERT_TRUE(reader.ok()) << reader.error().message;

  pid_t child = 0;
  ASSERT_EQ(posix_spawn(&child, self.c_str(), nullptr, nullptr, argv.data(), envp.data()), 0);
  struct Reaper {
    pid_t pid;
    ~Reaper() {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  } reaper{child};

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
  ASSERT_EQ(kill(child, SIGKILL), 0);
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
