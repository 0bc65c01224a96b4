#pragma once
// The velocity profile of the paper's Fig. 9 as a PNG: speed over simulated time, the vehicle's
// maximum speed as a dashed line, a moving average, the speed braking within the sensed region
// allowed (when the report has it), and every collision marked in red on the time axis.
//
// The layout, for whoever reads the picture back (tests do):
//   plot area: left 70 px, top 64 px, right margin 25 px, bottom margin 56 px;
//   x: 0 at the left edge to the later of the last sample and the last collision at the right
//      (1 s when both are 0); y: 0 at the bottom edge to 1.15 x max(maximum speed, fastest
//      sample) at the top;
//   colours (RGB, 0-255): speed (0, 102, 204), moving average (204, 102, 0), maximum speed
//      dashed (51, 51, 51), braking bound (51, 166, 51) drawn under the speed, collisions
//      (255, 0, 0), drawn last so that nothing hides them.

#include <string>

#include "figure.hpp"
#include "grip/common/result.hpp"
#include "speed_profile.hpp"

namespace grip::tools {

struct SpeedChartOptions {
  int width_px = 1200;    // [400, 8000]
  int height_px = 500;    // [240, 4000]
  double smooth_s = 1.0;  // moving-average window [s]; 0: no smoothed curve
};

// Errors (kInvalidArgument): a size or a window out of the ranges above.
Status check_speed_chart_options(const SpeedChartOptions& options);

// The plot area of a chart of this size (see the layout above).
PlotArea speed_chart_area(int width_px, int height_px);

// Errors: options out of range, or a report without samples (kInvalidArgument), a PNG that cannot
// be written (kIo).
Status write_speed_profile_png(const SpeedReport& report, const SpeedProfileSummary& summary,
                               const SpeedChartOptions& options, const std::string& path);

}  // namespace grip::tools
