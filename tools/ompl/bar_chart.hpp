#pragma once
// Grouped bar charts on a log scale, in the manner of the paper's Fig. 6 (one group per
// experiment, one bar per planner), drawn with cairo like the rest of the project's figures.

#include <string>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::ompl_bridge {

struct BarGroup {
  std::string label;               // under the group, e.g. "meandros / car"
  std::vector<double> values;      // one per series; NaN or +inf: no value (drawn as a stub)
  std::vector<std::string> notes;  // one per series, printed above the bar (e.g. "3/5")
};

struct BarPanel {
  std::string title;
  std::string y_label;
  std::vector<BarGroup> groups;
  double y_max = 0.0;  // top of the axis; no-value bars reach it, hatched (e.g. the time limit)
};

// Panels stacked vertically, sharing the series (legend) and their colours. Values must be
// positive (log scale). Errors: no panels, or a PNG that cannot be written.
Status write_bar_chart_png(const std::vector<std::string>& series,
                           const std::vector<BarPanel>& panels, const std::string& path);

}  // namespace grip::ompl_bridge
