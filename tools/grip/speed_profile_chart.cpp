#include "speed_profile_chart.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

namespace grip::tools {

namespace {

constexpr double kLeft = 70.0;
constexpr double kTop = 64.0;
constexpr double kRight = 25.0;
constexpr double kBottom = 56.0;
constexpr double kHeadroom = 1.15;  // the y axis reaches this times the top speed

constexpr Rgb kSpeedColour{0.0, 0.4, 0.8};
constexpr Rgb kAverageColour{0.8, 0.4, 0.0};
constexpr Rgb kMaxColour{0.2, 0.2, 0.2};
constexpr Rgb kCollisionColour{1.0, 0.0, 0.0};
constexpr Rgb kBrakingBoundColour{0.2, 0.65, 0.2};
constexpr Rgb kTurningBoundColour{0.6, 0.2, 0.8};
constexpr Rgb kGridColour{0.88, 0.88, 0.88};

// Data to pixels.
struct Axes {
  PlotArea area;
  double t_max_s;
  double v_max_m_s;

  double x(double t_s) const { return area.left_px + t_s / t_max_s * area.width_px; }
  double y(double v_m_s) const { return area.bottom_px() - v_m_s / v_max_m_s * area.height_px; }
};

std::string title_of(const SpeedReport& r) {
  std::string title = "Speed profile";
  if (!r.robot.empty()) title += ": " + r.robot;
  if (!r.world.empty()) title += (r.robot.empty() ? ": " : " in ") + r.world;
  if (!r.result.empty()) title += ", " + r.result;
  const std::size_t n = r.collision_times_s.size();
  if (n > 0) title += ", " + std::to_string(n) + (n == 1 ? " collision" : " collisions");
  return title;
}

void draw_grid_and_ticks(cairo_t* cr, const Axes& axes) {
  const PlotArea& a = axes.area;
  cairo_set_line_width(cr, 1.0);
  const int x_target = std::max(2, static_cast<int>(a.width_px / 110.0));
  for (const double t : linear_ticks(0.0, axes.t_max_s, x_target)) {
    const double x = axes.x(t);
    set_colour(cr, kGridColour);
    cairo_move_to(cr, x, a.top_px);
    cairo_line_to(cr, x, a.bottom_px());
    cairo_stroke(cr);
    set_colour(cr, {0.2, 0.2, 0.2});
    draw_text(cr, tick_label(t), x, a.bottom_px() + 18.0, 11.0, false, 0.5);
  }
  const int y_target = std::max(2, static_cast<int>(a.height_px / 60.0));
  for (const double v : linear_ticks(0.0, axes.v_max_m_s, y_target)) {
    const double y = axes.y(v);
    set_colour(cr, kGridColour);
    cairo_move_to(cr, a.left_px, y);
    cairo_line_to(cr, a.right_px(), y);
    cairo_stroke(cr);
    set_colour(cr, {0.2, 0.2, 0.2});
    draw_text(cr, tick_label(v), a.left_px - 8.0, y + 4.0, 11.0, false, 1.0);
  }
  set_colour(cr, {0.1, 0.1, 0.1});
  draw_text(cr, "simulated time [s]", a.left_px + a.width_px / 2.0, a.bottom_px() + 42.0, 12.0,
            false, 0.5);
  draw_y_label(cr, a, "speed [m/s]");
}

// A polyline through the samples; a single sample is a dot.
void draw_curve(cairo_t* cr, const Axes& axes, std::span<const SpeedSample> samples, Rgb colour,
                double width_px) {
  set_colour(cr, colour);
  if (samples.size() == 1) {
    cairo_arc(cr, axes.x(samples[0][0]), axes.y(samples[0][1]), width_px * 1.5, 0.0,
              2.0 * std::numbers::pi);
    cairo_fill(cr);
    return;
  }
  cairo_set_line_width(cr, width_px);
  cairo_move_to(cr, axes.x(samples[0][0]), axes.y(samples[0][1]));
  for (std::size_t i = 1; i < samples.size(); ++i) {
    cairo_line_to(cr, axes.x(samples[i][0]), axes.y(samples[i][1]));
  }
  cairo_stroke(cr);
}

// A red triangle standing on the time axis.
void draw_collision_marker(cairo_t* cr, double x_px, double base_y_px) {
  set_colour(cr, kCollisionColour);
  cairo_move_to(cr, x_px - 6.0, base_y_px);
  cairo_line_to(cr, x_px + 6.0, base_y_px);
  cairo_line_to(cr, x_px, base_y_px - 12.0);
  cairo_close_path(cr);
  cairo_fill(cr);
}

// Every collision: a thin line across the plot and a triangle on the time axis.
void draw_collisions(cairo_t* cr, const Axes& axes, std::span<const double> times_s) {
  const PlotArea& a = axes.area;
  for (const double t : times_s) {
    const double x = axes.x(t);
    cairo_set_source_rgba(cr, kCollisionColour.r, kCollisionColour.g, kCollisionColour.b, 0.6);
    cairo_set_line_width(cr, 1.0);
    cairo_move_to(cr, x, a.top_px);
    cairo_line_to(cr, x, a.bottom_px());
    cairo_stroke(cr);
  }
  for (const double t : times_s) draw_collision_marker(cr, axes.x(t), a.bottom_px());
}

// One row under the title: a sample of each line with its name, then the mean speed.
void draw_legend(cairo_t* cr, const SpeedReport& r, const SpeedProfileSummary& s,
                 const SpeedChartOptions& o) {
  const double y = 48.0;
  double x = kLeft;
  const auto swatch = [&](Rgb c, double width_px, bool dashed, const std::string& label) {
    cairo_save(cr);
    if (dashed) set_dashed(cr);
    set_colour(cr, c);
    cairo_set_line_width(cr, width_px);
    cairo_move_to(cr, x, y - 4.0);
    cairo_line_to(cr, x + 26.0, y - 4.0);
    cairo_stroke(cr);
    cairo_restore(cr);
    set_colour(cr, {0.05, 0.05, 0.05});
    x += 32.0 + draw_text(cr, label, x + 32.0, y, 12.0, false) + 24.0;
  };
  swatch(kSpeedColour, 2.0, false, "speed");
  if (!r.braking_bound.empty()) swatch(kBrakingBoundColour, 2.0, false, "braking bound");
  if (!r.turning_bound.empty()) swatch(kTurningBoundColour, 2.0, false, "within its turns");
  if (o.smooth_s > 0.0) swatch(kAverageColour, 2.5, false, tick_label(o.smooth_s) + " s average");
  swatch(kMaxColour, 1.5, true, "maximum " + tick_label(r.max_speed_m_s) + " m/s");
  if (!r.collision_times_s.empty()) {
    draw_collision_marker(cr, x + 8.0, y + 1.0);
    set_colour(cr, {0.05, 0.05, 0.05});
    x += 22.0 + draw_text(cr, "collision", x + 22.0, y, 12.0, false) + 24.0;
  }
  std::string mean = "mean speed " + fixed(s.mean_fraction, 2) + " of the maximum";
  if (r.mean_speed_fraction >= 0.0) {
    mean += " (report: " + fixed(r.mean_speed_fraction, 2) + " since the first plan)";
  }
  if (r.braking_bound_fraction >= 0.0 && !r.braking_bound.empty()) {
    mean += ", bound " + fixed(r.braking_bound_fraction, 2);
  }
  if (r.turning_bound_fraction >= 0.0 && !r.turning_bound.empty()) {
    mean += ", within its turns " + fixed(r.turning_bound_fraction, 2);
  }
  draw_text(cr, mean, x, y, 12.0, true);
}

}  // namespace

PlotArea speed_chart_area(int width_px, int height_px) {
  return {kLeft, kTop, static_cast<double>(width_px) - kLeft - kRight,
          static_cast<double>(height_px) - kTop - kBottom};
}

Status check_speed_chart_options(const SpeedChartOptions& options) {
  if (options.width_px < 400 || options.width_px > 8000 || options.height_px < 240 ||
      options.height_px > 4000) {
    return invalid_argument("the chart must be 400 to 8000 pixels wide and 240 to 4000 high (got " +
                            std::to_string(options.width_px) + "x" +
                            std::to_string(options.height_px) + ")");
  }
  if (!(std::isfinite(options.smooth_s) && options.smooth_s >= 0.0)) {
    return invalid_argument("the moving-average window (--smooth) must be a time >= 0 s");
  }
  return Ok{};
}

Status write_speed_profile_png(const SpeedReport& report, const SpeedProfileSummary& summary,
                               const SpeedChartOptions& options, const std::string& path) {
  if (Status s = check_speed_chart_options(options); !s) return s;
  if (report.profile.empty() || !(report.max_speed_m_s > 0.0)) {
    return invalid_argument("a speed profile needs samples and a maximum speed > 0");
  }
  auto figure = Figure::create(options.width_px, options.height_px);
  if (!figure) return figure.error();
  cairo_t* cr = figure->cr();
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);

