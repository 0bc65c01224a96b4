#include "scale_chart.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grip::tools {

namespace {

constexpr double kLeft = 80.0;
constexpr double kTop = 64.0;
constexpr double kRight = 170.0;
constexpr double kBottom = 60.0;
constexpr double kMarkerPx = 9.0;
constexpr double kFloorMs = 1e-3;  // the y axis reaches down to 1 us at least

constexpr Rgb kColours[kScalePhases.size()] = {
    {0.8, 0.4, 0.0}, {0.0, 0.6, 0.533}, {0.0, 0.4, 0.8}, {0.6, 0.2, 0.8}, {0.0, 0.0, 0.0}};
constexpr Rgb kGridColour{0.88, 0.88, 0.88};

bool drawn(double ms) { return std::isfinite(ms) && ms > 0.0; }

// log10 axes over whole decades.
struct LogAxes {
  PlotArea area;
  double x_lo;  // decades
  double x_hi;
  double y_lo;
  double y_hi;

  double x(double cells) const {
    return area.left_px + (std::log10(cells) - x_lo) / (x_hi - x_lo) * area.width_px;
  }
  double y(double ms) const {
    return area.bottom_px() - (std::log10(ms) - y_lo) / (y_hi - y_lo) * area.height_px;
  }
};

std::string decade_label(int decade, const char* unit) {
  if (decade >= 6) return tick_label(std::pow(10.0, decade - 6)) + " M" + unit;
  if (decade >= 3) return tick_label(std::pow(10.0, decade - 3)) + " k" + unit;
  return tick_label(std::pow(10.0, decade)) + unit;
}

void draw_grid(cairo_t* cr, const LogAxes& axes) {
  const PlotArea& a = axes.area;
  cairo_set_line_width(cr, 1.0);
  for (int d = static_cast<int>(axes.x_lo); d <= static_cast<int>(axes.x_hi); ++d) {
    const double x = axes.x(std::pow(10.0, d));
    set_colour(cr, kGridColour);
    cairo_move_to(cr, x, a.top_px);
    cairo_line_to(cr, x, a.bottom_px());
    cairo_stroke(cr);
    set_colour(cr, {0.2, 0.2, 0.2});
    draw_text(cr, decade_label(d, ""), x, a.bottom_px() + 18.0, 11.0, false, 0.5);
  }
  for (int d = static_cast<int>(axes.y_lo); d <= static_cast<int>(axes.y_hi); ++d) {
    const double y = axes.y(std::pow(10.0, d));
    set_colour(cr, kGridColour);
    cairo_move_to(cr, a.left_px, y);
    cairo_line_to(cr, a.right_px(), y);
    cairo_stroke(cr);
    set_colour(cr, {0.2, 0.2, 0.2});
    draw_text(cr, tick_label(std::pow(10.0, d)), a.left_px - 8.0, y + 4.0, 11.0, false, 1.0);
  }
  set_colour(cr, {0.1, 0.1, 0.1});
  draw_text(cr, "map size [cells]", a.left_px + a.width_px / 2.0, a.bottom_px() + 44.0, 12.0, false,
            0.5);
  draw_y_label(cr, a, "p99 per cycle [ms]");
}

void draw_phase(cairo_t* cr, const LogAxes& axes, const std::vector<ScaleChartRow>& rows,
                std::size_t phase) {
  set_colour(cr, kColours[phase]);
  cairo_set_line_width(cr, 2.0);
  bool open = false;
  for (const ScaleChartRow& row : rows) {
    if (!(row.cells > 0.0) || !drawn(row.p99_ms[phase])) continue;
    const double x = axes.x(row.cells);
    const double y = axes.y(row.p99_ms[phase]);
    if (open) {
      cairo_line_to(cr, x, y);
    } else {
      cairo_move_to(cr, x, y);
      open = true;
    }
  }
  cairo_stroke(cr);
  for (const ScaleChartRow& row : rows) {
    if (!(row.cells > 0.0) || !drawn(row.p99_ms[phase])) continue;
    cairo_rectangle(cr, axes.x(row.cells) - kMarkerPx / 2.0,
                    axes.y(row.p99_ms[phase]) - kMarkerPx / 2.0, kMarkerPx, kMarkerPx);
    cairo_fill(cr);
  }
}

void draw_legend(cairo_t* cr, const PlotArea& a) {
  double y = a.top_px + 10.0;
  for (std::size_t p = 0; p < kScalePhases.size(); ++p) {
    set_colour(cr, kColours[p]);
    cairo_rectangle(cr, a.right_px() + 20.0, y - 9.0, 18.0, 10.0);
    cairo_fill(cr);
    set_colour(cr, {0.1, 0.1, 0.1});
    draw_text(cr, p + 1 == kScalePhases.size() ? "whole cycle" : kScalePhases[p],
              a.right_px() + 46.0, y, 12.0, false);
    y += 22.0;
  }
}

}  // namespace

PlotArea scale_chart_area() {
  return {kLeft, kTop, kScaleChartWidthPx - kLeft - kRight, kScaleChartHeightPx - kTop - kBottom};
}

Rgb scale_phase_colour(std::size_t phase) { return kColours[phase]; }

Status write_scale_chart_png(const std::vector<ScaleChartRow>& rows, const std::string& title,
                             const std::string& path) {
  double cells_lo = std::numeric_limits<double>::infinity();
  double cells_hi = 0.0;
  double ms_lo = std::numeric_limits<double>::infinity();
  double ms_hi = 0.0;
  for (const ScaleChartRow& row : rows) {
    if (!(row.cells > 0.0)) continue;
    for (const double ms : row.p99_ms) {
      if (!drawn(ms)) continue;
      cells_lo = std::min(cells_lo, row.cells);
      cells_hi = std::max(cells_hi, row.cells);
      ms_lo = std::min(ms_lo, std::max(ms, kFloorMs));
      ms_hi = std::max(ms_hi, ms);
    }
  }
  if (!(cells_hi > 0.0)) {
    return invalid_argument("a scale chart needs a run with cells > 0 and a p99 > 0");
  }
  const auto decade_below = [](double v) { return std::floor(std::log10(v)); };
  const auto decade_above = [](double v) { return std::ceil(std::log10(v)); };
  LogAxes axes{scale_chart_area(), decade_below(cells_lo), decade_above(cells_hi),
               decade_below(ms_lo), decade_above(ms_hi)};
  if (axes.x_hi <= axes.x_lo) axes.x_hi = axes.x_lo + 1.0;
  if (axes.y_hi <= axes.y_lo) axes.y_hi = axes.y_lo + 1.0;

  auto figure = Figure::create(kScaleChartWidthPx, kScaleChartHeightPx);
  if (!figure) return figure.error();
  cairo_t* cr = figure->cr();
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  set_colour(cr, {0.0, 0.0, 0.0});
  draw_text(cr, title, kLeft, 26.0, 16.0, true);
  draw_grid(cr, axes);
  cairo_save(cr);
  cairo_rectangle(cr, axes.area.left_px - kMarkerPx, axes.area.top_px - kMarkerPx,
                  axes.area.width_px + 2 * kMarkerPx, axes.area.height_px + 2 * kMarkerPx);
  cairo_clip(cr);
  for (std::size_t p = 0; p < kScalePhases.size(); ++p) draw_phase(cr, axes, rows, p);
  cairo_restore(cr);
  draw_axes(cr, axes.area);
  draw_legend(cr, axes.area);
  return figure->write_png(path);
}

}  // namespace grip::tools
