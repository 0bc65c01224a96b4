#pragma once
// Summary statistics over a run's samples (tools only; allocates freely).

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace grip::tools {

struct Summary {
  std::size_t count = 0;
  double median = NAN;
  double mean = NAN;
  double max = NAN;
  double min = NAN;
};

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = static_cast<std::size_t>(std::ceil(pos));
  return v[lo] + (v[hi] - v[lo]) * (pos - static_cast<double>(lo));
}

// The median, or `if_empty` for no samples.
inline double median(const std::vector<double>& v, double if_empty = NAN) {
  return v.empty() ? if_empty : percentile(v, 0.5);
}

inline Summary summarize(const std::vector<double>& v) {
  Summary s;
  s.count = v.size();
  if (v.empty()) return s;
  s.median = median(v);
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  s.max = *std::max_element(v.begin(), v.end());
  s.min = *std::min_element(v.begin(), v.end());
  return s;
}

}  // namespace grip::tools
