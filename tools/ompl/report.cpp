#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>
#include <tuple>

#include "bar_chart.hpp"
#include "grip/planner/planner_config.hpp"
#include "stats.hpp"

namespace grip::ompl_bridge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// A time for the table: "> limit" where the order statistic is a run that did not solve.
std::string format_time(double s, double limit_s) {
  std::ostringstream o;
  if (!std::isfinite(s)) {
    o << ">" << std::setprecision(3) << limit_s;
  } else if (s < 0.1) {
    o << std::fixed << std::setprecision(4) << s;
  } else {
    o << std::fixed << std::setprecision(2) << s;
  }
  return o.str();
}

std::string format_count(double v) {
  if (std::isnan(v)) return "-";
  std::ostringstream o;
  if (v >= 1e6) {
    o << std::fixed << std::setprecision(1) << v / 1e6 << "M";
  } else if (v >= 1e4) {
    o << std::fixed << std::setprecision(1) << v / 1e3 << "k";
  } else {
    o << std::llround(v);
  }
  return o.str();
}

std::string format_fixed(double v, int digits) {
  if (std::isnan(v)) return "-";
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

// Scene and vehicle pairs in the order the runs first name them.
std::vector<std::pair<std::string, std::string>> experiments_of(
    const std::vector<PlannerSummary>& summaries) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const PlannerSummary& s : summaries) {
    const std::pair<std::string, std::string> e{s.scene, s.vehicle};
    if (std::find(out.begin(), out.end(), e) == out.end()) out.push_back(e);
  }
  return out;
}

double median_or_nan(const std::vector<double>& v) { return tools::median(v); }

}  // namespace

double censored_percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = static_cast<std::size_t>(std::ceil(pos));
  const double frac = pos - static_cast<double>(lo);
  if (frac == 0.0 || lo == hi) return v[lo];
  if (!std::isfinite(v[hi])) return kInf;
  return v[lo] + (v[hi] - v[lo]) * frac;
}

std::vector<PlannerSummary> summarize_runs(const std::vector<RunResult>& runs,
                                           const std::vector<std::string>& planners) {
  std::vector<std::pair<std::string, std::string>> experiments;
  for (const RunResult& r : runs) {
    const std::pair<std::string, std::string> e{r.spec.scene, r.spec.vehicle};
    if (std::find(experiments.begin(), experiments.end(), e) == experiments.end()) {
      experiments.push_back(e);
    }
  }
  std::vector<PlannerSummary> out;
  for (const auto& [scene, vehicle] : experiments) {
    for (const std::string& planner : planners) {
      PlannerSummary s{scene, vehicle, planner};
      std::vector<double> times;
      std::vector<double> props;
      std::vector<double> checks;
      std::vector<double> tree;
      std::vector<double> duration;
      std::vector<double> length;
      for (const RunResult& r : runs) {
        if (r.spec.scene != scene || r.spec.vehicle != vehicle || r.spec.planner != planner) {
          continue;
        }
        ++s.runs;
        if (!r.error.empty()) ++s.errors;
        if (r.exact && !r.verified) ++s.rejected;
        if (!r.verified) {
          times.push_back(kInf);
          continue;
        }
        ++s.solved;
        times.push_back(r.solve_time_s);
        props.push_back(static_cast<double>(r.propagations));
        checks.push_back(static_cast<double>(r.collision_checks));
        tree.push_back(static_cast<double>(r.tree_size));
        duration.push_back(r.duration_s);
        length.push_back(r.length_m);
      }
      if (s.runs == 0) continue;
      s.time_median_s = censored_percentile(times, 0.5);
      s.time_p90_s = censored_percentile(times, 0.9);
      s.time_max_s = censored_percentile(times, 1.0);
      s.propagations = median_or_nan(props);
      s.collision_checks = median_or_nan(checks);
      s.tree_size = median_or_nan(tree);
      s.duration_s = median_or_nan(duration);
      s.length_m = median_or_nan(length);
      out.push_back(s);
    }
  }
  return out;
}

