#pragma once
// The cycle's timing options that every planning command takes (--period-ms, --budget-ms,
// --margin-ms, --max-edges), checked in one place.

#include <cmath>
#include <cstdint>
#include <string>

#include "grip/common/result.hpp"

namespace grip::tools {

// margin_ms < 0: the default margin; max_edges 0: the default pool.
inline Status validate_cycle_options(double period_ms, double budget_ms, double margin_ms,
                                     std::uint32_t max_edges) {
  if (!std::isfinite(period_ms) || period_ms < 1.0 || period_ms > 4000.0) {
    return invalid_argument("--period-ms must be in [1, 4000] ms (got " +
                            std::to_string(period_ms) + ")");
  }
  if (!std::isfinite(budget_ms) || budget_ms <= 0.0 || budget_ms >= period_ms) {
    return invalid_argument("--budget-ms must be > 0 and below the period " +
                            std::to_string(period_ms) + " ms (got " + std::to_string(budget_ms) +
                            ")");
  }
  if (!std::isfinite(margin_ms) || margin_ms >= budget_ms) {
    return invalid_argument("--margin-ms must be below the budget (got " +
                            std::to_string(margin_ms) + ")");
  }
  if (max_edges != 0 && max_edges < 100) {
    return invalid_argument("--max-edges must be at least 100 (got " + std::to_string(max_edges) +
                            ")");
  }
  return Ok{};
}

}  // namespace grip::tools
