#include "fault_run.hpp"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "bench_children.hpp"
#include "stop_signal.hpp"
#include "vehicle_arg.hpp"

namespace grip::tools {

namespace {

using Clock = std::chrono::steady_clock;

// recovery_time(): a rest at least this long (a turn in place is shorter), beginning at most this
// long after the fault's end [s simulated].
constexpr double kMinRest_s = 0.5;
constexpr double kRestWindow_s = 10.0;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The processes of one run and the link faults on it; whatever is left is stopped and undone
// when it goes out of scope, on every path out of the run.
class FaultRun {
 public:
  FaultRun(const FaultRunSetup& s, const FaultProfile& p) : s_(s), p_(p) {}
  ~FaultRun() {
    stop_planner();
    (void)clear_link();
  }

  Status start_delayers() {
    for (const NetnsPair::End* end : {&s_.link->planner(), &s_.link->vehicle()}) {
      auto d =
          Child::spawn(NetnsPair::in_namespace(
                           *end, {s_.grip, "fault-delayer", "--delay-ms",
                                  std::to_string(p_.delay_ms), "--jitter-ms",
                                  std::to_string(p_.jitter_ms), "--seed", std::to_string(s_.seed)}),
                       {}, s_.stem + ".delayer-" + end->netns + ".log", true);
      if (!d) return d.error();
      delayers_.push_back(std::move(d).value());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // bound to their queues
    for (Child& d : delayers_) {
      if (const int status = d.poll(); status >= 0) {
        return Error{ErrorCode::kIo, "grip fault-delayer exited (" + std::to_string(status) +
                                         "); see " + s_.stem + ".delayer-*.log"};
      }
    }
    return Ok{};
  }

  Status start_planner() {
    const std::string n = std::to_string(++planner_starts_);
    std::vector<std::string> args{s_.grip, "planner"};
    for (auto& a : vehicle_args(s_.robot)) args.push_back(a);
    for (const std::string& a :
         {std::string("--domain"), std::to_string(s_.domain), std::string("--dds-config"),
          s_.planner_dds_config, std::string("--seed"), std::to_string(s_.seed),
          std::string("--report"), s_.stem + ".planner-" + n + ".json", std::string("--log-level"),
          std::string("warning")}) {
      args.push_back(a);
    }
    std::filesystem::remove(s_.stem + ".planner-" + n + ".json");
    auto c = Child::spawn(NetnsPair::in_namespace(s_.link->planner(), std::move(args)), {},
                          s_.stem + ".planner-" + n + ".log", true);
    if (!c) return c.error();
    planner_.emplace(std::move(c).value());
    return Ok{};
  }

  Status start_sim() {
    ++vehicle_starts_;
    std::vector<std::string> args{s_.grip, "sim"};
    for (auto& a : s_.world_args) args.push_back(a);
    for (auto& a : vehicle_args(s_.robot)) args.push_back(a);
    for (const std::string& a :
         {std::string("--seed"), std::to_string(s_.seed), std::string("--time-scale"),
          std::to_string(s_.time_scale), std::string("--max-sim-time"),
          std::to_string(s_.max_sim_time_s), std::string("--domain"), std::to_string(s_.domain),
          std::string("--dds-config"), s_.vehicle_dds_config, std::string("--report"),
          report_path()}) {
      args.push_back(a);
    }
    std::filesystem::remove(report_path());
    auto c = Child::spawn(NetnsPair::in_namespace(s_.link->vehicle(), std::move(args)), {},
                          s_.stem + ".sim-" + std::to_string(vehicle_starts_) + ".log", true);
    if (!c) return c.error();
    sim_.emplace(std::move(c).value());
    sim_started_ = Clock::now();
    return Ok{};
  }

  // The same rules at both ends: each direction suffers the fault.
  Status fault_link() {
    for (const NetnsPair::End* end : {&s_.link->planner(), &s_.link->vehicle()}) {
      for (auto rule : fault_rules(p_, end->interface)) {
        std::vector<std::string> args{"ip", "netns", "exec", end->netns, "iptables", "-w"};
        args.insert(args.end(), rule.begin(), rule.end());
        if (Status st = run_tool(args); !st) return st;
      }
    }
    return Ok{};
  }

  Status clear_link() {
    if (fault_rules(p_, "x").empty()) return Ok{};
    Status result = Ok{};
    for (const NetnsPair::End* end : {&s_.link->planner(), &s_.link->vehicle()}) {
      Status st = run_tool({"ip", "netns", "exec", end->netns, "iptables", "-w", "-F", "INPUT"});
      if (!st && result) result = st;
    }
    return result;
  }

  // SIGTERM, so that it writes its report; SIGKILL if it does not stop within 15 s.
  void stop_planner() {
    if (!planner_ || !planner_->running()) return;
    planner_->send(SIGTERM);
    const auto asked = Clock::now();
    while (planner_->poll() < 0 && seconds_since(asked) < 15.0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    planner_.reset();  // killed if still running
  }

  void kill_planner() {
    planner_->send(SIGKILL);
    planner_->wait();
  }
  void kill_sim() {
    sim_->send(SIGKILL);
    sim_->wait();
  }

  std::string report_path() const { return s_.stem + ".json"; }
  double wall_since_sim_start() const { return seconds_since(sim_started_); }
  Child& sim() { return *sim_; }
  Child* planner() { return planner_ ? &*planner_ : nullptr; }
  unsigned planner_starts() const { return planner_starts_; }
  unsigned vehicle_starts() const { return vehicle_starts_; }

 private:
  const FaultRunSetup& s_;
  const FaultProfile& p_;
  std::vector<Child> delayers_;  // stopped (SIGKILL) when the run is over: nothing to report
  std::optional<Child> planner_;
  std::optional<Child> sim_;
  Clock::time_point sim_started_;
  unsigned planner_starts_ = 0;
  unsigned vehicle_starts_ = 0;
};

// The plans the planners published that the vehicle did not receive; unknown when a process was
// killed (it left no count).
std::optional<std::int64_t> plans_lost(const FaultRunSetup& s, unsigned planner_starts,
                                       unsigned vehicle_starts, const nlohmann::json& report) {
  if (report.is_null() || vehicle_starts != 1) return std::nullopt;
  std::int64_t published = 0;
  for (unsigned n = 1; n <= planner_starts; ++n) {
    const nlohmann::json planner =
        read_child_report(s.stem + ".planner-" + std::to_string(n) + ".json");
    if (planner.is_null()) return std::nullopt;
    published += planner.at("plans").value("published", std::int64_t{0});
  }
  return published - report.value("plans_received", std::int64_t{0});
}

}  // namespace

std::optional<double> recovery_time(const nlohmann::json& speed_profile, double top_speed_m_s,
                                    double fault_start_s, double fault_end_s) {
  const double moving = 0.05 * top_speed_m_s;
  double rest_began = -1.0;  // of the current rest; < 0: moving
  for (const auto& sample : speed_profile) {
    const double t = sample[0].get<double>();
    const double v = sample[1].get<double>();
    if (v < moving) {
      if (rest_began < 0.0) rest_began = t;
      continue;
    }
    // Moving at t. A rest long enough not to be a turn in place, ending after the fault began:
    // the one the fault caused.
    if (rest_began >= 0.0 && t - rest_began >= kMinRest_s && t > fault_start_s) {
      return std::max(0.0, t - fault_end_s);
    }
    rest_began = -1.0;
    if (t > fault_end_s + kRestWindow_s) return 0.0;
  }
  return rest_began >= 0.0 ? std::nullopt : std::optional<double>(0.0);
}

FaultRunOutcome run_fault_profile(const FaultRunSetup& s, const FaultProfile& p) {
  FaultRunOutcome out;
  out.profile = p.name;
  out.robot = vehicle_label(s.robot);
  const auto started = Clock::now();
  FaultRun run(s, p);
  const auto finish = [&](std::string error) {
    out.error = std::move(error);
    out.planner_starts = run.planner_starts();
    out.vehicle_starts = run.vehicle_starts();
    out.wall_time_s = seconds_since(started);
    return out;
  };
  if (p.kind == FaultKind::kDelay) {
    if (Status st = run.start_delayers(); !st) return finish(st.error().message);
  }
  if (Status st = run.start_planner(); !st) return finish(st.error().message);
  if (Status st = run.start_sim(); !st) return finish(st.error().message);
  // Real time: the simulator ends by max_sim_time_s, give or take its start and end.
  const double wall_limit_s = s.fault_at_s + s.max_sim_time_s / s.time_scale + 120.0;
  bool faulted = false;
  bool fault_over = false;
  // When the fault began and ended, on the wall clock; converted to the simulator's timeline
  // from its end (its start-up is not simulated time).
  // Seconds since `started`; < 0: not (yet).
  double fault_began = -1.0;
  double fault_ended = -1.0;
  double sim_ended = -1.0;
  std::string error;
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (stop_flag().load()) {
      error = "interrupted";
      break;
    }
    if (const int status = run.sim().poll(); status >= 0) {
      out.sim_exit_status = status;
      sim_ended = seconds_since(started);
      break;
    }
    if (seconds_since(started) > wall_limit_s) {
      error = "no end after " + std::to_string(static_cast<int>(wall_limit_s)) + " s wall";
      break;
    }
    const double t = run.wall_since_sim_start();
    if (!faulted && t >= s.fault_at_s) {
      faulted = true;
      fault_began = seconds_since(started);
      Status st = Ok{};
      switch (p.kind) {
        case FaultKind::kLoss:
        case FaultKind::kDelay:
        case FaultKind::kCut:
          st = run.fault_link();
          break;
        case FaultKind::kPlannerRestart:
          run.kill_planner();
          st = run.start_planner();
          fault_ended = seconds_since(started);
          break;
        case FaultKind::kVehicleRestart:
          run.kill_sim();
          st = run.start_sim();
          fault_began = fault_ended = seconds_since(started);  // the new simulator's start
          break;
        case FaultKind::kNone:
          fault_began = -1.0;
          break;
      }
      if (!st) {
        error = st.error().message;
        break;
      }
    }
    if (p.kind == FaultKind::kCut && faulted && !fault_over && t >= s.fault_at_s + p.cut_s) {
      fault_over = true;
      if (Status st = run.clear_link(); !st) {
        error = st.error().message;
        break;
      }
      fault_ended = seconds_since(started);
    }
    if (Child* planner = run.planner(); planner != nullptr && planner->running()) {
      if (const int status = planner->poll(); status >= 0) {
        error = "the planner exited (" + std::to_string(status) + ")";  // the sim ends it
      }
    }
  }
  run.stop_planner();
  if (Status st = run.clear_link(); !st && error.empty()) error = st.error().message;
  out.report = read_child_report(run.report_path());
  out.result = out.report.is_null() ? "no report" : out.report.value("result", "?");
  out.plans_lost = plans_lost(s, run.planner_starts(), run.vehicle_starts(), out.report);
  if (!out.report.is_null() && sim_ended >= 0.0) {
    const double end_s = out.report.value("sim_time_s", 0.0);
    const auto on_sim_clock = [&](double t) {
      return std::max(0.0, end_s - (sim_ended - t) * s.time_scale);
    };
    if (fault_began >= 0.0) out.fault_start_s = on_sim_clock(fault_began);
    if (fault_ended >= 0.0) out.fault_end_s = on_sim_clock(fault_ended);
  }
  if (!out.report.is_null() && out.fault_start_s && out.fault_end_s) {
    out.recovery_s =
        recovery_time(out.report.at("speed_profile"), out.report.value("max_speed_m_s", 0.0),
                      *out.fault_start_s, *out.fault_end_s);
  }
  return finish(error);
}

}  // namespace grip::tools