TargetReport check_targets(const std::vector<RunResult>& runs,
                           const std::vector<PlannerSummary>& summaries) {
  TargetReport t;
  // Target 1: per scene, vehicle and seed.
  std::map<std::tuple<std::string, std::string, std::uint32_t>, std::pair<bool, std::string>>
      by_run;  // GRIP solved; the OMPL planners that solved
  for (const RunResult& r : runs) {
    auto& entry = by_run[{r.spec.scene, r.spec.vehicle, r.spec.seed}];
    if (r.spec.planner == "grip") {
      entry.first = r.verified;
    } else if (r.verified) {
      entry.second += (entry.second.empty() ? "" : ",") + r.spec.planner;
    }
  }
  for (const auto& [key, entry] : by_run) {
    if (!entry.first && !entry.second.empty()) {
      t.grip_missed.push_back(std::get<0>(key) + " / " + std::get<1>(key) + " / seed " +
                              std::to_string(std::get<2>(key)) + " (solved by " + entry.second +
                              ")");
    }
  }
  t.all_solved_met = t.grip_missed.empty();
  // Target 2: per scene and vehicle.
  for (const auto& [scene, vehicle] : experiments_of(summaries)) {
    const PlannerSummary* grip = nullptr;
    const PlannerSummary* best = nullptr;
    for (const PlannerSummary& s : summaries) {
      if (s.scene != scene || s.vehicle != vehicle) continue;
      if (s.planner == "grip") {
        grip = &s;
      } else if (best == nullptr || s.time_median_s < best->time_median_s) {
        best = &s;
      }
    }
    if (grip == nullptr || best == nullptr) continue;
    TargetReport::Speed sp{scene,
                           vehicle,
                           grip->time_median_s,
                           best->planner,
                           best->time_median_s,
                           best->time_median_s / grip->time_median_s,
                           best->propagations / grip->propagations,
                           best->collision_checks / grip->collision_checks,
                           false};
    // An unsolved GRIP median never meets it; an unsolved OMPL median loses to a solved one.
    if (!std::isfinite(grip->time_median_s)) sp.ratio = 0.0;
    sp.met = sp.ratio >= kSpeedTarget;
    t.speed_met = t.speed_met && sp.met;
    t.speed.push_back(sp);
  }
  return t;
}

void print_table(std::ostream& out, const std::vector<PlannerSummary>& summaries,
                 double time_limit_s) {
  out << std::left << std::setw(12) << "scene" << std::setw(10) << "vehicle" << std::setw(9)
      << "planner" << std::right << std::setw(8) << "solved" << std::setw(5) << "rej"
      << std::setw(9) << "t med s" << std::setw(9) << "t p90 s" << std::setw(9) << "t max s"
      << std::setw(9) << "props" << std::setw(9) << "checks" << std::setw(8) << "tree"
      << std::setw(8) << "dur s" << std::setw(8) << "len m"
      << "\n";
  std::string previous;
  for (const PlannerSummary& s : summaries) {
    const std::string experiment = s.scene + "/" + s.vehicle;
    if (!previous.empty() && experiment != previous) out << "\n";
    previous = experiment;
    std::ostringstream solved;
    solved << s.solved << "/" << s.runs;
    out << std::left << std::setw(12) << s.scene << std::setw(10) << s.vehicle << std::setw(9)
        << s.planner << std::right << std::setw(8) << solved.str() << std::setw(5) << s.rejected
        << std::setw(9) << format_time(s.time_median_s, time_limit_s) << std::setw(9)
        << format_time(s.time_p90_s, time_limit_s) << std::setw(9)
        << format_time(s.time_max_s, time_limit_s) << std::setw(9) << format_count(s.propagations)
        << std::setw(9) << format_count(s.collision_checks) << std::setw(8)
        << format_count(s.tree_size) << std::setw(8) << format_fixed(s.duration_s, 1)
        << std::setw(8) << format_fixed(s.length_m, 1) << (s.errors > 0 ? "  errors: " : "")
        << (s.errors > 0 ? std::to_string(s.errors) : "") << "\n";
  }
}

