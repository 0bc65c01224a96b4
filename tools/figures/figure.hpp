#pragma once
// What the project's charts share, drawn with cairo: a white RGB image to draw on and write as a
// PNG, text, a plot area with its axes, dashed reference lines and evenly spaced axis ticks.
// Used by `grip render` (tools/grip) and the bar chart of `grip bench ompl` (tools/ompl); the
// map pictures (tools/grip/render.hpp) write their PNG through write_png below.

#include <cairo.h>

#include <memory>
#include <string>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::tools {

struct Rgb {
  double r;
  double g;
  double b;
};

// The rectangle the data is drawn in, in pixels from the image's top left corner.
struct PlotArea {
  double left_px;
  double top_px;
  double width_px;
  double height_px;

  double right_px() const { return left_px + width_px; }
  double bottom_px() const { return top_px + height_px; }
};

// A white RGB image of a fixed size with its cairo context.
class Figure {
 public:
  // Errors: a size outside [1, 32767] pixels, or an image cairo cannot allocate.
  static Result<Figure> create(int width_px, int height_px);

  cairo_t* cr() const { return cr_.get(); }
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  // Errors (kIo): the file cannot be written; the message names the path and cairo's reason.
  Status write_png(const std::string& path) const;

 private:
  Figure(cairo_surface_t* surface, int width_px, int height_px);

  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface_;
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr_;
  int width_px_;
  int height_px_;
};

// Writes an image surface as a PNG. Errors (kIo) name the path and cairo's reason.
Status write_png(cairo_surface_t* surface, const std::string& path);

// Text in the current source colour with its baseline at (x, y): `align` 0 puts its left end at
// x, 0.5 its middle, 1 its right end; `angle_rad` turns it about (x, y) (-pi/2: reads upwards).
// Returns the text's width [px], to place what follows it.
double draw_text(cairo_t* cr, const std::string& text, double x_px, double y_px, double size_px,
                 bool bold, double align = 0.0, double angle_rad = 0.0);

// Makes `c` the colour of what is drawn next.
void set_colour(cairo_t* cr, Rgb c);

// The left and bottom axis lines of a plot area, in black.
void draw_axes(cairo_t* cr, const PlotArea& area);

// The y-axis label, centred along the left edge of the plot area and reading upwards.
void draw_y_label(cairo_t* cr, const PlotArea& area, const std::string& label);

// Makes the lines stroked from now on dashed, 6 px on and 4 off, as reference lines are drawn.
void set_dashed(cairo_t* cr);

// A dashed horizontal line across the plot area at y_px.
void draw_dashed_hline(cairo_t* cr, const PlotArea& area, double y_px, Rgb colour,
                       double width_px = 1.0);

// Tick values for a linear axis over [lo, hi] (lo < hi): the multiples in that range of a step
// of 1, 2 or 5 times a power of ten, chosen to give about `target` ticks (at least 2).
std::vector<double> linear_ticks(double lo, double hi, int target);

// A tick value as a short label: "0", "2.5", "120", without trailing zeros.
std::string tick_label(double value);

// A number with a fixed count of decimals, as printf's "%.*f" writes it: fixed(2.0, 3) is "2.000".
std::string fixed(double value, int decimals);

}  // namespace grip::tools
