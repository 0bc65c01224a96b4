// `grip planner`'s own options: values it cannot run with are refused before it joins DDS, with
// the option named and exit 2.

#include <gtest/gtest.h>

#include <string>

#include "grip_command.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::run_grip;

TEST(PlannerCommand, DurationsAndStartUpTimeoutsThatAreNotTimesAreRefusedNamingTheOption) {
  for (const char* bad : {"-1", "inf", "nan", "1e12"}) {
    CommandRun r = run_grip(std::string("planner --robot dd-vel --duration ") + bad);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--duration must be"), std::string::npos) << r.output;
    r = run_grip(std::string("planner --robot dd-vel --startup-timeout ") + bad);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--startup-timeout must be in [0, 86400] s"), std::string::npos)
        << r.output;
  }
}

}  // namespace
