#pragma once
// Summaries of the comparison's runs, the targets checked against them, the printed
// table, the JSON report and the Fig. 6-style chart.

#include <cstddef>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "comparison.hpp"
#include "grip/common/result.hpp"

namespace grip::ompl_bridge {

// One planner on one scene and vehicle, over its seeds.
struct PlannerSummary {
  std::string scene;
  std::string vehicle;
  std::string planner;
  std::size_t runs = 0;
  std::size_t solved = 0;    // verified
  std::size_t rejected = 0;  // exact by the planner's account, failed the re-check
  std::size_t errors = 0;    // could not run or crashed
  // Time to the first exact (and verified) solution [s]; a run that did not solve counts as
  // +infinity (it did not solve within the limit), so these are censored order statistics.
  double time_median_s = 0.0;
  double time_p90_s = 0.0;
  double time_max_s = 0.0;
  // Medians over the solved runs (NaN if none).
  double propagations = 0.0;
  double collision_checks = 0.0;
  double tree_size = 0.0;
  double duration_s = 0.0;
  double length_m = 0.0;
};

// The q-quantile with +infinity allowed (the interpolation never multiplies infinity by 0).
double censored_percentile(std::vector<double> v, double q);

std::vector<PlannerSummary> summarize_runs(const std::vector<RunResult>& runs,
                                           const std::vector<std::string>& planners);

// GRIP's median time to a first solution is to be this many times lower than the best OMPL
// planner's, on every scene and vehicle.
inline constexpr double kSpeedTarget = 3.0;

struct TargetReport {
  // Runs (scene, vehicle, seed) some OMPL planner solved and GRIP did not.
  std::vector<std::string> grip_missed;
  struct Speed {
    std::string scene;
    std::string vehicle;
    double grip_median_s;
    std::string best_ompl;  // the OMPL planner with the lowest median time
    double best_ompl_median_s;
    double ratio;  // best OMPL median / GRIP median (inf when OMPL's median run did not solve)
    double propagation_ratio;  // best OMPL planner's median propagations / GRIP's
    double check_ratio;
    bool met;  // ratio >= kSpeedTarget
  };
  std::vector<Speed> speed;
  bool all_solved_met = true;
  bool speed_met = true;
};

TargetReport check_targets(const std::vector<RunResult>& runs,
                           const std::vector<PlannerSummary>& summaries);

void print_table(std::ostream& out, const std::vector<PlannerSummary>& summaries,
                 double time_limit_s);
void print_targets(std::ostream& out, const TargetReport& targets);

// What the comparison holds equal, for the report.
nlohmann::json fairness_notes(double time_limit_s);
nlohmann::json to_json(const PlannerSummary& s);
nlohmann::json to_json(const TargetReport& t);

// Panel 1: median time to the first solution per scene/vehicle and planner (hatched at the time
// limit where the median run did not solve); panel 2: median propagations of the solved runs.
Status write_chart(const std::vector<PlannerSummary>& summaries,
                   const std::vector<std::string>& planners, double time_limit_s, std::size_t seeds,
                   const std::string& path);

}  // namespace grip::ompl_bridge
