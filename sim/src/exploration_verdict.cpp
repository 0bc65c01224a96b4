#include "grip/sim/exploration_verdict.hpp"

#include <cstdio>

namespace grip::sim {

ExplorationVerdict verdict_when_planner_done(std::size_t sensed_cells, std::size_t reachable_cells,
                                             std::uint32_t groups_given_up,
                                             std::uint32_t groups_unreachable) {
  const double coverage = reachable_cells == 0 ? 1.0
                                               : static_cast<double>(sensed_cells) /
                                                     static_cast<double>(reachable_cells);
  std::string left;
  if (groups_given_up > 0) {
    left = std::to_string(groups_given_up) + " frontier group(s) the planner gave up on";
  }
  if (groups_unreachable > 0) {
    if (!left.empty()) left += " and ";
    left += std::to_string(groups_unreachable) +
            " frontier group(s) the vehicle cannot reach at its turning radius";
  }
  const std::size_t unsensed = reachable_cells - sensed_cells;
  ExplorationVerdict verdict;
  if (coverage >= kCompleteCoverage) {
    verdict.result = "complete";
    if (!left.empty()) {
      verdict.reason =
          "left " + left + ", with " +
          (unsensed == 0 ? std::string("no") : std::to_string(unsensed) + " cell(s) of") +
          " reachable free space unsensed";
    }
  } else if (!left.empty()) {
    verdict.result = "stuck";
    verdict.reason = "left " + left;
  } else {
    verdict.result = "done-early";
    char reason[96];
    std::snprintf(reason, sizeof reason, "the planner said it was done at coverage %.3f", coverage);
    verdict.reason = reason;
  }
  return verdict;
}

}  // namespace grip::sim
