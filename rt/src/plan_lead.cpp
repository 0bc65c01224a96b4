#include "grip/rt/plan_lead.hpp"

#include <algorithm>

namespace grip::rt {

void PlanLead::observe(std::uint64_t plan_cycle, std::int64_t margin_ns) noexcept {
  if (plan_cycle == 0 || plan_cycle <= last_cycle_) return;
  last_cycle_ = plan_cycle;
  const std::int64_t jitter_ns = cycle_ns_ / 4;
  const std::int64_t max_lead_ns = kMaxLeadCycles * cycle_ns_;
  if (margin_ns < 0) {
    // Late: the next plans start later by what this one missed by, and a little more. The
    // margin is clamped first, so that a hostile value cannot overflow the sum.
    const std::int64_t missed = -std::max(margin_ns, -max_lead_ns);
    lead_ns_ = std::min(lead_ns_ + missed + jitter_ns, max_lead_ns);
  } else if (margin_ns > 2 * jitter_ns) {
    // Early by more than half a cycle: an eighth of the excess back, no further than zero.
    lead_ns_ = std::max<std::int64_t>(
        0, lead_ns_ - (std::min(margin_ns, max_lead_ns) - 2 * jitter_ns) / 8);
  }
}

}  // namespace grip::rt
