// `grip planner`: the planner as a DDS participant, as it runs on a vehicle computer. It waits
// for the map, the vehicle's state and a goal, then replans every cycle on a deadline-scheduled
// thread and publishes plans and its status (rt/dds/planner_participant.hpp). Ctrl-C stops it.
// Under systemd (platform/systemd/grip-planner.service) it says when it is ready, feeds the
// watchdog while planning cycles complete, and logs with timestamps for the journal.

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.hpp"
#include "cycle_trace.hpp"
#include "dds_config.hpp"
#include "grip/platform/overrun_watcher.hpp"
#include "grip/platform/service_notifier.hpp"
#include "grip/rt/dds/planner_participant.hpp"
#include "grip/tools/atomic_file.hpp"
#include "grip/tools/log.hpp"
#include "latency_json.hpp"
#include "params_options.hpp"
#include "report_file.hpp"

namespace grip::tools {

namespace {

struct PlannerOptions {
  ParamsOptions params{"car"};
  std::string dds_config;
  double duration_s = 0.0;
  double startup_timeout_s = 0.0;
  std::uint64_t seed = 1;
  std::string report;
  std::string cycle_trace;
  std::string log_level = "info";
};

// The status line goes to the service manager and, without a terminal, to the log this often.
constexpr std::chrono::seconds kStatusEvery{10};

std::atomic<rt::dds::PlannerParticipant*> g_running{nullptr};

extern "C" void stop_on_signal(int) {
  // An atomic store: async-signal-safe.
  if (auto* planner = g_running.load()) planner->request_stop();
}

Result<rt::dds::PlannerParticipantConfig> to_config(const PlannerOptions& o,
                                                    const params::GripParams& p) {
  // At most a century: the cycle count it becomes must fit in 64 bits (0: until stopped).
  constexpr double kMaxDurationS = 100.0 * 365.25 * 86'400.0;
  if (!(o.duration_s >= 0.0 && o.duration_s <= kMaxDurationS)) {
    return invalid_argument("--duration must be in [0, 100 years] s, 0: until stopped (got " +
                            std::to_string(o.duration_s) + ")");
  }
  rt::dds::PlannerParticipantConfig config = planner_participant_config(p);
  Result<std::string> dds_config =
      choose_dds_config(o.dds_config.empty() ? p.link.dds_config : o.dds_config);
  if (!dds_config) return dds_config.error();
  config.dds_config = *dds_config;
  auto security = security_files(p.link.security_dir, "planner");
  if (!security) return security.error();
  config.security = *security;
  config.seed = o.seed;
  config.duration_s = o.duration_s;
  auto timeout = startup_timeout(o.startup_timeout_s);
  if (!timeout) return timeout.error();
  config.startup_timeout = *timeout;
  return config;
}

// The service manager's side of a run (a no-op outside a service): a failed notification is
// logged once, and the run goes on.
class Service {
 public:
  explicit Service(const Logger& log)
      : log_(log), notifier_(platform::ServiceNotifier::from_environment()) {}
  const platform::ServiceNotifier& notifier() const { return notifier_; }
  void check(const Status& sent) {
    if (!sent.ok() && !warned_) {
      warned_ = true;
      log_.warning("service manager notification failed: " + sent.error().message);
    }
  }

