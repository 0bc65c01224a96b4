#pragma once
// A latency histogram in a JSON report: microseconds, the same fields in every report.

#include <nlohmann/json.hpp>

#include "grip/rt/latency_histogram.hpp"

namespace grip::tools {

inline double us(std::int64_t ns) { return static_cast<double>(ns) / 1e3; }

// null when nothing was recorded.
inline nlohmann::json latency_json_us(const rt::LatencyHistogram& h) {
  if (h.count() == 0) return nullptr;
  return {{"p50", us(h.percentile(0.5))},
          {"p99", us(h.percentile(0.99))},
          {"p999", us(h.percentile(0.999))},
          {"max", us(h.max())},
          {"min", us(h.min())},
          {"count", h.count()}};
}

}  // namespace grip::tools
