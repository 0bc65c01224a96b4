// `grip --version` and the "produced_by" section of every report: a figure can be traced to the
// code and the machine behind it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "grip_command.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::run_grip;

// "grip X.Y.Z (revision R)\n" with a version of three numbers and a revision without spaces.
bool is_version_line(const std::string& line) {
  const std::string head = "grip ";
  const std::string middle = " (revision ";
  const std::size_t open = line.find(middle);
  if (line.rfind(head, 0) != 0 || open == std::string::npos || !line.ends_with(")\n")) {
    return false;
  }
  const std::string version = line.substr(head.size(), open - head.size());
  const std::string revision =
      line.substr(open + middle.size(), line.size() - 2 - open - middle.size());
  const bool version_ok = std::count(version.begin(), version.end(), '.') == 2 &&
                          version.find_first_not_of("0123456789.") == std::string::npos &&
                          version.find("..") == std::string::npos && version.front() != '.' &&
                          version.back() != '.';
  return version_ok && !revision.empty() && revision.find(' ') == std::string::npos;
}

TEST(Version, GripSaysItsVersionAndRevision) {
  const CommandRun r = run_grip("--version");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(is_version_line(r.output)) << r.output;
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
