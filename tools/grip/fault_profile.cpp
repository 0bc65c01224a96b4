#include "fault_profile.hpp"

#include <cstdio>

namespace grip::tools {

const std::vector<FaultProfile>& fault_profiles() {
  static const std::vector<FaultProfile> profiles = [] {
    std::vector<FaultProfile> p(7);
    p[0].name = "none";
    p[1].name = "loss-10";
    p[1].kind = FaultKind::kLoss;
    p[1].loss_percent = 10;
    p[2].name = "loss-30";
    p[2].kind = FaultKind::kLoss;
    p[2].loss_percent = 30;
    p[3].name = "delay-50ms";
    p[3].kind = FaultKind::kDelay;
    p[3].delay_ms = 50.0;
    p[3].jitter_ms = 10.0;
    p[4].name = "cut-2s";
    p[4].kind = FaultKind::kCut;
    p[4].cut_s = 2.0;
    p[5].name = "planner-restart";
    p[5].kind = FaultKind::kPlannerRestart;
    p[6].name = "vehicle-restart";
    p[6].kind = FaultKind::kVehicleRestart;
    return p;
  }();
  return profiles;
}

std::vector<std::string> fault_profile_names() {
  std::vector<std::string> names;
  for (const auto& p : fault_profiles()) names.push_back(p.name);
  return names;
}

Result<FaultProfile> find_fault_profile(std::string_view name) {
  for (const auto& p : fault_profiles()) {
    if (p.name == name) return p;
  }
  return invalid_argument("no fault profile '" + std::string(name) + "'");
}

std::vector<std::vector<std::string>> fault_rules(const FaultProfile& profile,
                                                  const std::string& interface) {
  const std::vector<std::string> in{"-A", "INPUT", "-i", interface};
  const auto rule = [&in](std::vector<std::string> tail) {
    std::vector<std::string> r(in);
    r.insert(r.end(), tail.begin(), tail.end());
    return r;
  };
  switch (profile.kind) {
    case FaultKind::kLoss: {
      char probability[16];
      std::snprintf(probability, sizeof probability, "%.2f", profile.loss_percent / 100.0);
      return {rule(
          {"-m", "statistic", "--mode", "random", "--probability", probability, "-j", "DROP"})};
    }
    case FaultKind::kDelay:
      // No --queue-bypass: without its delayer the link is cut, never silently undelayed.
      return {rule({"-j", "NFQUEUE", "--queue-num", std::to_string(kFaultQueue)})};
    case FaultKind::kCut:
      return {rule({"-j", "DROP"})};
    case FaultKind::kNone:
    case FaultKind::kPlannerRestart:
    case FaultKind::kVehicleRestart:
      break;
  }
  return {};
}

}  // namespace grip::tools
