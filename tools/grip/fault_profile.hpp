#pragma once
// The network faults of `grip bench faults`, each made on the link between the planner's and the
// vehicle's network namespaces, and how: netfilter rules on each end's incoming traffic
// (iptables), so that both directions suffer alike. This kernel has no netem qdisc, so a delay is
// made by queueing the packets to userspace (NFQUEUE) where `grip fault-delayer` holds them.

#include <string>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::tools {

enum class FaultKind {
  kNone,            // the baseline
  kLoss,            // each packet lost with a probability, from fault start to the end
  kDelay,           // each packet held delay +- jitter, from fault start to the end
  kCut,             // every packet lost for cut_s
  kPlannerRestart,  // the planner killed (SIGKILL) and started again
  kVehicleRestart,  // the simulator killed (SIGKILL) and started again
};

struct FaultProfile {
  std::string name;
  FaultKind kind = FaultKind::kNone;
  int loss_percent = 0;
  double delay_ms = 0.0;
  double jitter_ms = 0.0;  // uniform in delay +- jitter
  double cut_s = 0.0;

  // A fault that ends (a cut, a restart), after which the run is expected to recover.
  bool ends() const {
    return kind == FaultKind::kCut || kind == FaultKind::kPlannerRestart ||
           kind == FaultKind::kVehicleRestart;
  }
};

// none, loss-10, loss-30, delay-50ms, cut-2s, planner-restart, vehicle-restart.
const std::vector<FaultProfile>& fault_profiles();
std::vector<std::string> fault_profile_names();
Result<FaultProfile> find_fault_profile(std::string_view name);

// The netfilter queue `grip fault-delayer` serves.
inline constexpr unsigned kFaultQueue = 0;

// `iptables` argument lists (after "iptables") that make the link fault of `profile` on traffic
// arriving at `interface`; none for the baseline and the restarts. Undone by flushing INPUT.
std::vector<std::vector<std::string>> fault_rules(const FaultProfile& profile,
                                                  const std::string& interface);

}  // namespace grip::tools