void print_targets(std::ostream& out, const TargetReport& t) {
  out << "\nTarget: GRIP solves every run that any OMPL planner solves: "
      << (t.all_solved_met ? "met" : "NOT met") << "\n";
  for (const std::string& m : t.grip_missed) out << "  GRIP missed " << m << "\n";
  out << "Target: GRIP's median time to first solution >= " << kSpeedTarget
      << "x lower than the best OMPL planner's: " << (t.speed_met ? "met" : "NOT met") << "\n";
  out << std::left << std::setw(13) << "  scene" << std::setw(10) << "vehicle" << std::right
      << std::setw(11) << "GRIP med s" << std::setw(10) << "best OMPL" << std::setw(10) << "med s"
      << std::setw(9) << "ratio" << std::setw(12) << "props x" << std::setw(12) << "checks x"
      << "\n";
  for (const auto& s : t.speed) {
    std::ostringstream ratio;
    if (std::isinf(s.ratio)) {
      ratio << "inf";
    } else {
      ratio << std::fixed << std::setprecision(1) << s.ratio;
    }
    out << std::left << std::setw(13) << ("  " + s.scene) << std::setw(10) << s.vehicle
        << std::right << std::setw(11) << format_time(s.grip_median_s, NAN) << std::setw(10)
        << s.best_ompl << std::setw(10) << format_time(s.best_ompl_median_s, NAN) << std::setw(9)
        << ratio.str() << std::setw(12) << format_fixed(s.propagation_ratio, 1) << std::setw(12)
        << format_fixed(s.check_ratio, 1) << (s.met ? "" : "   <- below the target") << "\n";
  }
  out << "  (props x, checks x: the best OMPL planner's median work per solved run over GRIP's)\n";
}

nlohmann::json fairness_notes(double time_limit_s) {
  const PlannerConfig config;
  return {
      {"dynamics",
       "the core vehicle models; OMPL's StatePropagator calls vehicle.step once per "
       "propagation step"},
      {"propagation_step_s", config.integration_step_s},
      {"control_duration_s", {config.min_plan_duration_s, config.max_plan_duration_s}},
      {"controls", "the vehicle's sample_control, for GRIP and (through a ControlSampler) OMPL"},
      {"collision_checker",
       "the core CollisionChecker with the planner's margin (half a step's chassis motion at "
       "the state's speed), "
       "once per propagation step"},
      {"goal",
       "the scene's goal disk (reference point within the radius); OMPL: Goal "
       "with distanceGoal = distance to the goal point, threshold = radius, sampleable"},
      {"projection", "(x, y), 1 m cells, the default for KPIECE1, PDST and EST"},
      {"sst",
       "path-length objective with an infinite cost threshold: stops at the first "
       "solution"},
      {"other_ompl_parameters", "OMPL 1.5 defaults"},
      {"seeds",
       "the same seed per run for every planner; ompl::RNG::setSeed in a fresh "
       "process before anything of OMPL is built"},
      {"timing",
       "only the solve call; setup (GRIP: create, set_problem; OMPL: setup()) "
       "excluded; one thread per run"},
      {"time_limit_s", time_limit_s},
      {"counts",
       "propagations = vehicle.step calls (GRIP: random plans and braking "
       "maneuvers), collision_checks = CollisionChecker::is_free calls, both during "
       "the solve"},
      {"tree_size", "GRIP: edges added; OMPL: planner-data vertices"},
      {"recheck",
       "every returned plan re-propagated from the start by the core: coarse at the "
       "step (must match the planner's states and end in the goal) and fine at a "
       "tenth of it, checked with a tenth of the margin; a failure counts as "
       "unsolved"},
      {"time_statistics",
       "over all runs, a run that did not solve counting as beyond the "
       "limit; work, duration and length: medians over solved runs"}};
}

