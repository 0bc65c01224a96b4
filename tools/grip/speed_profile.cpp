#include "speed_profile.hpp"

#include <cmath>
#include <sstream>

#include "grip/common/assert.hpp"

namespace grip::tools {

SpeedProfileSummary summarize_speed_profile(std::span<const SpeedSample> profile,
                                            double max_speed_m_s) {
  GRIP_ASSERT(max_speed_m_s > 0.0);
  SpeedProfileSummary s;
  s.samples = profile.size();
  if (profile.empty()) return s;
  double sum_m_s = 0.0;
  std::size_t above_50 = 0;
  std::size_t above_80 = 0;
  for (const SpeedSample& p : profile) {
    sum_m_s += p[1];
    if (p[1] > 0.5 * max_speed_m_s) ++above_50;
    if (p[1] > 0.8 * max_speed_m_s) ++above_80;
  }
  const auto n = static_cast<double>(profile.size());
  s.duration_s = profile.back()[0];
  s.mean_speed_m_s = sum_m_s / n;
  s.mean_fraction = s.mean_speed_m_s / max_speed_m_s;
  s.fraction_above_50 = static_cast<double>(above_50) / n;
  s.fraction_above_80 = static_cast<double>(above_80) / n;
  return s;
}

std::vector<SpeedSample> moving_average(std::span<const SpeedSample> profile, double window_s) {
  std::vector<SpeedSample> out;
  out.reserve(profile.size());
  const double half = 0.5 * window_s;
  // The window [t - half, t + half] slides forward: samples enter at `hi`, leave at `lo`.
  std::size_t lo = 0;
  std::size_t hi = 0;
  double sum = 0.0;
  for (const SpeedSample& p : profile) {
    while (hi < profile.size() && profile[hi][0] <= p[0] + half) sum += profile[hi++][1];
    while (profile[lo][0] < p[0] - half) sum -= profile[lo++][1];
    out.push_back({p[0], sum / static_cast<double>(hi - lo)});
  }
  return out;
}

namespace {

Error parse_error(const std::string& message) { return Error{ErrorCode::kParse, message}; }

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A field that must be a string when present.
Status read_text(const nlohmann::json& report, const char* key, std::string& out) {
  const auto it = report.find(key);
  if (it == report.end()) return Ok{};
  if (!it->is_string()) return parse_error(std::string(key) + " is not a string: " + it->dump());
  out = it->get<std::string>();
  return Ok{};
}

Status read_profile(const nlohmann::json& report, std::vector<SpeedSample>& out) {
  const auto it = report.find("speed_profile");
  if (it == report.end()) return parse_error("no speed_profile (a report of grip explore or sim?)");
  if (!it->is_array()) return parse_error("speed_profile is not an array");
  if (it->empty()) return parse_error("speed_profile is empty: nothing to draw");
  out.reserve(it->size());
  for (std::size_t i = 0; i < it->size(); ++i) {
    const nlohmann::json& e = (*it)[i];
    const std::string where = "speed_profile[" + std::to_string(i) + "]";
    if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number()) {
      return parse_error(where + " is not a pair of numbers [t_s, speed_m_s]: " + e.dump());
    }
    const SpeedSample p{e[0].get<double>(), e[1].get<double>()};
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
      return parse_error(where + " is not finite: " + e.dump());
    }
    if (p[0] < 0.0) return parse_error(where + ": time " + number_text(p[0]) + " s is negative");
    if (p[1] < 0.0) {
      return parse_error(where + ": speed " + number_text(p[1]) +
                         " m/s is negative (the profile holds |v|)");
    }
    if (!out.empty() && p[0] < out.back()[0]) {
      return parse_error(where + ": time " + number_text(p[0]) +
                         " s is before the previous sample's (" + number_text(out.back()[0]) +
                         " s): time goes backwards");
    }
    out.push_back(p);
  }
  return Ok{};
}

