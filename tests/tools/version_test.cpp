// `grip --version` and the "produced_by" section of every report: a figure can be traced to the
// code and the machine behind it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "grip_command.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::run_grip;

TEST(Version, GripSaysItsVersionAndRevision) {
  const CommandRun r = run_grip("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::regex_match(r.output, std::regex("grip [0-9]+\\.[0-9]+\\.[0-9]+ \\(revision "
                                                    "[0-9a-z.-]+\\)\n")))
      << r.output;
}

TEST(Version, AReportSaysWhichBuildAndWhichMachineProducedIt) {
  // GIVEN a report written by a command (the standalone benchmark, briefly)
  const std::string path = ::testing::TempDir() + "grip-version-report.json";
  const CommandRun r =
      run_grip("bench paper --seeds 1 --experiments table2 --jobs 1 --json " + path);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  const nlohmann::json produced_by = nlohmann::json::parse(in).at("produced_by");

  // THEN it names the build that `grip --version` names, and this machine
  const std::string version = run_grip("--version").output;
  const nlohmann::json& grip = produced_by.at("grip");
  EXPECT_EQ(version, "grip " + grip.at("version").get<std::string>() + " (revision " +
                         grip.at("revision").get<std::string>() + ")\n");
  const nlohmann::json& machine = produced_by.at("machine");
  EXPECT_EQ(machine.at("online_cpus").get<long>(), sysconf(_SC_NPROCESSORS_ONLN));
  EXPECT_EQ(machine.at("kernel").get<std::string>().rfind("Linux ", 0), 0U) << machine;
  EXPECT_FALSE(machine.at("architecture").get<std::string>().empty()) << machine;
  EXPECT_FALSE(machine.at("hostname").get<std::string>().empty()) << machine;
}

}  // namespace
