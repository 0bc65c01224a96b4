// `grip bench dds` for real, briefly: the planner as a child process publishing plans to this
// bench's vehicle, which follows them, and ddsperf beside it. Its figures are measured, not
// asserted here; what must hold is that both sides measured something and that the vehicle
// was planned for as a vehicle following its plans.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "grip_command.hpp"

namespace {

TEST(BenchDdsCommand, MeasuresBothSidesWithAVehicleThatFollowsThePlans) {
  const std::string json = ::testing::TempDir() + "grip-bench-dds.json";
  const grip::testing::CommandRun r =
      grip::testing::run_grip("bench dds --duration 4 --domain 88 --json " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  const auto plans = j.at("planner").at("count").get<std::uint64_t>();
  EXPECT_GE(plans, 40U) << r.output;  // 20 Hz for 4 s
  EXPECT_GT(j.at("planner").at("p99").get<double>(), 0.0);
  EXPECT_GT(j.at("ddsperf").at("round_trips").get<std::uint64_t>(), 0U) << r.output;
  // It drove along the plans; a vehicle standing still while claiming to follow them would be
  // found off its plans every cycle. A plan delayed past its start by a stall may be refused
  // and noticed now and then, not every cycle.
  const nlohmann::json& vehicle = j.at("vehicle");
  EXPECT_GT(vehicle.at("distance_m").get<double>(), 1.0) << r.output;
  EXPECT_LT(vehicle.at("planner_found_it_off_its_plans").get<std::uint64_t>(), plans / 10)
      << r.output;
}

}  // namespace
