// `grip bench explore` runs its matrix for real (here: one small map, a built-in robot and one
// from a parameter file, two seeds, in lockstep): every run leaves its report, the table counts
// them, and bad options are refused.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "grip_command.hpp"
#include "small_room_map.hpp"

namespace {

using grip::testing::CommandRun;

TEST(BenchExploreCommand, RunsEveryWorldRobotAndSeedAndTabulatesThem) {
  const std::string out_dir = ::testing::TempDir() + "grip-bench-explore";
  const std::string json = ::testing::TempDir() + "grip-bench-explore.json";
  const std::string slow = ::testing::TempDir() + "slow-dd.yaml";
  {
    std::ofstream out(slow);
    out << "vehicle:\n  model: dd-vel\n  max_wheel_speed_m_s: 1.5\n";
  }
  std::filesystem::remove_all(out_dir);
  const CommandRun r = grip::testing::run_grip(
      "bench explore --scenes '' --map " +
      grip::testing::write_small_room_map("grip-bench-explore-room.map") + " --robots dd-vel," +
      slow + " --seeds 2 --lockstep --max-sim-time 300 --jobs 2 --out " + out_dir + " --json " +
      json);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("runs").size(), 4U) << r.output;
  for (const auto& run : j.at("runs")) {
    EXPECT_EQ(run.at("result"), "complete") << run.dump();
    EXPECT_EQ(run.at("collisions").get<int>(), 0) << run.dump();
    EXPECT_TRUE(std::filesystem::exists(run.at("report").get<std::string>())) << run.dump();
  }
  EXPECT_NE(j.at("runs")[0].at("seed"), j.at("runs")[1].at("seed"));
  ASSERT_EQ(j.at("table").size(), 2U);
  EXPECT_EQ(j.at("table")[0].at("robot"), "dd-vel");
  EXPECT_EQ(j.at("table")[1].at("robot"), "slow-dd");  // the file's, by its name
  for (const auto& row : j.at("table")) {
    EXPECT_EQ(row.at("runs").get<int>(), 2);
    EXPECT_EQ(row.at("complete").get<int>(), 2);
    EXPECT_TRUE(row.at("target_met").get<bool>());
  }
  // The file's vehicle ran: its report says so.
  std::ifstream slow_report(j.at("runs")[2].at("report").get<std::string>());
  const nlohmann::json slow_run = nlohmann::json::parse(slow_report);
  EXPECT_DOUBLE_EQ(slow_run.at("max_speed_m_s").get<double>(), 1.5);
  // Without --domain every run is private to itself (tools/grip/private_link.hpp).
  EXPECT_TRUE(slow_run.at("link").at("private").get<bool>()) << slow_run.at("link").dump();
  EXPECT_EQ(slow_run.at("link").at("other_writers").get<int>(), 0) << slow_run.at("link").dump();
  EXPECT_NE(r.output.find("target (every run: 0 collisions, coverage >= 0.97): met"),
            std::string::npos)
      << r.output;
}

TEST(BenchExploreCommand, BadOptionsAreRefusedNamingWhatIsWrong) {
  CommandRun r = grip::testing::run_grip("bench explore --robots bicycle");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("bicycle"), std::string::npos) << r.output;
  r = grip::testing::run_grip("bench explore --map /nonexistent/grip.map --scenes ''");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("/nonexistent/grip.map"), std::string::npos) << r.output;
  // One domain per job, and Cyclone's ports end at domain 232.
  r = grip::testing::run_grip("bench explore --domain 200 --jobs 40");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--domain 200 with --jobs 40 would use domains above 232"),
            std::string::npos)
      << r.output;
}

}  // namespace
