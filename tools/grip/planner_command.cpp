// `grip planner`: the planner as a DDS participant, as it runs on a vehicle computer. It waits
// for the map, the vehicle's state and a goal, then replans every cycle on a deadline-scheduled
// thread and publishes plans and its status (rt/dds/planner_participant.hpp). Ctrl-C stops it.

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.hpp"
#include "cycle_options.hpp"
#include "cycle_trace.hpp"
#include "dds_config.hpp"
#include "grip/platform/overrun_watcher.hpp"
#include "grip/rt/dds/planner_participant.hpp"
#include "latency_json.hpp"
#include "report_file.hpp"

namespace grip::tools {

namespace {

struct PlannerOptions {
  std::string robot = "car";
  unsigned domain = 0;
  std::string dds_config;
  double period_ms = 50.0;
  double budget_ms = 25.0;
  double margin_ms = -1.0;
  std::string policy = "auto";
  std::uint32_t max_edges = 0;
  std::uint32_t lockstep_edges = kDefaultLockstepEdges;
  double lease_ms = 500.0;
  double duration_s = 0.0;
  double startup_timeout_s = 0.0;
  std::uint64_t seed = 1;
  std::string report;
  std::string cycle_trace;
};

std::atomic<rt::dds::PlannerParticipant*> g_running{nullptr};

extern "C" void stop_on_signal(int) {
  // An atomic store: async-signal-safe.
  if (auto* planner = g_running.load()) planner->request_stop();
}

Result<rt::dds::PlannerParticipantConfig> to_config(const PlannerOptions& o) {
  rt::dds::PlannerParticipantConfig config;
  auto robot = vehicle_kind_from_name(o.robot);
  if (!robot) return robot.error();
  config.robot = *robot;
  auto policy = platform::parse_policy_request(o.policy);
  if (!policy) return policy.error();
  config.policy = *policy;
  if (o.domain >= DDS_DOMAIN_DEFAULT) {
    return invalid_argument("--domain must be below " + std::to_string(DDS_DOMAIN_DEFAULT));
  }
  config.domain = o.domain;
  Result<std::string> dds_config = choose_dds_config(o.dds_config);
  if (!dds_config) return dds_config.error();
  config.dds_config = *dds_config;
  if (Status s = validate_cycle_options(o.period_ms, o.budget_ms, o.margin_ms, o.max_edges); !s) {
    return s.error();
  }
  if (!(o.lease_ms >= 10.0)) return invalid_argument("--lease-ms must be at least 10");
  if (!(o.duration_s >= 0.0) || !(o.startup_timeout_s >= 0.0)) {
    return invalid_argument("--duration and --startup-timeout must be >= 0");
  }
  config.cycle_s = o.period_ms / 1e3;
  config.budget_s = o.budget_ms / 1e3;
  config.margin_s = o.margin_ms < 0.0 ? -1.0 : o.margin_ms / 1e3;
  config.max_edges = o.max_edges;
  config.lockstep_edges = o.lockstep_edges;
  config.seed = o.seed;
  config.liveliness_lease = std::chrono::nanoseconds(static_cast<std::int64_t>(o.lease_ms * 1e6));
  config.duration_s = o.duration_s;
  config.startup_timeout =
      std::chrono::nanoseconds(static_cast<std::int64_t>(o.startup_timeout_s * 1e9));
  return config;
}

int run_planner(const PlannerOptions& o) {
  auto config = to_config(o);
  if (!config) {
    std::cerr << "grip planner: " << config.error().message << "\n";
    return 2;
  }
  // Before any thread, Cyclone's included: every thread must block SIGXCPU (overrun_watcher.hpp).
  auto overruns = platform::OverrunWatcher::start();
  if (!overruns) {
    std::cerr << "grip planner: " << overruns.error().message << "\n";
    return 2;
  }
  const bool tty = isatty(STDERR_FILENO) == 1;
  config->on_progress = [tty](const std::string& line) {
    if (tty) std::cerr << "\r" << line << "    " << std::flush;
  };
  std::optional<CycleTrace> trace;
  if (!o.cycle_trace.empty()) {
    auto opened = CycleTrace::open(o.cycle_trace);
    if (!opened) {
      std::cerr << "grip planner: " << opened.error().message << "\n";
      return 2;
    }
    trace.emplace(std::move(opened).value());
    config->on_cycle = [&trace](const rt::CycleRecord& r) { trace->write(r); };
  }
  auto planner = rt::dds::PlannerParticipant::create(*config);
  if (!planner) {
    std::cerr << "grip planner: " << planner.error().message << "\n";
    return 2;
  }
  g_running.store(planner->get());
  std::signal(SIGINT, stop_on_signal);
  std::signal(SIGTERM, stop_on_signal);
  std::cerr << "grip planner: " << o.robot << " on DDS domain " << o.domain << " ("
            << (config->dds_config.empty() ? "loopback-only configuration" : config->dds_config)
            << "); waiting for map, vehicle state and goal\n";
  auto report = (*planner)->run();
  g_running.store(nullptr);
  if (tty) std::cerr << "\n";
  if (!report) {
    std::cerr << "grip planner: " << report.error().message << "\n";
    return 1;
  }
  if (trace) {
    if (Status s = trace->close(); !s) {
      std::cerr << "grip planner: " << s.error().message << "\n";
      return 1;
    }
  }
  const auto& r = *report;
  std::cout << "grip planner: " << r.cycles << " cycles, " << r.misses << " misses, policy "
            << r.policy << (r.policy_fallback.empty() ? "" : " (" + r.policy_fallback + ")")
            << ", publish thread " << r.publish_policy << ", time scale " << r.time_scale
            << "\n  plans: " << r.plans_committed << " committed, " << r.plans_published
            << " published, " << r.plans_superseded << " superseded, " << r.write_failures
            << " write failures\n  rejected: " << r.rejected_vehicle_state << " states, "
            << r.rejected_map_update << " map updates, " << r.rejected_goal << " goals; map gaps "
            << r.map_gaps << ", heals " << r.map_heals << "; vehicle lost " << r.vehicle_losses
            << " times, off its plans " << r.resyncs << " times\n"
            << "  planning thread after warm-up: "
            << (r.allocations_counted ? std::to_string(r.heap_allocations_in_loop)
                                      : std::string("(not counted)"))
            << " heap allocations, " << r.usage_in_loop.minor_faults + r.usage_in_loop.major_faults
            << " page faults, " << overruns->overruns() << " overruns\n";
  if (!o.report.empty()) {
    nlohmann::json j;
    j["robot"] = o.robot;
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
                  {"write_failures", r.write_failures}};
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
  cmd->add_option("--robot", o->robot, "dd-vel, dd-accel or car")->capture_default_str();
  cmd->add_option("--domain", o->domain, "DDS domain id")->capture_default_str();
  cmd->add_option("--dds-config", o->dds_config,
                  "Cyclone DDS XML configuration file (default: $CYCLONEDDS_URI, else the built-in "
                  "loopback-only one)");
  cmd->add_option("--period-ms", o->period_ms, "Cycle T in vehicle time [ms]")
      ->capture_default_str();
  cmd->add_option("--budget-ms", o->budget_ms, "Planning time per cycle in vehicle time [ms]")
      ->capture_default_str();
  cmd->add_option("--margin-ms", o->margin_ms,
                  "Growth stops this long before the deadline [ms] (default: budget/5)");
  cmd->add_option("--policy", o->policy, "auto, deadline, fifo or other")->capture_default_str();
  cmd->add_option("--max-edges", o->max_edges, "Edge pool (default: 400 per ms of budget)");
  cmd->add_option("--lockstep-edges", o->lockstep_edges,
                  "Edges per cycle when the vehicle runs in lockstep (a `grip sim --lockstep`)")
      ->check(CLI::Range(1U, 200'000U))
      ->capture_default_str();
  cmd->add_option("--lease-ms", o->lease_ms, "Liveliness lease of every endpoint [ms]")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Planner seed")->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Seconds of planning, 0: until Ctrl-C")
      ->capture_default_str();
  cmd->add_option("--startup-timeout", o->startup_timeout_s,
                  "Give up if map, state and goal are not there after this many seconds (0: wait)")
      ->capture_default_str();
  cmd->add_option("--report", o->report, "Write a JSON report here");
  cmd->add_option("--cycle-trace", o->cycle_trace,
                  "Write every planning cycle's timing and outcome here (CSV)");
  cmd->callback([o]() {
    const int rc = run_planner(*o);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
