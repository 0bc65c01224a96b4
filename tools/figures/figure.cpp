#include "figure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "grip/tools/atomic_file.hpp"

namespace grip::tools {

Result<Figure> Figure::create(int width_px, int height_px) {
  // cairo's image surfaces are limited to 32767 pixels a side.
  if (width_px < 1 || height_px < 1 || width_px > 32767 || height_px > 32767) {
    return invalid_argument("a figure must be 1 to 32767 pixels a side (got " +
                            std::to_string(width_px) + "x" + std::to_string(height_px) + ")");
  }
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface);
    return Error{ErrorCode::kIo, "cannot create a " + std::to_string(width_px) + "x" +
                                     std::to_string(height_px) + " image"};
  }
  return Figure(surface, width_px, height_px);
}

Figure::Figure(cairo_surface_t* surface, int width_px, int height_px)
    : surface_(surface, &cairo_surface_destroy),
      cr_(cairo_create(surface), &cairo_destroy),
      width_px_(width_px),
      height_px_(height_px) {
  cairo_set_source_rgb(cr_.get(), 1.0, 1.0, 1.0);
  cairo_paint(cr_.get());
}

Status Figure::write_png(const std::string& path) const {
  return grip::tools::write_png(surface_.get(), path);
}

Status write_png(cairo_surface_t* surface, const std::string& path) {
  cairo_surface_flush(surface);
  // Whole or not at all (atomic_file.hpp): encoded into a temporary file, then renamed.
  auto file = AtomicFile::create(path);
  if (!file) return file.error();
  const auto to_file = [](void* closure, const unsigned char* data, unsigned int length) {
    return std::fwrite(data, 1, length, static_cast<std::FILE*>(closure)) == length
               ? CAIRO_STATUS_SUCCESS
               : CAIRO_STATUS_WRITE_ERROR;
  };
  const cairo_status_t status = cairo_surface_write_to_png_stream(surface, to_file, file->stream());
  if (status != CAIRO_STATUS_SUCCESS) {
    return Error{ErrorCode::kIo,
                 "cannot write PNG '" + path + "': " + cairo_status_to_string(status)};
  }
  return file->commit();
}

double draw_text(cairo_t* cr, const std::string& text, double x_px, double y_px, double size_px,
                 bool bold, double align, double angle_rad) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_px);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  cairo_save(cr);
  cairo_translate(cr, x_px, y_px);
  cairo_rotate(cr, angle_rad);
  cairo_move_to(cr, -align * ext.width, 0.0);
  cairo_show_text(cr, text.c_str());
  cairo_restore(cr);
  return ext.x_advance;
}

void set_colour(cairo_t* cr, Rgb c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void draw_axes(cairo_t* cr, const PlotArea& area) {
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.2);
  cairo_move_to(cr, area.left_px, area.top_px);
  cairo_line_to(cr, area.left_px, area.bottom_px());
  cairo_line_to(cr, area.right_px(), area.bottom_px());
  cairo_stroke(cr);
}

void draw_y_label(cairo_t* cr, const PlotArea& area, const std::string& label) {
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  draw_text(cr, label, 18.0, area.top_px + area.height_px / 2.0, 12.0, false, 0.5,
            -std::numbers::pi / 2.0);
}

void set_dashed(cairo_t* cr) {
  const std::array<double, 2> dash{6.0, 4.0};
  cairo_set_dash(cr, dash.data(), static_cast<int>(dash.size()), 0.0);
}

void draw_dashed_hline(cairo_t* cr, const PlotArea& area, double y_px, Rgb colour,
                       double width_px) {
  cairo_save(cr);
  set_dashed(cr);
  cairo_set_source_rgb(cr, colour.r, colour.g, colour.b);
  cairo_set_line_width(cr, width_px);
  cairo_move_to(cr, area.left_px, y_px);
  cairo_line_to(cr, area.right_px(), y_px);
  cairo_stroke(cr);
  cairo_restore(cr);
}

std::vector<double> linear_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi)) return ticks;
  const double raw = (hi - lo) / static_cast<double>(std::max(target, 2));
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * decade;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  }
  // Integer multiples of the step, so that no error accumulates along the axis.
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  for (double k = first; k <= last; k += 1.0) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  }
  return ticks;
}

std::string tick_label(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", value == 0.0 ? 0.0 : value);
  return buf;
}

std::string fixed(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace grip::tools
