// `grip stress` run for real, briefly: it runs the planner on the planning thread, writes a
// sane report, allocates nothing on that thread after warm-up, and refuses bad timing options.
// No timing is asserted: the machines running the tests are shared and noisy.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "grip_command.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::kGrip;

CommandRun run(const std::string& arguments) { return grip::testing::run_grip(arguments); }

bool sanitized() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return true;
#else
  return false;
#endif
}

TEST(StressCommand, AShortRunWritesASaneReportWithoutAllocationsOnThePlanningThread) {
  const std::string report_path = ::testing::TempDir() + "grip-stress-report.json";
  // A sanitized planner runs several times slower (a whole-map pass takes tens of ms), so it
  // gets a proportionate period: the same 40 cycles, each with time to grow the tree.
  const std::string timing = sanitized() ? "--duration 8 --period-ms 200 --budget-ms 100"
                                         : "--duration 2 --period-ms 50 --budget-ms 25";
  const CommandRun r = run("stress " + timing + " --report " + report_path);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(report_path);
  ASSERT_TRUE(in.good()) << r.output;
  const nlohmann::json report = nlohmann::json::parse(in);

  EXPECT_EQ(report.at("cycles").get<int>(), 40);
  const double miss_rate = report.at("miss_rate").get<double>();
  EXPECT_GE(miss_rate, 0.0);
  EXPECT_LE(miss_rate, 1.0);
  // Skipped releases (woken after the next was due) are among the misses.
  EXPECT_LE(report.at("skipped").get<int>(), report.at("misses").get<int>());
  const std::string policy = report.at("policy");
  EXPECT_TRUE(policy == "deadline" || policy == "fifo" || policy == "other") << policy;
  // A fallback always says why; the first choice says nothing.
  EXPECT_EQ(report.at("policy_fallback_reason").get<std::string>().empty(), policy == "deadline");
  for (const char* key : {"wake_latency_us", "lateness_us", "reference_wake_latency_us"}) {
    ASSERT_TRUE(report.at(key).is_object()) << key;
    for (const char* p : {"p50", "p99", "p999", "max"}) {
      EXPECT_GE(report.at(key).at(p).get<double>(), 0.0) << key << "." << p;
    }
    EXPECT_LE(report.at(key).at("p50").get<double>(), report.at(key).at("max").get<double>());
  }
  EXPECT_TRUE(report.at("overruns").is_number());
  EXPECT_FALSE(report.at("kernel").get<std::string>().empty());
  EXPECT_EQ(report.at("load").at("kind"), "none");
  EXPECT_GT(report.at("planner").at("edges_added").get<double>(), 0.0);
  // Every restart is counted under its cause.
  std::uint64_t restarts_with_cause = 0;
  for (const auto& [cause, count] : report.at("planner").at("restarts_by_cause").items()) {
    EXPECT_NE(cause, "none");
    restarts_with_cause += count.get<std::uint64_t>();
  }
  EXPECT_EQ(restarts_with_cause, report.at("planner").at("restarts").get<std::uint64_t>());
  if (sanitized()) {
    EXPECT_FALSE(report.at("heap_allocations_counted").get<bool>());
    EXPECT_TRUE(report.at("heap_allocations_in_loop").is_null());
  } else {
    ASSERT_TRUE(report.at("heap_allocations_counted").get<bool>()) << r.output;
    EXPECT_EQ(report.at("heap_allocations_in_loop").get<int>(), 0) << r.output;
    // Memory is locked and prefaulted: the loop takes no page fault.
    EXPECT_EQ(report.at("page_faults_in_loop").get<int>(), 0) << r.output;
  }
  std::remove(report_path.c_str());
}

TEST(StressCommand, InconsistentTimingOptionsAreRefusedWithAClearMessage) {
  const CommandRun budget = run("stress --duration 1 --period-ms 50 --budget-ms 50");
  EXPECT_EQ(budget.status, 2);
  EXPECT_NE(budget.output.find("planner.budget_s must be in (0, cycle_s = 0.05) (got 0.05) (set by "
                               "--budget-ms)"),
            std::string::npos)
      << budget.output;
  const CommandRun slow = run("stress --duration 1 --period-ms 5000 --budget-ms 10");
  EXPECT_EQ(slow.status, 2);
  EXPECT_NE(slow.output.find("planner.cycle_s must be in [0.001, 4] (got 5) (set by --period-ms)"),
            std::string::npos)
      << slow.output;
  const CommandRun fast = run("stress --duration 1 --period-ms 0.5 --budget-ms 0.1");
  EXPECT_EQ(fast.status, 2);
  EXPECT_NE(fast.output.find("planner.cycle_s must be in [0.001, 4]"), std::string::npos)
      << fast.output;
  const CommandRun negative = run("stress --duration -3");
  EXPECT_EQ(negative.status, 2);
  EXPECT_NE(negative.output.find("--duration must be in"), std::string::npos) << negative.output;
  const CommandRun load = run("stress --duration 1 --load disk");
  EXPECT_EQ(load.status, 2);
  EXPECT_NE(load.output.find("none | cpu | mem | all"), std::string::npos) << load.output;
}

TEST(StressCommand, AMissRateAboveTheThresholdFailsTheRun) {
  // GIVEN a 50 us budget, which no cycle can meet (retainment alone takes longer), under
  // SCHED_OTHER so that no deadline reservation throttles the run
  const CommandRun r =
      run("stress --duration 1 --period-ms 20 --budget-ms 0.05 --margin-ms 0 "
          "--policy other --max-miss-rate 0");
  // THEN the run completes, reports, and its exit status says the threshold was exceeded
  EXPECT_EQ(r.status, 3) << r.output;
  EXPECT_NE(r.output.find("exceeds --max-miss-rate"), std::string::npos) << r.output;
}

}  // namespace