// A bound's profile (`key`): a speed per sample of the profile, at the sample's time.
Status read_bound(const nlohmann::json& report, const std::string& key,
                  const std::vector<SpeedSample>& profile, std::vector<SpeedSample>& out) {
  const auto it = report.find(key);
  if (it == report.end()) return Ok{};
  if (!it->is_array()) return parse_error(key + " is not an array");
  if (it->empty()) return Ok{};
  if (it->size() != profile.size()) {
    return parse_error(key + " has " + std::to_string(it->size()) + " samples, speed_profile " +
                       std::to_string(profile.size()));
  }
  out.reserve(it->size());
  for (std::size_t i = 0; i < it->size(); ++i) {
    const nlohmann::json& e = (*it)[i];
    if (!e.is_number() || !std::isfinite(e.get<double>()) || e.get<double>() < 0.0) {
      return parse_error(key + "[" + std::to_string(i) + "] is not a speed >= 0: " + e.dump());
    }
    out.push_back({profile[i][0], e.get<double>()});
  }
  return Ok{};
}

// A fraction >= 0 when present; `out` untouched when absent.
Status read_fraction(const nlohmann::json& report, const char* key, double& out) {
  const auto f = report.find(key);
  if (f == report.end()) return Ok{};
  if (!f->is_number() || !std::isfinite(f->get<double>()) || f->get<double>() < 0.0) {
    return parse_error(std::string(key) + " is not a fraction >= 0: " + f->dump());
  }
  out = f->get<double>();
  return Ok{};
}

Status read_collisions(const nlohmann::json& report, std::vector<double>& out) {
  const auto it = report.find("collision_events");
  if (it == report.end()) return Ok{};
  if (!it->is_array()) return parse_error("collision_events is not an array");
  for (std::size_t i = 0; i < it->size(); ++i) {
    const nlohmann::json& e = (*it)[i];
    const std::string where = "collision_events[" + std::to_string(i) + "]";
    if (!e.is_object() || !e.contains("time_s") || !e["time_s"].is_number()) {
      return parse_error(where + " has no numeric time_s: " + e.dump());
    }
    const double t = e["time_s"].get<double>();
    if (!std::isfinite(t) || t < 0.0) {
      return parse_error(where + ": time_s " + number_text(t) + " is not a time >= 0");
    }
    out.push_back(t);
  }
  return Ok{};
}

}  // namespace

Result<SpeedReport> speed_report_from_json(const nlohmann::json& report) {
  if (!report.is_object()) return parse_error("not a JSON object (a report of grip explore?)");
  SpeedReport r;
  if (Status s = read_profile(report, r.profile); !s) return s.error();
  const auto max = report.find("max_speed_m_s");
  if (max == report.end()) return parse_error("no max_speed_m_s (the vehicle's maximum speed)");
  if (!max->is_number() || !std::isfinite(max->get<double>()) || !(max->get<double>() > 0.0)) {
    return parse_error("max_speed_m_s is not a speed > 0: " + max->dump());
  }
  r.max_speed_m_s = max->get<double>();
  if (Status s = read_collisions(report, r.collision_times_s); !s) return s.error();
  for (const auto& [key, out] : {std::pair{"robot", &r.robot}, std::pair{"world", &r.world},
                                 std::pair{"result", &r.result}}) {
    if (Status s = read_text(report, key, *out); !s) return s.error();
  }
  if (Status s = read_fraction(report, "mean_speed_fraction", r.mean_speed_fraction); !s) {
    return s.error();
  }
  for (const auto& [name, bound, fraction] :
       {std::tuple{"braking", &r.braking_bound, &r.braking_bound_fraction},
        std::tuple{"turning", &r.turning_bound, &r.turning_bound_fraction}}) {
    const std::string key = std::string(name) + "_bound_";
    if (Status s = read_bound(report, key + "profile", r.profile, *bound); !s) return s.error();
    if (Status s = read_fraction(report, (key + "fraction").c_str(), *fraction); !s) {
      return s.error();
    }
  }
  return r;
}

}  // namespace grip::tools
