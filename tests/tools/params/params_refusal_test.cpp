// What a parameter file is refused for: every refusal is kInvalidArgument and names the file,
// the line and column of the offending text, and its key.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <future>
#include <string>

#include "grip/params/params.hpp"

namespace {

using grip::ErrorCode;
using grip::params::load_params;
using grip::params::parse_params;

bool has(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

// A file's text, read as "robot.yaml", refused at line:column `where` with a message that says
// `says` (which names the key).
struct Refusal {
  const char* name;
  const char* text;
  const char* where;
  const char* says;
};

const Refusal kRefusals[] = {
    {"MalformedYamlAtTheParsersMark", "vehicle:\n  model: car\nplanner: [1, 2\n", "4:1",
     "invalid YAML"},
    {"AListAtTheTopNamingTheSections", "- vehicle\n- planner\n", "1:1",
     "expected a mapping of the sections (vehicle, planner,"},
    {"AnUnknownSectionListingTheSections", "vehicle:\n  model: car\nvehicles:\n  x: 1\n", "3:1",
     "vehicles: unknown key (allowed: vehicle, planner, sensor,"},
    {"AnUnknownVehicleKeyListingTheModelsKeys", "vehicle:\n  model: car\n  max_sped_m_s: 2\n",
     "3:3", "vehicle.max_sped_m_s: unknown key (model car allows: model, max_speed_m_s,"},
    {"AnUnknownKeyInASectionListingItsKeys", "vehicle:\n  model: car\nplanner:\n  cycle: 0.1\n",
     "4:3", "planner.cycle: unknown key (allowed: cycle_s, budget_s,"},
    {"AnUnknownKeyInANestedMapping", "vehicle:\n  model: car\n  footprint:\n    length_m: 1\n",
     "4:5", "vehicle.footprint.length_m: unknown key (allowed: front_m, rear_m,"},
    {"AKeyOfAnotherModel", "vehicle:\n  model: dd-vel\n  wheelbase_m: 0.9\n", "3:3",
     "vehicle.wheelbase_m: unknown key (model dd-vel allows:"},
    {"AMissingModelListingTheThree", "\n\nvehicle:\n  max_speed_m_s: 2\n", "3:1",
     "vehicle.model is required (dd-vel, dd-accel, car)"},
    {"AMissingVehicle", "planner:\n  cycle_s: 0.1\n", "1:1", "vehicle.model is required"},
    {"AnEmptyFile", "", "1:1", "vehicle.model is required"},
    {"AnUnknownModelListingTheThree", "vehicle:\n  model: tank\n", "2:10",
     "vehicle.model: expected one of dd-vel, dd-accel, car, got 'tank'"},
    {"TextForANumber", "vehicle:\n  model: car\nplanner:\n  cycle_s: fast\n", "4:12",
     "planner.cycle_s: expected a number, got 'fast'"},
    {"AQuotedNumber", "vehicle:\n  model: car\n  wheelbase_m: \"0.9\"\n", "3:16",
     "vehicle.wheelbase_m: expected a number, got the string '0.9'"},
    {"AFractionForAWholeNumber", "vehicle:\n  model: car\nplanner:\n  max_edges: 1.5\n", "4:14",
     "planner.max_edges: expected a whole number in [0, 4294967295] or auto"},
    {"ANegativeDomain", "vehicle:\n  model: car\nlink:\n  domain: -1\n", "4:11",
     "link.domain: expected a whole number in [0, 4294967295], got '-1'"},
    {"ADomainBeyondThePortMapping", "vehicle:\n  model: car\nlink:\n  domain: 233\n", "4:11",
     "link.domain must be at most 232"},
    {"ABooleanSpelledOtherwiseThanTrueOrFalse",
     "vehicle:\n  model: car\nruntime:\n  lock_memory: yes\n", "4:16",
     "runtime.lock_memory: expected true or false, got 'yes'"},
    {"AnUnknownSchedulingPolicy", "vehicle:\n  model: car\nruntime:\n  policy: rr\n", "4:11",
     "runtime.policy: unknown scheduling policy 'rr'"},
    {"AVehicleLimitOutOfTheModelsRange", "vehicle:\n  model: car\n  max_steer_rad: 2.0\n", "3:18",
     "vehicle.max_steer_rad must be < pi/2"},
    {"AFootprintWithoutLength",
     "vehicle:\n  model: dd-vel\n  footprint:\n    front_m: -0.5\n    rear_m: 0.25\n", "4:14",
     "vehicle.footprint.front_m + rear_m must be"},
    {"ABudgetNotBelowTheCycleAtTheBudget",
     "vehicle:\n  model: car\nplanner:\n  cycle_s: 0.05\n  budget_s: 0.05\n", "5:13",
     "planner.budget_s must be in (0, cycle_s = 0.05) (got 0.05)"},
    // The budget left at its default is not in the file: the planner section stands for it.
    {"ACycleShorterThanTheDefaultBudgetAtTheSection",
     "vehicle:\n  model: car\nplanner:\n  cycle_s: 0.02\n", "3:1",
     "planner.budget_s must be in (0, cycle_s = 0.02) (got 0.025)"},
    {"PlanDurationsThePlannerRefuses",
     "vehicle:\n  model: car\nplanner:\n  min_plan_duration_s: 5\n", "4:24",
     "planner.min_plan_duration_s (5.000000) exceeds max_plan_duration_s"},
    {"AFrontierApproachRangeInsideTheClearance",
     "vehicle:\n  model: car\nexploration:\n  frontier:\n    approach_range_m: 0.2\n", "5:23",
     "exploration.frontier.approach_range_m must be"},
    {"ATopicPrefixStartingWithADigit", "vehicle:\n  model: car\nlink:\n  topic_prefix: 9lives\n",
     "4:17",
     "link.topic_prefix must be empty or up to 64 of [A-Za-z0-9_], starting with a letter (got "
     "'9lives')"},
    {"ATopicPrefixWithADash", "vehicle:\n  model: car\nlink:\n  topic_prefix: robot-7\n", "4:17",
     "link.topic_prefix must be"},
    {"ADuplicatedKeyAtItsSecondPlace",
     "vehicle:\n  model: car\nplanner:\n  cycle_s: 0.1\n  budget_s: 0.02\n  cycle_s: 0.2\n", "6:3",
     "planner.cycle_s: duplicate key (first at line 4)"},
    {"ADuplicatedSection", "vehicle:\n  model: car\nvehicle:\n  model: car\n", "3:1",
     "vehicle: duplicate key (first at line 1)"},
    {"NotANumber", "vehicle:\n  model: car\nplanner:\n  cycle_s: .nan\n", "4:12",
     "planner.cycle_s: expected a finite number, got '.nan'"},
    {"Infinity", "vehicle:\n  model: car\nplanner:\n  cycle_s: -.Inf\n", "4:12",
     "planner.cycle_s: expected a finite number, got '-.Inf'"},
    {"ANumberBeyondADouble", "vehicle:\n  model: car\nplanner:\n  cycle_s: 1e999\n", "4:12",
     "planner.cycle_s: expected a finite number, got '1e999'"},
    {"ASecondDocument", "vehicle:\n  model: car\n---\nvehicle:\n  model: car\n", "4:1",
     "a second YAML document"},
};

class ParamsRefusal : public ::testing::TestWithParam<Refusal> {};

TEST_P(ParamsRefusal, NamesTheFileThePlaceAndTheKey) {
  const Refusal& r = GetParam();
  const auto read = parse_params(r.text, "robot.yaml");
  ASSERT_FALSE(read.ok()) << "accepted:\n" << r.text;
  EXPECT_EQ(read.error().code, ErrorCode::kInvalidArgument);
  const std::string& message = read.error().message;
  EXPECT_TRUE(message.starts_with("robot.yaml:" + std::string(r.where) + ": ")) << message;
  EXPECT_TRUE(has(message, r.says)) << message;
}

INSTANTIATE_TEST_SUITE_P(Text, ParamsRefusal, ::testing::ValuesIn(kRefusals),
                         [](const auto& refusal) { return std::string(refusal.param.name); });

std::string load_refusal(const std::string& path) {
  const auto read = load_params(path);
  if (read.ok()) {
    ADD_FAILURE() << "accepted: " << path;
    return {};
  }
  EXPECT_EQ(read.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(read.error().message.starts_with(path + ": ")) << read.error().message;
  return read.error().message;
}

TEST(ParamsFileRefusal, APathThatCannotBeOpened) {
  const std::string path = ::testing::TempDir() + "no-such-folder/robot.yaml";
  EXPECT_TRUE(has(load_refusal(path), "cannot open the parameter file"));
}

TEST(ParamsFileRefusal, ADirectory) {
  EXPECT_TRUE(has(load_refusal(::testing::TempDir()), "is a directory"));
}

TEST(ParamsFileRefusal, ADeviceThatNeverEnds) {
  EXPECT_TRUE(has(load_refusal("/dev/zero"), "is not a regular file"));
}

TEST(ParamsFileRefusal, AFifoWithoutWaitingForAWriter) {
  const std::string path = ::testing::TempDir() + "grip-params-fifo.yaml";
  std::remove(path.c_str());
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  auto refused = std::async(std::launch::async, [&path] { return load_params(path); });
  const bool returned = refused.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
  if (!returned) {
    // A reader blocked in open() waits for a writer: be one, or the test would never end.
    const int fd = ::open(path.c_str(), O_WRONLY);
    if (fd >= 0) ::close(fd);
  }
  ASSERT_TRUE(returned) << "load_params waited for a writer of the FIFO";
  const auto read = refused.get();
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(has(read.error().message, path + ": is not a regular file")) << read.error().message;
  std::remove(path.c_str());
}

TEST(ParamsFileRefusal, AFileLargerThanAMebibyte) {
  const std::string path = ::testing::TempDir() + "grip-params-large.yaml";
  {
    std::ofstream out(path);
    out << "vehicle:\n  model: car\n" << std::string((1 << 20) + 1, '#') << "\n";
  }
  EXPECT_TRUE(has(load_refusal(path), "is larger than 1048576 bytes"));
  std::remove(path.c_str());
}

TEST(ParamsFileRefusal, AFileNamesItselfInItsErrors) {
  const std::string path = ::testing::TempDir() + "grip-params-bad.yaml";
  {
    std::ofstream out(path);
    out << "vehicle:\n  model: car\n  max_steer_rad: 2.0\n";
  }
  const auto read = load_params(path);
  ASSERT_FALSE(read.ok());
  EXPECT_TRUE(read.error().message.starts_with(path + ":3:18: vehicle.max_steer_rad"))
      << read.error().message;
  std::remove(path.c_str());
}

}  // namespace
