// `grip render REPORT.json --speed-profile OUT.png`: figures from a run report of `grip explore`
// or `grip sim`. The speed profile is the paper's Fig. 9; a short summary goes to stdout.
// Exit status: 0 drawn; 2 a report that cannot be read or is malformed, or bad options;
// 1 an image that cannot be written.

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ios>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "figure.hpp"
#include "speed_profile.hpp"
#include "speed_profile_chart.hpp"

namespace grip::tools {

namespace {

struct RenderOptions {
  std::string report;
  std::string speed_profile;
  SpeedChartOptions chart;
};

constexpr const char* kCommand = "grip render";

// The report's JSON; every failure (no file, not JSON) as an error naming what is wrong.
Result<nlohmann::json> read_report(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error{ErrorCode::kIo, "is a directory"};
  std::ifstream in(path);
  if (!in) return Error{ErrorCode::kIo, "cannot open: " + std::string(std::strerror(errno))};
  try {
    return nlohmann::json::parse(in);
  } catch (const std::ios_base::failure& e) {  // libstdc++ throws from reading what is no file
    return Error{ErrorCode::kIo, "cannot read: " + std::string(e.what())};
  } catch (const nlohmann::json::exception& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line 1, ...".
    const std::string what = e.what();
    const std::size_t end_of_id = what.find("] ");
    return Error{
        ErrorCode::kParse,
        "not JSON: " + (end_of_id == std::string::npos ? what : what.substr(end_of_id + 2))};
  }
}

void print_summary(const RenderOptions& o, const SpeedReport& r, const SpeedProfileSummary& s) {
  std::cout << kCommand << ": " << o.report;
  if (!r.robot.empty()) std::cout << ": " << r.robot;
  if (!r.world.empty()) std::cout << " in " << r.world;
  if (!r.result.empty()) std::cout << ", " << r.result;
  std::cout << "\n  duration " << fixed(s.duration_s, 2) << " s (" << s.samples
            << " samples), collisions " << r.collision_times_s.size() << "\n  mean speed "
            << fixed(s.mean_speed_m_s, 3) << " m/s, " << fixed(s.mean_fraction, 3)
            << " of the maximum " << fixed(r.max_speed_m_s, 3) << " m/s\n"
            << "  fraction of the time above 50% of the maximum " << fixed(s.fraction_above_50, 3)
            << ", above 80% " << fixed(s.fraction_above_80, 3) << "\n";
  if (r.mean_speed_fraction >= 0.0) {
    std::cout << "  the report's mean speed fraction (since the first plan) "
              << fixed(r.mean_speed_fraction, 3) << "\n";
  }
  if (r.braking_bound_fraction >= 0.0) {
    std::cout << "  the report's braking bound fraction (braking within the sensed region) "
              << fixed(r.braking_bound_fraction, 3) << "\n";
  }
  if (r.turning_bound_fraction >= 0.0) {
    std::cout << "  the report's turning bound fraction (the same, within the route's turns) "
              << fixed(r.turning_bound_fraction, 3) << "\n";
  }
}

int run_render(const RenderOptions& o) {
  if (Status s = check_speed_chart_options(o.chart); !s) {
    std::cerr << kCommand << ": " << s.error().message << "\n";
    return 2;
  }
  auto json = read_report(o.report);
  if (!json) {
    std::cerr << kCommand << ": " << o.report << ": " << json.error().message << "\n";
    return 2;
  }
  Result<SpeedReport> report = Error{ErrorCode::kParse, ""};
  try {
    report = speed_report_from_json(*json);
  } catch (const nlohmann::json::exception& e) {  // not expected: the fields are checked first
    report = Error{ErrorCode::kParse, e.what()};
  }
  if (!report) {
    std::cerr << kCommand << ": " << o.report << ": " << report.error().message << "\n";
    return 2;
  }
  const SpeedProfileSummary summary =
      summarize_speed_profile(report->profile, report->max_speed_m_s);
  print_summary(o, *report, summary);
  if (Status s = write_speed_profile_png(*report, summary, o.chart, o.speed_profile); !s) {
    std::cerr << kCommand << ": " << s.error().message << "\n";
    return s.error().code == ErrorCode::kIo ? 1 : 2;
  }
  std::cout << "  speed profile drawn to " << o.speed_profile << "\n";
  return 0;
}

}  // namespace

void register_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Draw figures from a run report of `grip explore` or `grip sim` (--report)");
  cmd->add_option("report", options->report, "The JSON report")->required();
  cmd->add_option("--speed-profile", options->speed_profile,
                  "Draw the speed over simulated time (the paper's Fig. 9) into this PNG")
      ->required();
  cmd->add_option("--smooth", options->chart.smooth_s,
                  "Window of the moving average drawn over the speed [s]; 0: none")
      ->capture_default_str();
  cmd->add_option("--width", options->chart.width_px, "Image width [px], 400 to 8000")
      ->capture_default_str();
  cmd->add_option("--height", options->chart.height_px, "Image height [px], 240 to 4000")
      ->capture_default_str();
  cmd->callback([options]() {
    if (const int rc = run_render(*options); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
