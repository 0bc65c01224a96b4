// The operator's tools for a running system: `grip echo` prints a topic's samples as JSON lines,
// `grip goal` hands the planner a goal it then heads for. Against a real lockstep exploration
// (simulator and planner); every test that talks has a DDS domain of its own.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <csignal>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "grip_command.hpp"
#include "json_lines.hpp"

namespace {

using grip::testing::ChildProcess;
using grip::testing::CommandRun;
using grip::testing::json_lines;
using grip::testing::kGrip;
using grip::testing::run_grip;

// A lockstep exploration of `rooms` on `domain`, stopped when the test ends.
class RunningExploration {
 public:
  explicit RunningExploration(const std::string& domain)
      : child_(ChildProcess::spawn(
            {kGrip, "explore", "--lockstep", "--max-sim-time", "600", "--domain", domain})) {}
  ~RunningExploration() {
    if (child_) {
      child_->kill(SIGTERM);
      child_->wait();
    }
  }
  bool started() const { return child_.has_value(); }

 private:
  std::optional<ChildProcess> child_;
};

TEST(EchoCommand, PrintsThePlannersStatusAsJsonLines) {
  RunningExploration exploration("86");
  ASSERT_TRUE(exploration.started());

  const CommandRun r = run_grip("echo grip_planner_status --domain 86 --count 3 --timeout 60");

  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<nlohmann::json> lines = json_lines(r.output);
  ASSERT_EQ(lines.size(), 3U) << r.output;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].at("topic"), "grip_planner_status");
    EXPECT_GT(lines[i].at("source_timestamp_ns").get<std::int64_t>(), 0);
    const nlohmann::json& status = lines[i].at("sample");
    EXPECT_TRUE(status.at("map_in_sync").get<bool>()) << status;
    if (i > 0) {
      EXPECT_GT(status.at("cycle").get<std::uint64_t>(),
                lines[i - 1].at("sample").at("cycle").get<std::uint64_t>());
    }
  }
}

TEST(EchoCommand, ATopicWithoutSamplesEndsAtTheTimeoutWithStatus3) {
  const CommandRun r = run_grip("echo grip_goal --domain 80 --count 1 --timeout 1");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("0 samples of grip_goal in 1 s"), std::string::npos) << r.output;
}

TEST(EchoCommand, WithoutDdsConfigCycloneddsUriIsFollowed) {
  // A configuration file that does not exist: the participant cannot be created, which shows
  // that the environment's configuration was the one used (and no packet leaves).
  ASSERT_EQ(setenv("CYCLONEDDS_URI", "file:///nonexistent/grip-test.xml", 1), 0);
  const CommandRun r = run_grip("echo grip_goal --domain 80 --count 1 --timeout 1");
  unsetenv("CYCLONEDDS_URI");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("nonexistent/grip-test.xml"), std::string::npos) << r.output;
}

TEST(EchoCommand, AnUnknownTopicIsRefused) {
  const CommandRun r = run_grip("echo grip_nonsense --count 1");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("grip_planner_status"), std::string::npos)
      << "the valid topics are listed: " << r.output;
}

TEST(GoalCommand, ThePlannerHeadsForTheGoalItAcknowledged) {
  // GIVEN a planner that explores (its first status says so)
  RunningExploration exploration("79");
  ASSERT_TRUE(exploration.started());
  const CommandRun first = run_grip("echo grip_planner_status --domain 79 --count 1 --timeout 60");
  ASSERT_EQ(first.status, 0) << first.output;
  ASSERT_TRUE(json_lines(first.output).at(0).at("sample").at("exploring").get<bool>());

  // WHEN an operator sends a goal in the sensed part of the first room
  const CommandRun sent = run_grip("goal 3.5 2.5 --radius 1 --domain 79 --wait 60");
  ASSERT_EQ(sent.status, 0) << sent.output;
  EXPECT_NE(sent.output.find("goal 1 at (3.5, 2.5) radius 1 m delivered"), std::string::npos)
      << sent.output;

  // THEN the planner stops exploring and targets it (within a few cycles: a cycle under way
  // when the goal came still explores)
  const CommandRun status =
      run_grip("echo grip_planner_status --domain 79 --count 10 --timeout 30");
  ASSERT_EQ(status.status, 0) << status.output;
  const nlohmann::json sample = json_lines(status.output).back().at("sample");
  EXPECT_FALSE(sample.at("exploring").get<bool>()) << sample;
  EXPECT_DOUBLE_EQ(sample.at("target_x_m").get<double>(), 3.5);
  EXPECT_DOUBLE_EQ(sample.at("target_y_m").get<double>(), 2.5);
}

TEST(GoalCommand, WithoutAPlannerItSaysSoWithStatus3) {
  const CommandRun r = run_grip("goal 1 1 --domain 78 --wait 1");
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("no planner on DDS domain 78 within 1 s"), std::string::npos) << r.output;
}

TEST(GoalCommand, ANonFiniteGoalIsRefusedWithStatus2) {
  const CommandRun r = run_grip("goal 1 nan");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("X and Y must be finite"), std::string::npos) << r.output;
}

}  // namespace
