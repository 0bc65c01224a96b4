// Two vehicles on one DDS domain, each with its planner, kept apart by topic prefixes: two
// lockstep explorations running at the same time each make exactly the run they make alone (a
// planner that read the other vehicle's states or map, or a vehicle that took the other
// planner's plans, would change it), and `grip echo --topic-prefix` hears one vehicle only.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "grip_command.hpp"
#include "json_lines.hpp"
#include "small_room_map.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::json_lines;
using grip::testing::run_grip;

// The exploration of the small room by `robot` on domain 99 under `prefix`, into `report`.
std::string exploration(const std::string& prefix, const std::string& robot,
                        const std::string& report) {
  return "explore --map " + grip::testing::write_small_room_map("grip-prefix-room.map") +
         " --robot " + robot + " --lockstep --seed 3 --max-sim-time 60 --domain 99 " +
         "--topic-prefix " + prefix + " --report " + report;
}

// The report without what the machine decides: times and memory.
nlohmann::json read_run(const std::string& path) {
  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"wall_time_s", "planner_startup", "peak_rss_mb"}) j.erase(key);
  return j;
}

TEST(TopicPrefix, TwoExplorationsShareADomainWithoutHearingEachOther) {
  const std::string dir = ::testing::TempDir();
  const struct {
    std::string prefix, robot, kind;
  } vehicles[2] = {{"a", "dd-vel", "DD_VELOCITY"}, {"b", "dd-accel", "DD_ACCELERATION"}};

  // GIVEN each vehicle's run alone
  nlohmann::json alone[2];
  for (int i = 0; i < 2; ++i) {
    const std::string report = dir + "grip-prefix-alone-" + vehicles[i].prefix + ".json";
    const CommandRun r = run_grip(exploration(vehicles[i].prefix, vehicles[i].robot, report));
    ASSERT_TRUE(r.status == 0 || r.status == 3) << r.output;
    alone[i] = read_run(report);
  }

  // WHEN both run at once on the same domain, while `grip echo` listens to each prefix
  CommandRun together[2];
  CommandRun states[2];
  CommandRun described[2];
  std::vector<std::thread> runs;
  for (int i = 0; i < 2; ++i) {
    const std::string& prefix = vehicles[i].prefix;
    runs.emplace_back([&, i, prefix] {
      together[i] = run_grip(
          exploration(prefix, vehicles[i].robot, dir + "grip-prefix-together-" + prefix + ".json"));
    });
    runs.emplace_back([&, i, prefix] {
      states[i] = run_grip("echo grip_vehicle_state --topic-prefix " + prefix +
                           " --domain 99 --count 20 --timeout 60");
    });
    runs.emplace_back([&, i, prefix] {
      described[i] = run_grip("echo grip_vehicle_description --topic-prefix " + prefix +
                              " --domain 99 --count 1 --timeout 60");
    });
  }
  for (std::thread& t : runs) t.join();

  // THEN each run is the one it makes alone, and each prefix carries one vehicle
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE(vehicles[i].prefix);
    ASSERT_TRUE(together[i].status == 0 || together[i].status == 3) << together[i].output;
    const nlohmann::json run =
        read_run(dir + "grip-prefix-together-" + vehicles[i].prefix + ".json");
    EXPECT_EQ(run.at("start_mismatches").get<int>(), 0);
    EXPECT_EQ(run.at("plans_rejected").get<int>(), 0);
    EXPECT_EQ(run, alone[i]) << "the other vehicle's samples changed the run";

    ASSERT_EQ(states[i].status, 0) << states[i].output;
    const std::vector<nlohmann::json> lines = json_lines(states[i].output);
    ASSERT_EQ(lines.size(), 20U);
    for (const nlohmann::json& line : lines) {
      EXPECT_EQ(line.at("topic"), vehicles[i].prefix + "_grip_vehicle_state");
      EXPECT_EQ(line.at("sample").at("kind"), vehicles[i].kind) << line;
    }
    ASSERT_EQ(described[i].status, 0) << described[i].output;
    const nlohmann::json description = json_lines(described[i].output).at(0).at("sample");
    EXPECT_EQ(description.at("model"), vehicles[i].kind) << description;
  }
}

TEST(TopicPrefix, APrefixThatIsNotAnIdentifierIsRefusedNamingIt) {
  for (const char* command :
       {"explore --topic-prefix 9a", "sim --topic-prefix 9a", "planner --topic-prefix 9a",
        "echo grip_plan --topic-prefix 9a", "goal 1 1 --topic-prefix 9a"}) {
    const CommandRun r = run_grip(command);
    EXPECT_NE(r.status, 0) << command;
    EXPECT_NE(r.output.find("topic prefix \"9a\" must start with a letter"), std::string::npos)
        << command << ": " << r.output;
  }
}

}  // namespace
