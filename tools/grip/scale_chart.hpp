#pragma once
// `grip bench scale --png`: how the cost of a cycle grows with the map, as a picture. Each
// cycle phase's p99 against the map's cell count, both axes logarithmic (a cost that does not
// grow with the map is a flat line; one proportional to it rises a decade per decade), a marker
// per run joined in order of size.
//
// The layout, for whoever reads the picture back (tests do):
//   1000 x 600 px; plot area: left 80 px, top 64 px, right margin 170 px (the legend), bottom
//   margin 60 px;
//   x: log10(cells) from the decade at or below the fewest cells to the decade at or above the
//      most; y: log10(ms) likewise over every p99 drawn (1 us at least);
//   a phase's colour (RGB, 0-255): prepare (204, 102, 0), retain (0, 153, 136), grow
//      (0, 102, 204), commit (153, 51, 204), the whole cycle ("compute") (0, 0, 0); markers are
//      squares 9 px wide centred on the point.

#include <array>
#include <string>
#include <vector>

#include "figure.hpp"
#include "grip/common/result.hpp"

namespace grip::tools {

inline constexpr std::array<const char*, 5> kScalePhases = {"prepare", "retain", "grow", "commit",
                                                            "compute"};

struct ScaleChartRow {
  double cells = 0.0;
  std::array<double, kScalePhases.size()> p99_ms{};  // NaN or <= 0: not drawn
};

inline constexpr int kScaleChartWidthPx = 1000;
inline constexpr int kScaleChartHeightPx = 600;

// The plot area (see the layout above).
PlotArea scale_chart_area();
Rgb scale_phase_colour(std::size_t phase);

// Errors: no row with cells > 0 and a p99 > 0 (kInvalidArgument); a PNG that cannot be written
// (kIo). `title` heads the picture.
Status write_scale_chart_png(const std::vector<ScaleChartRow>& rows, const std::string& title,
                             const std::string& path);

}  // namespace grip::tools
