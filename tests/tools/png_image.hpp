#pragma once
// A PNG read back with cairo, for the tests of the charts the grip command draws.

#include <cairo.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace grip::testing {

struct Rgb {
  int r, g, b;
};

// A PNG read back with cairo.
class Image {
 public:
  explicit Image(const std::string& path)
      : surface_(cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy) {}

  bool ok() const { return cairo_surface_status(surface_.get()) == CAIRO_STATUS_SUCCESS; }
  int width() const { return cairo_image_surface_get_width(surface_.get()); }
  int height() const { return cairo_image_surface_get_height(surface_.get()); }

  Rgb at(int x, int y) const {
    const unsigned char* row =
        cairo_image_surface_get_data(surface_.get()) +
        static_cast<std::ptrdiff_t>(y) * cairo_image_surface_get_stride(surface_.get());
    std::uint32_t pixel = 0;  // 0x00RRGGBB (or AARRGGBB) in native byte order
    std::memcpy(&pixel, row + static_cast<std::ptrdiff_t>(x) * 4, sizeof pixel);
    return {static_cast<int>((pixel >> 16) & 0xFFU), static_cast<int>((pixel >> 8) & 0xFFU),
            static_cast<int>(pixel & 0xFFU)};
  }
  bool is(int x, int y, Rgb c) const {
    const Rgb p = at(x, y);
    return std::abs(p.r - c.r) <= 2 && std::abs(p.g - c.g) <= 2 && std::abs(p.b - c.b) <= 2;
  }
  // The rows of column x between top and bottom (inclusive) that have colour c.
  std::vector<int> rows_with(int x, Rgb c, int top, int bottom) const {
    std::vector<int> rows;
    for (int y = top; y <= bottom; ++y) {
      if (is(x, y, c)) rows.push_back(y);
    }
    return rows;
  }
  bool has_near(double x, double y, Rgb c, int radius) const {
    for (int dy = -radius; dy <= radius; ++dy) {
      for (int dx = -radius; dx <= radius; ++dx) {
        const int px = static_cast<int>(x) + dx;
        const int py = static_cast<int>(y) + dy;
        if (px >= 0 && py >= 0 && px < width() && py < height() && is(px, py, c)) return true;
      }
    }
    return false;
  }

 private:
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface_;
};

}  // namespace grip::testing