nlohmann::json to_json(const PlannerSummary& s) {
  return {{"scene", s.scene},
          {"vehicle", s.vehicle},
          {"planner", s.planner},
          {"runs", s.runs},
          {"solved", s.solved},
          {"rejected_by_recheck", s.rejected},
          {"errors", s.errors},
          {"time_median_s", number_or_null(s.time_median_s)},
          {"time_p90_s", number_or_null(s.time_p90_s)},
          {"time_max_s", number_or_null(s.time_max_s)},
          {"propagations_median", number_or_null(s.propagations)},
          {"collision_checks_median", number_or_null(s.collision_checks)},
          {"tree_size_median", number_or_null(s.tree_size)},
          {"duration_median_s", number_or_null(s.duration_s)},
          {"length_median_m", number_or_null(s.length_m)}};
}

nlohmann::json to_json(const TargetReport& t) {
  nlohmann::json speed = nlohmann::json::array();
  for (const auto& s : t.speed) {
    speed.push_back(
        {{"scene", s.scene},
         {"vehicle", s.vehicle},
         {"grip_median_s", number_or_null(s.grip_median_s)},
         {"best_ompl", s.best_ompl},
         {"best_ompl_median_s", number_or_null(s.best_ompl_median_s)},
         {"ratio", std::isinf(s.ratio) ? nlohmann::json("inf") : nlohmann::json(s.ratio)},
         {"propagation_ratio", number_or_null(s.propagation_ratio)},
         {"check_ratio", number_or_null(s.check_ratio)},
         {"met", s.met}});
  }
  return {{"grip_solves_all_ompl_solved", t.all_solved_met},
          {"grip_missed", t.grip_missed},
          {"median_time_lower_by", kSpeedTarget},
          {"median_time_lower_by_met", t.speed_met},
          {"speed", speed}};
}

Status write_chart(const std::vector<PlannerSummary>& summaries,
                   const std::vector<std::string>& planners, double time_limit_s, std::size_t seeds,
                   const std::string& path) {
  BarPanel time{"Median time to first solution (" + std::to_string(seeds) +
                    " seeds; hatched: the median run did not solve within " +
                    format_fixed(time_limit_s, 0) + " s; above the bars: solved/runs)",
                "seconds (log)",
                {},
                time_limit_s};
  BarPanel work{
      "Median propagations (vehicle.step calls) of the solved runs", "steps (log)", {}, 0.0};
  for (const auto& [scene, vehicle] : experiments_of(summaries)) {
    BarGroup t{scene + " / " + vehicle, {}, {}};
    BarGroup w{scene + " / " + vehicle, {}, {}};
    for (const std::string& planner : planners) {
      const auto it = std::find_if(summaries.begin(), summaries.end(), [&](const auto& s) {
        return s.scene == scene && s.vehicle == vehicle && s.planner == planner;
      });
      if (it == summaries.end()) {
        t.values.push_back(NAN);
        w.values.push_back(NAN);
        t.notes.emplace_back("");
        w.notes.emplace_back("");
        continue;
      }
      t.values.push_back(it->time_median_s);
      t.notes.push_back(std::to_string(it->solved) + "/" + std::to_string(it->runs));
      w.values.push_back(it->propagations);
      w.notes.emplace_back(std::isnan(it->propagations) ? "none" : "");
      if (!std::isnan(it->propagations)) work.y_max = std::max(work.y_max, it->propagations);
    }
    time.groups.push_back(t);
    work.groups.push_back(w);
  }
  work.y_max = work.y_max > 0.0 ? std::pow(10.0, std::ceil(std::log10(work.y_max) + 1e-9)) : 10.0;
  return write_bar_chart_png(planners, {time, work}, path);
}

}  // namespace grip::ompl_bridge
