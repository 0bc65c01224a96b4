#include "bar_chart.hpp"

#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "figure.hpp"

namespace grip::ompl_bridge {

namespace {

using tools::draw_text;
using tools::Rgb;

constexpr double kWidth = 1400.0;
constexpr double kPanelHeight = 420.0;
constexpr double kLegendHeight = 40.0;
constexpr double kLeft = 80.0;
constexpr double kRight = 20.0;
constexpr double kTop = 40.0;     // in a panel: title
constexpr double kBottom = 60.0;  // in a panel: group labels

// GRIP first and dark; the OMPL planners in distinct lighter colours.
constexpr std::array<Rgb, 8> kColours{{{0.80, 0.15, 0.10},
                                       {0.20, 0.40, 0.75},
                                       {0.35, 0.65, 0.30},
                                       {0.55, 0.35, 0.70},
                                       {0.95, 0.60, 0.10},
                                       {0.45, 0.45, 0.45},
                                       {0.10, 0.65, 0.70},
                                       {0.75, 0.55, 0.40}}};

void draw_panel(cairo_t* cr, const std::vector<std::string>& series, const BarPanel& panel,
                double y0) {
  const tools::PlotArea area{kLeft, y0 + kTop, kWidth - kLeft - kRight,
                             kPanelHeight - kTop - kBottom};
  const double plot_bottom = area.bottom_px();
  const double plot_h = area.height_px;
  const double plot_w = area.width_px;

  // Log axis from the decade below the smallest value to y_max.
  double lo = panel.y_max;
  for (const BarGroup& g : panel.groups) {
    for (double v : g.values) {
      if (std::isfinite(v) && v > 0.0) lo = std::min(lo, v);
    }
  }
  // Half a decade of room below the smallest bar and above the cap (for the notes).
  const double log_lo = std::floor(std::log10(lo) - 0.5);
  const double log_hi = std::log10(panel.y_max) + 0.5;
  const auto y_of = [&](double v) {
    const double f = (std::log10(v) - log_lo) / std::max(log_hi - log_lo, 1e-9);
    return plot_bottom - std::clamp(f, 0.0, 1.0) * plot_h;
  };

  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  draw_text(cr, panel.title, kLeft, y0 + 24.0, 16.0, true);
  // Grid lines at the decades, the axis label.
  cairo_set_line_width(cr, 1.0);
  for (double d = std::ceil(log_lo); d <= std::log10(panel.y_max) + 1e-9; d += 1.0) {
    const double y = y_of(std::pow(10.0, d));
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, kLeft, y);
    cairo_line_to(cr, kLeft + plot_w, y);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    char buf[32];
    std::snprintf(buf, sizeof buf, "1e%d", static_cast<int>(d));
    draw_text(cr, buf, kLeft - 8.0, y + 4.0, 11.0, false, 1.0);
  }
  // The cap (e.g. the time limit) as a dashed line.
  const double y_cap = y_of(panel.y_max);
  tools::draw_dashed_hline(cr, area, y_cap, {0.5, 0.1, 0.1});
  tools::draw_y_label(cr, area, panel.y_label);

  const double group_w =
      plot_w / static_cast<double>(std::max<std::size_t>(panel.groups.size(), 1));
  const double bar_w = group_w * 0.8 / static_cast<double>(std::max<std::size_t>(series.size(), 1));
  for (std::size_t gi = 0; gi < panel.groups.size(); ++gi) {
    const BarGroup& g = panel.groups[gi];
    const double gx = kLeft + group_w * static_cast<double>(gi) + group_w * 0.1;
    for (std::size_t si = 0; si < series.size() && si < g.values.size(); ++si) {
      const double v = g.values[si];
      const bool has_value = std::isfinite(v) && v > 0.0;
      const double x = gx + bar_w * static_cast<double>(si);
      const double top = has_value ? y_of(v) : y_cap;
      const Rgb c = kColours[si % kColours.size()];
      cairo_rectangle(cr, x + 1.0, top, bar_w - 2.0, plot_bottom - top);
      if (has_value) {
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_fill(cr);
      } else {
        // No value (e.g. the median run did not solve): an outline reaching the cap, hatched.
        cairo_set_source_rgba(cr, c.r, c.g, c.b, 0.15);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_set_line_width(cr, 1.0);
        cairo_stroke(cr);
        cairo_save(cr);
        cairo_rectangle(cr, x + 1.0, top, bar_w - 2.0, plot_bottom - top);
        cairo_clip(cr);
        for (double h = top - bar_w; h < plot_bottom; h += 8.0) {
          cairo_move_to(cr, x, h + bar_w);
          cairo_line_to(cr, x + bar_w, h);
        }
        cairo_stroke(cr);
        cairo_restore(cr);
      }
      if (si < g.notes.size()) {
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_text(cr, g.notes[si], x + bar_w / 2.0 + 3.0, top - 4.0, 9.0, false, 0.0,
                  -std::numbers::pi / 2.0);
      }
    }
    cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
    draw_text(cr, g.label, gx + group_w * 0.4, plot_bottom + 18.0, 12.0, false, 0.5);
  }
  tools::draw_axes(cr, area);
}

}  // namespace

Status write_bar_chart_png(const std::vector<std::string>& series,
                           const std::vector<BarPanel>& panels, const std::string& path) {
  if (panels.empty()) return invalid_argument("bar chart: no panels");
  const int w = static_cast<int>(kWidth);
  const int h = static_cast<int>(kLegendHeight + kPanelHeight * static_cast<double>(panels.size()));
  auto figure = tools::Figure::create(w, h);
  if (!figure) return Error{figure.error().code, "bar chart: " + figure.error().message};
  cairo_t* cr = figure->cr();

  // Legend.
  double x = kLeft;
  for (std::size_t si = 0; si < series.size(); ++si) {
    const Rgb c = kColours[si % kColours.size()];
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, x, 14.0, 16.0, 16.0);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    draw_text(cr, series[si], x + 22.0, 27.0, 13.0, si == 0);
    x += 130.0;
  }
  for (std::size_t p = 0; p < panels.size(); ++p) {
    draw_panel(cr, series, panels[p], kLegendHeight + kPanelHeight * static_cast<double>(p));
  }
  return figure->write_png(path);
}

}  // namespace grip::ompl_bridge
