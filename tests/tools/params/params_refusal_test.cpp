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

// The message of the refusal of `text` read as "robot.yaml", after checking that it is a
// refusal and starts with "robot.yaml:<where>: ".
std::string refusal(const std::string& text, const std::string& where) {
  const auto read = parse_params(text, "robot.yaml");
  if (read.ok()) {
    ADD_FAILURE() << "accepted:\n" << text;
    return {};
  }
  EXPECT_EQ(read.error().code, ErrorCode::kInvalidArgument);
  const std::string& message = read.error().message;
  EXPECT_TRUE(message.starts_with("robot.yaml:" + where + ": ")) << message;
  return message;
}

bool has(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

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

TEST(ParamsRefusal, MalformedYamlAtTheParsersMark) {
  const std::string m = refusal("vehicle:\n  model: car\nplanner: [1, 2\n", "4:1");
  EXPECT_TRUE(has(m, "invalid YAML")) << m;
}

TEST(ParamsRefusal, AListAtTheTopNamingTheSections) {
  const std::string m = refusal("- vehicle\n- planner\n", "1:1");
  EXPECT_TRUE(has(m, "expected a mapping of the sections (vehicle, planner,")) << m;
}

TEST(ParamsRefusal, AnUnknownSectionListingTheSections) {
  const std::string m = refusal("vehicle:\n  model: car\nvehicles:\n  x: 1\n", "3:1");
  EXPECT_TRUE(has(m, "vehicles: unknown key (allowed: vehicle, planner, sensor,")) << m;
}

TEST(ParamsRefusal, AnUnknownVehicleKeyListingTheModelsKeys) {
  const std::string m = refusal("vehicle:\n  model: car\n  max_sped_m_s: 2\n", "3:3");
  EXPECT_TRUE(has(m, "vehicle.max_sped_m_s: unknown key (model car allows: model, max_speed_m_s,"))
      << m;
}

TEST(ParamsRefusal, AnUnknownKeyInASectionListingItsKeys) {
  const std::string m = refusal("vehicle:\n  model: car\nplanner:\n  cycle: 0.1\n", "4:3");
  EXPECT_TRUE(has(m, "planner.cycle: unknown key (allowed: cycle_s, budget_s,")) << m;
}

TEST(ParamsRefusal, AnUnknownKeyInANestedMapping) {
  const std::string m = refusal("vehicle:\n  model: car\n  footprint:\n    length_m: 1\n", "4:5");
  EXPECT_TRUE(has(m, "vehicle.footprint.length_m: unknown key (allowed: front_m, rear_m,")) << m;
}

TEST(ParamsRefusal, AKeyOfAnotherModel) {
  const std::string m = refusal("vehicle:\n  model: dd-vel\n  wheelbase_m: 0.9\n", "3:3");
  EXPECT_TRUE(has(m, "vehicle.wheelbase_m: unknown key (model dd-vel allows:")) << m;
}

TEST(ParamsRefusal, AMissingModelListingTheThree) {
  const std::string m = refusal("\n\nvehicle:\n  max_speed_m_s: 2\n", "3:1");
  EXPECT_TRUE(has(m, "vehicle.model is required (dd-vel, dd-accel, car)")) << m;
  const std::string no_vehicle = refusal("planner:\n  cycle_s: 0.1\n", "1:1");
  EXPECT_TRUE(has(no_vehicle, "vehicle.model is required")) << no_vehicle;
  const std::string empty = refusal("", "1:1");
  EXPECT_TRUE(has(empty, "vehicle.model is required")) << empty;
}

TEST(ParamsRefusal, AnUnknownModelListingTheThree) {
  const std::string m = refusal("vehicle:\n  model: tank\n", "2:10");
  EXPECT_TRUE(has(m, "vehicle.model: expected one of dd-vel, dd-accel, car, got 'tank'")) << m;
}

TEST(ParamsRefusal, TextForANumber) {
  const std::string m = refusal("vehicle:\n  model: car\nplanner:\n  cycle_s: fast\n", "4:12");
  EXPECT_TRUE(has(m, "planner.cycle_s: expected a number, got 'fast'")) << m;
}

TEST(ParamsRefusal, AQuotedNumber) {
  const std::string m = refusal("vehicle:\n  model: car\n  wheelbase_m: \"0.9\"\n", "3:16");
  EXPECT_TRUE(has(m, "vehicle.wheelbase_m: expected a number, got the string '0.9'")) << m;
}

TEST(ParamsRefusal, AFractionForAWholeNumber) {
  const std::string m = refusal("vehicle:\n  model: car\nplanner:\n  max_edges: 1.5\n", "4:14");
  EXPECT_TRUE(has(m, "planner.max_edges: expected a whole number in [0, 4294967295] or auto")) << m;
}

TEST(ParamsRefusal, ANegativeDomain) {
  const std::string m = refusal("vehicle:\n  model: car\nlink:\n  domain: -1\n", "4:11");
  EXPECT_TRUE(has(m, "link.domain: expected a whole number in [0, 4294967295], got '-1'")) << m;
}

TEST(ParamsRefusal, ADomainBeyondThePortMapping) {
  const std::string m = refusal("vehicle:\n  model: car\nlink:\n  domain: 233\n", "4:11");
  EXPECT_TRUE(has(m, "link.domain must be at most 232")) << m;
}

TEST(ParamsRefusal, ABooleanSpelledOtherwiseThanTrueOrFalse) {
  const std::string m = refusal("vehicle:\n  model: car\nruntime:\n  lock_memory: yes\n", "4:16");
  EXPECT_TRUE(has(m, "runtime.lock_memory: expected true or false, got 'yes'")) << m;
}

TEST(ParamsRefusal, AnUnknownSchedulingPolicy) {
  const std::string m = refusal("vehicle:\n  model: car\nruntime:\n  policy: rr\n", "4:11");
  EXPECT_TRUE(has(m, "runtime.policy: unknown scheduling policy 'rr'")) << m;
}

TEST(ParamsRefusal, AVehicleLimitOutOfTheModelsRange) {
  const std::string m = refusal("vehicle:\n  model: car\n  max_steer_rad: 2.0\n", "3:18");
  EXPECT_TRUE(has(m, "vehicle.max_steer_rad must be < pi/2")) << m;
}

TEST(ParamsRefusal, AFootprintWithoutLength) {
  const std::string m = refusal(
      "vehicle:\n  model: dd-vel\n  footprint:\n    front_m: -0.5\n    rear_m: 0.25\n", "4:14");
  EXPECT_TRUE(has(m, "vehicle.footprint.front_m + rear_m must be")) << m;
}

TEST(ParamsRefusal, ABudgetNotBelowTheCycleAtTheBudget) {
  const std::string m =
      refusal("vehicle:\n  model: car\nplanner:\n  cycle_s: 0.05\n  budget_s: 0.05\n", "5:13");
  EXPECT_TRUE(has(m, "planner.budget_s must be in (0, cycle_s = 0.05) (got 0.05)")) << m;
}

TEST(ParamsRefusal, ACycleShorterThanTheDefaultBudgetAtTheSection) {
  // The budget left at its default is not in the file: the planner section stands for it.
  const std::string m = refusal("vehicle:\n  model: car\nplanner:\n  cycle_s: 0.02\n", "3:1");
  EXPECT_TRUE(has(m, "planner.budget_s must be in (0, cycle_s = 0.02) (got 0.025)")) << m;
}

TEST(ParamsRefusal, PlanDurationsThePlannerRefuses) {
  const std::string m =
      refusal("vehicle:\n  model: car\nplanner:\n  min_plan_duration_s: 5\n", "4:24");
  EXPECT_TRUE(has(m, "planner.min_plan_duration_s (5.000000) exceeds max_plan_duration_s")) << m;
}

TEST(ParamsRefusal, AFrontierApproachRangeInsideTheClearance) {
  const std::string m = refusal(
      "vehicle:\n  model: car\nexploration:\n  frontier:\n    approach_range_m: 0.2\n", "5:23");
  EXPECT_TRUE(has(m, "exploration.frontier.approach_range_m must be")) << m;
}

TEST(ParamsRefusal, ABadTopicPrefix) {
  const std::string m = refusal("vehicle:\n  model: car\nlink:\n  topic_prefix: 9lives\n", "4:17");
  EXPECT_TRUE(has(m,
                  "link.topic_prefix must be empty or up to 64 of [A-Za-z0-9_], starting with "
                  "a letter (got '9lives')"))
      << m;
  refusal("vehicle:\n  model: car\nlink:\n  topic_prefix: robot-7\n", "4:17");
}

TEST(ParamsRefusal, ADuplicatedKeyAtItsSecondPlace) {
  const std::string m = refusal(
      "vehicle:\n  model: car\nplanner:\n  cycle_s: 0.1\n  budget_s: 0.02\n  cycle_s: 0.2\n",
      "6:3");
  EXPECT_TRUE(has(m, "planner.cycle_s: duplicate key (first at line 4)")) << m;
  const std::string section = refusal("vehicle:\n  model: car\nvehicle:\n  model: car\n", "3:1");
  EXPECT_TRUE(has(section, "vehicle: duplicate key")) << section;
}

TEST(ParamsRefusal, NonFiniteNumbers) {
  for (const char* value : {".nan", ".inf", "-.Inf", "nan", "1e999"}) {
    const std::string m = refusal(
        "vehicle:\n  model: car\nplanner:\n  cycle_s: " + std::string(value) + "\n", "4:12");
    EXPECT_TRUE(has(m, "planner.cycle_s: expected a finite number")) << m;
  }
}

TEST(ParamsRefusal, ASecondDocument) {
  const std::string m = refusal("vehicle:\n  model: car\n---\nvehicle:\n  model: car\n", "4:1");
  EXPECT_TRUE(has(m, "a second YAML document")) << m;
}

TEST(ParamsRefusal, APathThatCannotBeOpened) {
  const std::string path = ::testing::TempDir() + "no-such-folder/robot.yaml";
  EXPECT_TRUE(has(load_refusal(path), "cannot open the parameter file"));
}

TEST(ParamsRefusal, ADirectory) {
  EXPECT_TRUE(has(load_refusal(::testing::TempDir()), "is a directory"));
}

TEST(ParamsRefusal, ADeviceThatNeverEnds) {
  EXPECT_TRUE(has(load_refusal("/dev/zero"), "is not a regular file"));
}

TEST(ParamsRefusal, AFifoWithoutWaitingForAWriter) {
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

TEST(ParamsRefusal, AFileLargerThanAMebibyte) {
  const std::string path = ::testing::TempDir() + "grip-params-large.yaml";
  {
    std::ofstream out(path);
    out << "vehicle:\n  model: car\n" << std::string((1 << 20) + 1, '#') << "\n";
  }
  EXPECT_TRUE(has(load_refusal(path), "is larger than 1048576 bytes"));
  std::remove(path.c_str());
}

TEST(ParamsRefusal, AFileNamesItselfInItsErrors) {
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
