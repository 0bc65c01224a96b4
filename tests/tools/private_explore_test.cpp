// `grip explore` keeps to itself by default: two runs with default options at once on one
// machine (both on domain 0, the same topics) each complete and neither matched a writer of the
// other; runs given a domain are shared on purpose and see each other, unless --private.
// Reports, pictures and cycle traces appear whole (no temporary file is left behind), and an
// output that cannot be written is refused before the run.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "grip_command.hpp"
#include "small_room_map.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::run_grip;

// A fresh directory of the test's own for its outputs.
std::string fresh_directory(const std::string& name) {
  const std::string dir = ::testing::TempDir() + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Runs every command line at once; their results in the same order.
std::vector<CommandRun> run_at_once(const std::vector<std::string>& arguments) {
  std::vector<CommandRun> runs(arguments.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    threads.emplace_back([&, i] { runs[i] = run_grip(arguments[i]); });
  }
  for (std::thread& t : threads) t.join();
  return runs;
}

std::string small_room() { return grip::testing::write_small_room_map("grip-private-room.map"); }

// Cross-talk between two runs of one vehicle shows as other_writers (a planner would take the
// other vehicle's states, the vehicle the other planner's plans).
TEST(PrivateExplore, TwoDefaultRunsAtOnceBothCompleteAndNeitherReceivesASampleOfTheOther) {
  const std::string dir = fresh_directory("grip-private-default");
  const std::string robots[] = {"first", "second"};
  std::vector<std::string> arguments;
  for (const std::string& robot : robots) {
    arguments.push_back("explore --map " + small_room() +
                        " --robot dd-vel --lockstep --seed 3 --max-sim-time 300 --report " + dir +
                        "/" + robot + ".json --image " + dir + "/" + robot + ".png --cycle-trace " +
                        dir + "/" + robot + ".csv");
  }
  const std::vector<CommandRun> runs = run_at_once(arguments);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    SCOPED_TRACE(robots[i]);
    EXPECT_EQ(runs[i].status, 0) << runs[i].output;  // complete
    const nlohmann::json report = read_json(dir + "/" + robots[i] + ".json");
    EXPECT_EQ(report.at("result"), "complete") << runs[i].output;
    EXPECT_EQ(report.at("collisions").get<int>(), 0);
    const nlohmann::json& link = report.at("link");
    EXPECT_TRUE(link.at("private").get<bool>()) << link.dump();
    EXPECT_EQ(link.at("domain").get<int>(), 0) << link.dump();
    EXPECT_EQ(link.at("other_writers").get<int>(), 0) << link.dump();
    for (const char* rejected : {"vehicle_states", "map_updates", "goals", "plans"}) {
      EXPECT_EQ(link.at("rejected").at(rejected).get<int>(), 0) << rejected << link.dump();
    }
  }
  EXPECT_NE(read_json(dir + "/first.json").at("link").at("discovery_tag"),
            read_json(dir + "/second.json").at("link").at("discovery_tag"));
  // Every output whole and in place; nothing else (no temporary file) in the directory.
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  const std::vector<std::string> expected = {"first.csv",  "first.json",  "first.png",
                                             "second.csv", "second.json", "second.png"};
  EXPECT_EQ(files, expected);
}

// Two runs on a domain they were given hear each other (what the default prevents); a third on
// that domain with --private hears neither.
TEST(PrivateExplore, RunsGivenADomainAreSharedUnlessPrivate) {
  const std::string dir = fresh_directory("grip-private-shared");
  const std::string common =
      "explore --map " + small_room() + " --robot dd-vel --lockstep --max-sim-time 15 --domain 200";
  const std::vector<CommandRun> runs =
      run_at_once({common + " --report " + dir + "/a.json", common + " --report " + dir + "/b.json",
                   common + " --private --report " + dir + "/c.json"});
  nlohmann::json links[3];
  const char* names[] = {"a", "b", "c"};
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::filesystem::exists(dir + "/" + names[i] + ".json")) << runs[i].output;
    links[i] = read_json(dir + "/" + names[i] + ".json").at("link");
    EXPECT_EQ(links[i].at("domain").get<int>(), 200) << links[i].dump();
  }
  EXPECT_FALSE(links[0].at("private").get<bool>()) << links[0].dump();
  EXPECT_FALSE(links[1].at("private").get<bool>()) << links[1].dump();
  // The two shared runs overlap in time: at least the later one matched the other's writers.
  EXPECT_GT(links[0].at("other_writers").get<int>() + links[1].at("other_writers").get<int>(), 0)
      << links[0].dump() << "\n"
      << links[1].dump();
  EXPECT_TRUE(links[2].at("private").get<bool>()) << links[2].dump();
  EXPECT_EQ(links[2].at("other_writers").get<int>(), 0) << links[2].dump();
}

TEST(PrivateExplore, AnOutputThatCannotBeWrittenIsRefusedBeforeTheRun) {
  const std::string dir = fresh_directory("grip-private-unwritable");
  const std::string not_a_directory = dir + "/plain-file";
  std::ofstream(not_a_directory) << "x\n";
  const std::string base = "explore --map " + small_room() + " --robot dd-vel --lockstep ";
  for (const std::string& option :
       {std::string("--report"), std::string("--image"), std::string("--cycle-trace")}) {
    for (const std::string& path :
         {dir + "/missing/out", not_a_directory + "/out", dir}) {  // the last: a directory
      const CommandRun r = run_grip(base + option + " " + path);
      EXPECT_EQ(r.status, 2) << option << " " << path << "\n" << r.output;
      EXPECT_NE(r.output.find(option + ": cannot write '" + path + "'"), std::string::npos)
          << r.output;
      EXPECT_EQ(r.output.find("coverage"), std::string::npos) << "it ran:\n" << r.output;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/missing"));
}

}  // namespace
