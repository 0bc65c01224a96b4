#pragma once
// One piece of a plan: a control held for a duration (the paper's Sec. II, p = {(u1, dt1), ...}).

#include <array>

namespace grip {

struct PlanStep {
  std::array<double, 2> control{};
  double duration_s = 0.0;
};

}  // namespace grip
