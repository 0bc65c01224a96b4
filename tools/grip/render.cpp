#include "render.hpp"

#include "figure.hpp"

namespace grip::tools {

Result<MapCanvas> MapCanvas::create(const OccupancyGrid& grid, int pixels_per_cell) {
  if (pixels_per_cell < 1 || pixels_per_cell > 16) {
    return invalid_argument("pixels per cell must be in [1, 16] (got " +
                            std::to_string(pixels_per_cell) + ")");
  }
  const int w = grid.width() * pixels_per_cell;
  const int h = grid.height() * pixels_per_cell;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface);
    return Error{ErrorCode::kIo,
                 "cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " image"};
  }
  return MapCanvas(surface, pixels_per_cell / grid.resolution(), grid.origin_x(), grid.origin_y(),
                   h);
}

MapCanvas::MapCanvas(cairo_surface_t* surface, double scale, double origin_x, double origin_y,
                     int height_px)
    : surface_(surface, &cairo_surface_destroy),
      cr_(cairo_create(surface), &cairo_destroy),
      scale_(scale),
      origin_x_(origin_x),
      origin_y_(origin_y),
      height_px_(height_px) {
  cairo_set_line_join(cr_.get(), CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr_.get(), CAIRO_LINE_CAP_ROUND);
}

void MapCanvas::draw_grid(const OccupancyGrid& grid) {
  cairo_t* cr = cr_.get();
  const double cell = grid.resolution() * scale_;
  for (int cy = 0; cy < grid.height(); ++cy) {
    for (int cx = 0; cx < grid.width(); ++cx) {
      switch (grid.at(cx, cy)) {
        case Cell::kFree:
          cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
          break;
        case Cell::kObstacle:
          cairo_set_source_rgb(cr, 0.15, 0.15, 0.18);
          break;
        case Cell::kUnknown:
          cairo_set_source_rgb(cr, 0.72, 0.74, 0.78);
          break;
      }
      const double x = px(grid.origin_x() + cx * grid.resolution());
      const double y = py(grid.origin_y() + (cy + 1) * grid.resolution());
      cairo_rectangle(cr, x, y, cell, cell);
      cairo_fill(cr);
    }
  }
}

void MapCanvas::draw_polyline(const std::vector<Point>& points, double r, double g, double b,
                              double width_px, double alpha) {
  if (points.size() < 2) return;
  cairo_t* cr = cr_.get();
  cairo_set_source_rgba(cr, r, g, b, alpha);
  cairo_set_line_width(cr, width_px);
  cairo_move_to(cr, px(points.front().x_m), py(points.front().y_m));
  for (std::size_t i = 1; i < points.size(); ++i) {
    cairo_line_to(cr, px(points[i].x_m), py(points[i].y_m));
  }
  cairo_stroke(cr);
}

void MapCanvas::draw_disk(Point centre, double radius_m, double r, double g, double b,
                          double alpha) {
  cairo_t* cr = cr_.get();
  cairo_set_source_rgba(cr, r, g, b, alpha);
  cairo_arc(cr, px(centre.x_m), py(centre.y_m), radius_m * scale_, 0.0, 6.283185307179586);
  cairo_fill(cr);
}

void MapCanvas::draw_marker(Point at, double radius_px, double r, double g, double b) {
  cairo_t* cr = cr_.get();
  cairo_set_source_rgb(cr, r, g, b);
  cairo_arc(cr, px(at.x_m), py(at.y_m), radius_px, 0.0, 6.283185307179586);
  cairo_fill(cr);
}

void MapCanvas::draw_label(const std::string& text, double x_px, double y_px, double size_px) {
  cairo_t* cr = cr_.get();
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, size_px);
  cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.85);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  cairo_rectangle(cr, x_px - 4, y_px - ext.height - 4, ext.width + 8, ext.height + 8);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.05, 0.05, 0.1);
  cairo_move_to(cr, x_px, y_px);
  cairo_show_text(cr, text.c_str());
}

Status MapCanvas::write_png(const std::string& path) {
  return grip::tools::write_png(surface_.get(), path);
}

}  // namespace grip::tools
