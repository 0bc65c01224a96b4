// `grip bench dds` for real, briefly: the planner as a child process publishing plans to this
// bench's vehicle, which follows them, and ddsperf in turn with it, round by round. Its
// figures are measured, not asserted here; what must hold is that both sides measured
// something in each round and that the vehicle was planned for as a vehicle following its
// plans.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "grip_command.hpp"

namespace {

TEST(BenchDdsCommand, MeasuresBothSidesWithAVehicleThatFollowsThePlans) {
  const std::string json = ::testing::TempDir() + "grip-bench-dds.json";
  const grip::testing::CommandRun r =
      grip::testing::run_grip("bench dds --duration 6 --rounds 2 --domain 88 --json " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  const auto plans = j.at("planner").at("count").get<std::uint64_t>();
  EXPECT_GE(plans, 40U) << r.output;  // 20 Hz for 2 x 3 s, of which the first second not measured
  EXPECT_GT(j.at("planner").at("p99").get<double>(), 0.0);
  // Both sides measured in each round, in turn.
  EXPECT_EQ(j.at("rounds").get<unsigned>(), 2U);
  EXPECT_EQ(j.at("planner").at("rounds").size(), 2U);
  // Each round names its slowest plans, slowest first, within the round and the pooled max.
  for (const nlohmann::json& round : j.at("planner").at("rounds")) {
    const nlohmann::json& slowest = round.at("slowest_s_us");
    ASSERT_GE(slowest.size(), 1U);
    EXPECT_LE(slowest.size(), 3U);
    double previous = j.at("planner").at("max").get<double>() + 1e-3;
    for (const nlohmann::json& plan : slowest) {
      EXPECT_GE(plan[0].get<double>(), 0.0);
      EXPECT_LE(plan[0].get<double>(), 3.0);  // measured after the round's first second
      EXPECT_LE(plan[1].get<double>(), previous);
      previous = plan[1].get<double>();
    }
  }
  for (int round = 1; round <= 2; ++round) {
    EXPECT_NE(r.output.find("round " + std::to_string(round) + ": plan delivery p99"),
              std::string::npos)
        << r.output;
  }
  // ddsperf's first second of each round (discovery) is dropped: at least 2 x 2 windows.
  EXPECT_GE(j.at("ddsperf").at("p99_us_per_second").size(), 4U) << r.output;
  EXPECT_GT(j.at("ddsperf").at("round_trips").get<std::uint64_t>(), 0U) << r.output;
  // It drove along the plans; a vehicle standing still while claiming to follow them would be
  // found off its plans every cycle. A plan delayed past its start by a stall may be refused
  // and noticed now and then, not every cycle.
  const nlohmann::json& vehicle = j.at("vehicle");
  EXPECT_GT(vehicle.at("distance_m").get<double>(), 1.0) << r.output;
  EXPECT_LT(vehicle.at("planner_found_it_off_its_plans").get<std::uint64_t>(), plans / 10)
      << r.output;
}

TEST(BenchDdsCommand, RoundsTooShortForDdsperfAreRefusedBeforeAnythingRuns) {
  const grip::testing::CommandRun r =
      grip::testing::run_grip("bench dds --duration 4 --rounds 4 --domain 88");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("leaves 1 s per round and side; at least 3 are needed"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("planner -> subscriber"), std::string::npos) << r.output;
}

}  // namespace
