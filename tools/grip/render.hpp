#pragma once
// PNG figures with cairo: the 3-valued grid, a tree, a path, start and goal.

#include <cairo.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::tools {

struct Point {
  double x_m;
  double y_m;
};

// A canvas in map coordinates (metres, y up) over an image of `pixels_per_cell` per cell.
class MapCanvas {
 public:
  static Result<MapCanvas> create(const OccupancyGrid& grid, int pixels_per_cell = 3);

  void draw_grid(const OccupancyGrid& grid);
  void draw_polyline(const std::vector<Point>& points, double r, double g, double b,
                     double width_px, double alpha = 1.0);
  void draw_disk(Point centre, double radius_m, double r, double g, double b, double alpha);
  void draw_marker(Point at, double radius_px, double r, double g, double b);
  void draw_label(const std::string& text, double x_px, double y_px, double size_px);
  Status write_png(const std::string& path);

 private:
  MapCanvas(cairo_surface_t* surface, double scale, double origin_x, double origin_y,
            int height_px);
  double px(double x_m) const { return (x_m - origin_x_) * scale_; }
  double py(double y_m) const { return height_px_ - (y_m - origin_y_) * scale_; }

  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface_;
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr_;
  double scale_;
  double origin_x_;
  double origin_y_;
  int height_px_;
};

}  // namespace grip::tools