 private:
  const Logger& log_;
  platform::ServiceNotifier notifier_;
  bool warned_ = false;
};

// Readiness, watchdog, status and warnings: from run()'s thread and the receive thread, never
// from the planning thread.
void wire_service(rt::dds::PlannerParticipantConfig& config, const Logger& log, Service& service) {
  config.on_ready = [&log, &service](const std::string& summary) {
    log.info("ready: " + summary);
    service.check(service.notifier().ready(summary));
  };
  if (service.notifier().watchdog_timeout().count() > 0) {
    config.alive_interval = service.notifier().watchdog_timeout() / 2;
    config.on_alive = [&service] { service.check(service.notifier().watchdog()); };
  }
  config.on_warning = [&log](const std::string& line) { log.warning(line); };
  const bool tty = isatty(STDERR_FILENO) == 1;
  config.on_progress = [tty, &log, &service, next = std::chrono::steady_clock::time_point{}](
                           const std::string& line) mutable {
    if (tty) std::cerr << "\r" << line << "    " << std::flush;
    const auto now = std::chrono::steady_clock::now();
    if (now < next) return;
    next = now + kStatusEvery;
    if (!tty) log.info(line);
    service.check(service.notifier().status(line));
  };
}

int run_planner(const PlannerOptions& o) {
  auto level = parse_log_level(o.log_level);
  if (!level) {
    std::cerr << "grip planner: " << level.error().message << "\n";
    return 2;
  }
  const Logger log("grip planner", *level);
  auto p = effective_params(o.params);
  if (!p) {
    log.error(p.error().message);
    return 2;
  }
  auto config = to_config(o, *p);
  if (!config) {
    log.error(config.error().message);
    return 2;
  }
  if (Status s = o.report.empty() ? Status(Ok{}) : check_writable(o.report, "--report"); !s) {
    log.error(s.error().message);  // refused now, not after hours of planning
    return 2;
  }
  // Before any thread, Cyclone's included: every thread must block SIGXCPU (overrun_watcher.hpp).
  auto overruns = platform::OverrunWatcher::start();
  if (!overruns) {
    log.error(overruns.error().message);
    return 2;
  }
  if (!config->security) log.warning(unauthenticated_link_warning());
  if (config->security) log_refused_peers([log](const std::string& line) { log.warning(line); });
  const bool tty = isatty(STDERR_FILENO) == 1;
  Service service(log);
  wire_service(*config, log, service);
  std::optional<CycleTrace> trace;
  if (!o.cycle_trace.empty()) {
    auto opened = CycleTrace::open(o.cycle_trace);
    if (!opened) {
      log.error(opened.error().message);
      return 2;
    }
    trace.emplace(std::move(opened).value());
    config->on_cycle = [&trace](const rt::CycleRecord& r) { trace->write(r); };
  }
  auto planner = rt::dds::PlannerParticipant::create(*config);
  if (!planner) {
    log.error(planner.error().message);
    return 2;
  }
  g_running.store(planner->get());
  std::signal(SIGINT, stop_on_signal);
  std::signal(SIGTERM, stop_on_signal);
  const std::string robot(vehicle_name(vehicle_kind(p->vehicle)));
  log.info(robot + (o.params.file.empty() ? "" : " from " + o.params.file) + " on DDS domain " +
           std::to_string(config->domain) + " (" +
           (config->dds_config.empty() ? "loopback-only configuration" : config->dds_config) +
           (config->security ? ", DDS Security with the keys in " + config->security->directory()
                             : std::string(", unauthenticated")) +
           "); waiting for map, vehicle state and goal");
  service.check(service.notifier().status("waiting for map, vehicle state and goal"));
  auto report = (*planner)->run();
  service.check(service.notifier().stopping());
  g_running.store(nullptr);
  if (tty) std::cerr << "\n";
  if (!report) {
    log.error(report.error().message);
    // kInvalidArgument: a vehicle other than the parameters describe, or what it sent the
    // planner cannot plan with. Like a bad file, restarting does not mend it (the unit's
    // RestartPreventExitStatus).
    return report.error().code == ErrorCode::kInvalidArgument ? 2 : 1;
  }
  if (trace) {
    if (Status s = trace->close(); !s) {
      log.error(s.error().message);
      return 1;
    }
  }
  const auto& r = *report;
  std::cout << "grip planner: " << r.cycles << " cycles, " << r.misses << " misses, policy "
            << r.policy << (r.policy_fallback.empty() ? "" : " (" + r.policy_fallback + ")")
            << ", publish thread " << r.publish_policy << ", time scale " << r.time_scale
            << "\n  plans: " << r.plans_committed << " committed, " << r.plans_published
            << " published, " << r.plans_superseded << " superseded, " << r.write_failures
            << " write failures, " << r.plans_rewritten
            << " written again (for a lockstep vehicle that still waited)\n  rejected: "
            << r.rejected_vehicle_state << " states, " << r.rejected_map_update << " map updates, "
            << r.rejected_goal << " goals; map gaps " << r.map_gaps << ", heals " << r.map_heals
            << "; vehicle lost " << r.vehicle_losses << " times, off its plans " << r.resyncs
            << " times\n"
            << "  planning thread after warm-up: "
            << (r.allocations_counted ? std::to_string(r.heap_allocations_in_loop)
                                      : std::string("(not counted)"))
            << " heap allocations, " << r.usage_in_loop.minor_faults + r.usage_in_loop.major_faults
            << " page faults, " << overruns->overruns() << " overruns\n";
  if (!o.report.empty()) {
    nlohmann::json j;
    j["robot"] = robot;
    j["parameters"] = params::to_yaml(*p);
    j["policy"] = r.policy;
    j["policy_fallback_reason"] = r.policy_fallback;
    j["publish_thread_policy"] = r.publish_policy;
    j["time_scale"] = r.time_scale;
    j["cycles"] = r.cycles;
    j["misses"] = r.misses;
    j["overruns"] = overruns->overruns();
    j["plans"] = {{"committed", r.plans_committed},
                  {"published", r.plans_published},
                  {"superseded", r.plans_superseded},
                  {"write_failures", r.write_failures},
                  {"rewritten", r.plans_rewritten}};
    j["rejected"] = {{"vehicle_state", r.rejected_vehicle_state},
                     {"map_update", r.rejected_map_update},
                     {"goal", r.rejected_goal}};
    j["map"] = {{"gaps", r.map_gaps},
                {"heals", r.map_heals},
                {"sequence", r.map_sequence},
                {"checksum", r.map_checksum}};
    j["vehicle_losses"] = r.vehicle_losses;
    j["resyncs"] = r.resyncs;
    j["heap_allocations_in_loop"] =
        r.allocations_counted ? nlohmann::json(r.heap_allocations_in_loop) : nullptr;
    j["page_faults_in_loop"] = r.usage_in_loop.minor_faults + r.usage_in_loop.major_faults;
    j["wake_latency_us"] = latency_json_us(r.wake_latency);
    j["compute_us"] = latency_json_us(r.compute);
    j["plan_handoff_us"] = latency_json_us(r.plan_handoff);
    j["plan_write_us"] = latency_json_us(r.plan_write);
    if (!write_report("grip planner", o.report, std::move(j))) return 1;
  }
  return 0;
}

}  // namespace

void register_planner_command(CLI::App& app) {
  auto o = std::make_shared<PlannerOptions>();
  CLI::App* cmd = app.add_subcommand(
      "planner",
      "Run the planner as a DDS participant (vehicle computer): state, map and goal in, "
      "plans and status out");
  add_vehicle_options(*cmd, o->params);
  add_sensor_option(*cmd, o->params);
  add_domain_option(*cmd, o->params);
  add_dds_config_option(*cmd, o->dds_config);
  add_security_option(*cmd, o->params);
  add_cycle_options(*cmd, o->params);
  add_lockstep_options(*cmd, o->params);
  cmd->add_option("--seed", o->seed, "Planner seed")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of planning, 0: until Ctrl-C")
      ->capture_default_str();
  add_startup_timeout_option(*cmd, o->startup_timeout_s);
  cmd->add_option("--report", o->report, "Write a JSON report here");
  cmd->add_option("--cycle-trace", o->cycle_trace,
                  "Write every planning cycle's timing and outcome here (CSV)");
  cmd->add_option("--log-level", o->log_level,
                  "error, warning or info: what goes to stderr, each line with its UTC time "
                  "(without a terminal the status line too, every 10 s)")
      ->check(CLI::IsMember({"error", "warning", "info"}))
      ->capture_default_str();
  cmd->callback([o]() {
    const int rc = run_planner(*o);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
