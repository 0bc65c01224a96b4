// One GRIP and one OMPL run in this process, and `grip bench ompl` run as users run it, briefly
// (a scene and vehicle both solve in well under a second). Nothing about time is asserted.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "comparison.hpp"
#include "test_paths.hpp"

namespace grip::ompl_bridge {
namespace {

TEST(BenchOmpl, AGripRunSolvesCountsItsWorkAndPassesTheRecheck) {
  const RunResult r = run_one(RunSpec{"rooms", "dd-vel", "grip", 1, 60.0});
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.exact);
  EXPECT_TRUE(r.verified) << r.failure;
  EXPECT_GT(r.propagations, 0U);
  EXPECT_EQ(r.propagations, r.collision_checks);  // one check per step, braking steps included
  EXPECT_GT(r.tree_size, 0U);
  EXPECT_GT(r.duration_s, 0.0);
  EXPECT_GT(r.length_m, 0.0);
}

TEST(BenchOmpl, AnOmplRunThroughTheAdapterSolvesAndPassesTheRecheck) {
  const RunResult r = run_one(RunSpec{"rooms", "dd-vel", "kpiece1", 1, 60.0});
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.exact) << r.failure;
  EXPECT_TRUE(r.verified) << r.failure;
  EXPECT_GT(r.propagations, 0U);
  EXPECT_GT(r.collision_checks, 0U);
  EXPECT_GT(r.tree_size, 1U);
}

TEST(BenchOmpl, AnUnknownPlannerIsAnErrorNotACrash) {
  const RunResult r = run_one(RunSpec{"rooms", "dd-vel", "prm", 1, 1.0});
  EXPECT_FALSE(r.error.empty());
  EXPECT_FALSE(r.verified);
}

TEST(BenchOmpl, RunResultsRoundTripThroughJson) {
  RunResult r;
  r.spec = RunSpec{"labyrinth", "car", "sst", 4, 2.5};
  r.exact = true;
  r.solve_time_s = 1.25;
  r.propagations = 12345;
  r.collision_checks = 12000;
  r.tree_size = 77;
  r.failure = "re-check: x";
  const RunResult back = run_result_from_json(to_json(r));
  EXPECT_EQ(to_json(back), to_json(r));
}

TEST(BenchOmplCommand, AShortRunWritesTheTableTheJsonAndTheChart) {
  const std::string dir = ::testing::TempDir();
  const std::string json = dir + "grip-bench-ompl-test.json";
  const std::string png = dir + "grip-bench-ompl-test.png";
  std::remove(png.c_str());
  const std::string command = std::string(GRIP_BINARY_DIR) +
                              "/bin/grip bench ompl --seeds 2 --time-limit 20 --scenes rooms "
                              "--vehicles dd-vel --planners grip kpiece1 --jobs 2 --json " +
                              json + " --png " + png + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  EXPECT_NE(output.find("Held equal"), std::string::npos) << output;
  EXPECT_NE(output.find("Target: GRIP solves every run"), std::string::npos) << output;

  std::ifstream in(json);
  ASSERT_TRUE(in.good());
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report.at("runs").size(), 4U);
  for (const auto& run : report.at("runs")) {
    EXPECT_EQ(run.at("error").get<std::string>(), "") << run.dump();
    EXPECT_TRUE(run.at("verified").get<bool>()) << run.dump();
  }
  ASSERT_EQ(report.at("summary").size(), 2U);
  EXPECT_EQ(report.at("summary")[0].at("planner"), "grip");
  EXPECT_EQ(report.at("summary")[0].at("solved"), 2);
  EXPECT_TRUE(report.at("targets").at("grip_solves_all_ompl_solved").get<bool>());

  std::ifstream image(png, std::ios::binary);
  ASSERT_TRUE(image.good());
  char magic[8] = {};
  image.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

}  // namespace
}  // namespace grip::ompl_bridge
