#pragma once
// The velocity profile of a run (the paper's Fig. 9): the vehicle's speed sampled once per
// simulated tick, what it says in a few numbers, and the report fields `grip render` draws it
// from. The numbers are computed here only, for `grip explore`'s report and for `grip render`.

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::tools {

// [t_s, speed_m_s]: simulated time since the run started [s] and |v| [m/s], one per tick.
using SpeedSample = std::array<double, 2>;

// Over the samples, each standing for one tick (so the fractions are fractions of the time).
// An empty profile gives zeros.
struct SpeedProfileSummary {
  std::size_t samples = 0;
  double duration_s = 0.0;         // the last sample's time
  double mean_speed_m_s = 0.0;     // mean over the samples
  double mean_fraction = 0.0;      // mean_speed_m_s / max_speed_m_s
  double fraction_above_50 = 0.0;  // of the samples faster than 0.5 x max_speed_m_s
  double fraction_above_80 = 0.0;  // of the samples faster than 0.8 x max_speed_m_s
};

// max_speed_m_s must be > 0.
SpeedProfileSummary summarize_speed_profile(std::span<const SpeedSample> profile,
                                            double max_speed_m_s);

// A centred moving average over `window_s` seconds: each sample's speed becomes the mean of the
// samples within window_s / 2 of its time (fewer at the ends). Times must not decrease.
std::vector<SpeedSample> moving_average(std::span<const SpeedSample> profile, double window_s);

// What `grip render --speed-profile` needs from a run report (`grip explore --report`).
struct SpeedReport {
  std::vector<SpeedSample> profile;       // non-empty; times >= 0, never decreasing; speeds >= 0
  double max_speed_m_s = 0.0;             // > 0
  std::vector<double> collision_times_s;  // >= 0, from collision_events
  std::string robot;                      // "" when the report has none; likewise world, result
  std::string world;
  std::string result;
  double mean_speed_fraction = -1.0;  // the report's (since the first plan); < 0: absent
  // The speed braking within the sensed region allowed at each sample's time (finite, >= 0;
  // sim/braking_bound.hpp); empty when the report has none (a vehicle that stops at once).
  std::vector<SpeedSample> braking_bound;
  double braking_bound_fraction = -1.0;  // the report's; < 0: absent
  // The same within what the route's turns allow (sim/turning_bound.hpp).
  std::vector<SpeedSample> turning_bound;
  double turning_bound_fraction = -1.0;
};

// Reads and checks the fields above. Errors (kParse) say what is wrong and where, e.g.
// "speed_profile[3]: time 0.1 s is before the previous sample's (0.15 s)"; the caller adds the
// file name.
Result<SpeedReport> speed_report_from_json(const nlohmann::json& report);

}  // namespace grip::tools