  double t_max_s = report.profile.back()[0];
  for (const double t : report.collision_times_s) t_max_s = std::max(t_max_s, t);
  if (!(t_max_s > 0.0)) t_max_s = 1.0;
  double fastest_m_s = report.max_speed_m_s;
  for (const SpeedSample& p : report.profile) fastest_m_s = std::max(fastest_m_s, p[1]);
  const Axes axes{speed_chart_area(options.width_px, options.height_px), t_max_s,
                  kHeadroom * fastest_m_s};

  set_colour(cr, {0.0, 0.0, 0.0});
  draw_text(cr, title_of(report), kLeft, 24.0, 16.0, true);
  draw_legend(cr, report, summary, options);
  draw_grid_and_ticks(cr, axes);
  draw_dashed_hline(cr, axes.area, axes.y(report.max_speed_m_s), kMaxColour, 1.5);

  cairo_save(cr);
  cairo_rectangle(cr, axes.area.left_px, axes.area.top_px, axes.area.width_px, axes.area.height_px);
  cairo_clip(cr);
  // The bounds under the speed: where they meet, the vehicle drove as fast as braking (and its
  // turns) allowed.
  if (!report.braking_bound.empty()) {
    draw_curve(cr, axes, report.braking_bound, kBrakingBoundColour, 2.0);
  }
  if (!report.turning_bound.empty()) {
    draw_curve(cr, axes, report.turning_bound, kTurningBoundColour, 2.0);
  }
  draw_curve(cr, axes, report.profile, kSpeedColour, 2.0);
  if (options.smooth_s > 0.0) {
    draw_curve(cr, axes, moving_average(report.profile, options.smooth_s), kAverageColour, 2.5);
  }
  cairo_restore(cr);
  draw_axes(cr, axes.area);
  draw_collisions(cr, axes, report.collision_times_s);
  return figure->write_png(path);
}

}  // namespace grip::tools
