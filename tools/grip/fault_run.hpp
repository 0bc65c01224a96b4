#pragma once
// One run of `grip bench faults`: a `grip planner` in the planner's network namespace and a
// `grip sim` in the vehicle's, a fault made on the link between them (or a process killed and
// started again) some wall-clock seconds into the run, until the simulator ends. What the run
// came to is the simulator's report, with what the fault cost: plans lost on the way, and how
// long the vehicle took to move again once the fault was over.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fault_profile.hpp"
#include "netns_pair.hpp"

namespace grip::tools {

struct FaultRunSetup {
  std::string grip;                     // the executable
  const NetnsPair* link = nullptr;      // the two namespaces
  std::vector<std::string> world_args;  // --scene NAME or --map FILE
  std::string robot;                    // a built-in vehicle or a parameter file
  std::uint64_t seed = 1;
  double time_scale = 2.0;
  double max_sim_time_s = 1800.0;
  double fault_at_s = 10.0;  // wall-clock seconds after the simulator's start
  unsigned domain = 0;
  std::string planner_dds_config;  // Cyclone files of each end
  std::string vehicle_dds_config;
  std::string stem;  // out_dir/stem: the run's reports and logs
};

struct FaultRunOutcome {
  std::string profile;
  std::string robot;
  std::string result;     // the simulator's, or "no report"
  nlohmann::json report;  // the (last) simulator's report; null without one
  int sim_exit_status = -1;
  unsigned planner_starts = 0;
  unsigned vehicle_starts = 0;
  // On the (last) simulator's timeline [s simulated], from the wall clock counted back from its
  // end; unset when the fault did not happen or does not end. A vehicle restart is at 0.
  std::optional<double> fault_start_s;
  std::optional<double> fault_end_s;
  std::optional<double> recovery_s;        // see recovery_time()
  std::optional<std::int64_t> plans_lost;  // published by the planner(s), not received
  std::string error;                       // what went wrong around the run itself
  double wall_time_s = 0.0;

  bool target_met() const {
    return error.empty() && result == "complete" && report.value("collisions", 1) == 0;
  }
};

FaultRunOutcome run_fault_profile(const FaultRunSetup& setup, const FaultProfile& profile);

// Simulated seconds from the fault's end until the vehicle moves again after the rest the fault
// caused: the first rest (below 5% of top speed for at least 0.5 s; a turn in place is shorter)
// that ends after the fault began; 0 when it did not rest within 10 s of the fault's end; unset
// when it never moved again. `speed_profile` is the report's [[t, |v|], ...].
std::optional<double> recovery_time(const nlohmann::json& speed_profile, double top_speed_m_s,
                                    double fault_start_s, double fault_end_s);

}  // namespace grip::tools
