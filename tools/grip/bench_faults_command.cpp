// `grip bench faults`: the planner (`grip planner`) and the vehicle (`grip sim`) as two processes
// in two network namespaces joined by a veth pair, through fault profiles: none, 10% and 30%
// loss, 50 +- 10 ms delay, a 2 s cut, the planner killed and restarted, the simulator killed and
// restarted. A row per vehicle and profile: result, coverage, collisions, plans lost, contingency
// stops and recovery time; the target is 0 collisions and a complete exploration in each.
// Needs root (namespaces, netfilter). The namespaces (grip-f<pid>p and grip-f<pid>v) and every
// process are this run's own and gone when it ends, however it ends; traffic never leaves them.
// A benchmark: it measures and prints, it asserts nothing.

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench_children.hpp"
#include "commands.hpp"
#include "dds_config.hpp"
#include "fault_profile.hpp"
#include "fault_run.hpp"
#include "netns_pair.hpp"
#include "report_file.hpp"
#include "stop_signal.hpp"
#include "vehicle_arg.hpp"

namespace grip::tools {

namespace {

struct BenchFaultsOptions {
  std::vector<std::string> robots{"dd-vel"};
  std::vector<std::string> profiles = fault_profile_names();
  std::string scene = "rooms";
  std::string map;
  std::uint64_t seed = 1;
  double time_scale = kDefaultTimeScale;
  double max_sim_time_s = kDefaultMaxSimTimeS;
  double fault_at_s = 10.0;
  unsigned domain = 0;  // inside the namespaces: no other run can hear it
  std::string out_dir = "bench-faults";
  std::string json;
};

bool in_path(const std::string& tool) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path == nullptr ? "/usr/sbin:/usr/bin:/sbin:/bin" : path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (access((dir + "/" + tool).c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string optional_text(const std::optional<double>& v, int precision) {
  if (!v) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(precision) << *v;
  return s.str();
}

void print_table(const std::vector<FaultRunOutcome>& rows) {
  std::cout << "\n"
            << std::left << std::setw(17) << "profile" << std::setw(10) << "robot" << std::setw(11)
            << "result" << std::right << std::setw(9) << "coverage" << std::setw(11) << "collisions"
            << std::setw(11) << "plans lost" << std::setw(12) << "cont. stops" << std::setw(12)
            << "recovery s"
            << "  target\n";
  std::size_t met = 0;
  for (const FaultRunOutcome& r : rows) {
    met += r.target_met() ? 1U : 0U;
    const nlohmann::json& j = r.report;
    const bool have = !j.is_null();
    std::cout << std::left << std::setw(17) << r.profile << std::setw(10) << r.robot
              << std::setw(11) << r.result << std::right << std::setw(9)
              << (have ? optional_text(j.value("coverage", 0.0), 3) : "-") << std::setw(11)
              << (have ? std::to_string(j.value("collisions", 0)) : "-") << std::setw(11)
              << (r.plans_lost ? std::to_string(*r.plans_lost) : "-") << std::setw(12)
              << (have ? std::to_string(j.value("contingency_stops", 0)) : "-") << std::setw(12)
              << optional_text(r.recovery_s, 1) << "  " << (r.target_met() ? "met" : "NOT met")
              << (r.error.empty() ? "" : " (" + r.error + ")") << "\n";
  }
  std::cout << "\ntarget (every profile: 0 collisions, complete): "
            << (met == rows.size() ? "met on all " + std::to_string(rows.size())
                                   : "NOT met on " + std::to_string(rows.size() - met) + " of " +
                                         std::to_string(rows.size()))
            << " runs\n";
}

nlohmann::json optional_json(const auto& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::json run_json(const FaultRunOutcome& r, const std::string& report_path) {
  nlohmann::json e{{"profile", r.profile},
                   {"robot", r.robot},
                   {"result", r.result},
                   {"target_met", r.target_met()},
                   {"plans_lost", optional_json(r.plans_lost)},
                   {"recovery_s", optional_json(r.recovery_s)},
                   {"fault_start_sim_s", optional_json(r.fault_start_s)},
                   {"fault_end_sim_s", optional_json(r.fault_end_s)},
                   {"planner_starts", r.planner_starts},
                   {"vehicle_starts", r.vehicle_starts},
                   {"sim_exit_status", r.sim_exit_status},
                   {"wall_time_s", r.wall_time_s},
                   {"report", report_path}};
  if (!r.error.empty()) e["error"] = r.error;
  if (!r.report.is_null()) {
    for (const char* key : {"coverage", "collisions", "contingency_stops", "plans_received",
                            "plans_rejected", "planner_losses", "sim_time_s", "distance_m",
                            "start_mismatches", "empty_plans", "reason"}) {
      if (r.report.contains(key)) e[key] = r.report.at(key);
    }
  }
  return e;
}

Status write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) return Error{ErrorCode::kIo, "cannot write '" + path + "'"};
  return Ok{};
}

int run_bench(const BenchFaultsOptions& o) {
  const char* command = "grip bench faults";
  if (geteuid() != 0) {
    std::cerr << command
              << ": needs root (it creates network namespaces and netfilter rules); run it as "
                 "root or with sudo\n";
    return 2;
  }
  for (const char* tool : {"ip", "iptables", "setpriv"}) {
    if (!in_path(tool)) {
      std::cerr << command << ": needs '" << tool
                << "' (Debian: iproute2, iptables, util-linux; scripts/bootstrap.sh)\n";
      return 2;
    }
  }
  std::vector<FaultProfile> profiles;
  for (const std::string& name : o.profiles) {
    auto p = find_fault_profile(name);
    if (!p) {
      std::cerr << command << ": " << p.error().message << "\n";
      return 2;
    }
    profiles.push_back(*p);
  }
  if (!o.map.empty() && !std::filesystem::is_regular_file(o.map)) {
    std::cerr << command << ": " << o.map << ": no such map file\n";
    return 2;
  }
  std::string self;
  if (const int rc = prepare_bench_children(command, o.out_dir, self); rc != 0) return rc;
  const std::string out_dir = std::filesystem::absolute(o.out_dir).string();
  stop_on_signals();  // Ctrl-C: the run in progress ends, then everything is cleaned up
  auto link = NetnsPair::create("f" + std::to_string(getpid()));
  if (!link) {
    std::cerr << command << ": " << link.error().message << "\n";
    return 1;
  }
  FaultRunSetup setup;
  setup.grip = self;
  setup.link = &*link;
  setup.world_args = o.map.empty() ? std::vector<std::string>{"--scene", o.scene}
                                   : std::vector<std::string>{"--map", o.map};
  setup.seed = o.seed;
  setup.time_scale = o.time_scale;
  setup.max_sim_time_s = o.max_sim_time_s;
  setup.fault_at_s = o.fault_at_s;
  setup.domain = o.domain;
  setup.planner_dds_config = out_dir + "/planner.cyclonedds.xml";
  setup.vehicle_dds_config = out_dir + "/vehicle.cyclonedds.xml";
  for (const auto& [path, end] : {std::pair{setup.planner_dds_config, &link->planner()},
                                  std::pair{setup.vehicle_dds_config, &link->vehicle()}}) {
    if (Status s = write_file(path, NetnsPair::cyclone_config(*end)); !s) {
      std::cerr << command << ": " << s.error().message << "\n";
      return 1;
    }
  }
  const std::string world = o.map.empty() ? o.scene : o.map;
  std::cout << command << ": " << o.robots.size() * profiles.size() << " runs on " << world
            << ", time scale " << o.time_scale << ", faults " << o.fault_at_s
            << " s (wall) into each; planner in " << link->planner().netns << ", vehicle in "
            << link->vehicle().netns << "; reports in " << o.out_dir << "/\n";
  std::vector<FaultRunOutcome> rows;
  std::vector<std::string> reports;
  for (const std::string& robot : o.robots) {
    for (const FaultProfile& profile : profiles) {
      if (stop_flag().load()) break;
      setup.robot = robot;
      setup.stem = out_dir + "/" + vehicle_label(robot) + "-" + profile.name;
      rows.push_back(run_fault_profile(setup, profile));
      reports.push_back(setup.stem + ".json");
      const FaultRunOutcome& r = rows.back();
      std::cout << "[" << rows.size() << "/" << o.robots.size() * profiles.size() << "] " << r.robot
                << " " << r.profile << ": " << r.result;
      if (!r.report.is_null()) {
        std::cout << ", coverage " << std::fixed << std::setprecision(3)
                  << r.report.value("coverage", 0.0) << ", collisions "
                  << r.report.value("collisions", 0) << ", " << std::setprecision(0)
                  << r.report.value("sim_time_s", 0.0) << " s simulated";
      }
      std::cout << (r.error.empty() ? "" : " (" + r.error + ")") << std::endl;
    }
  }
  print_table(rows);
  if (!o.json.empty()) {
    nlohmann::json j;
    j["world"] = world;
    j["seed"] = o.seed;
    j["time_scale"] = o.time_scale;
    j["max_sim_time_s"] = o.max_sim_time_s;
    j["fault_at_wall_s"] = o.fault_at_s;
    j["link"] = {{"planner", {{"address", link->planner().address}}},
                 {"vehicle", {{"address", link->vehicle().address}}}};
    nlohmann::json runs = nlohmann::json::array();
    for (std::size_t i = 0; i < rows.size(); ++i) runs.push_back(run_json(rows[i], reports[i]));
    j["runs"] = runs;
    if (!write_report(command, o.json, std::move(j), 1)) return 1;  // whole or not at all
  }
  return stop_flag().load() ? 130 : 0;
}

}  // namespace

void register_bench_faults_command(CLI::App& bench) {
  auto o = std::make_shared<BenchFaultsOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "faults",
      "Planner and vehicle in two network namespaces, through link faults and restarts (root)");
  cmd->add_option("--robots", o->robots,
                  "Vehicles: dd-vel, dd-accel, car, or parameter files (.yaml)")
      ->delimiter(',')
      ->check(CLI::IsMember({"dd-vel", "dd-accel", "car"}) | CLI::ExistingFile)
      ->capture_default_str();
  cmd->add_option("--profiles", o->profiles, "Fault profiles")
      ->delimiter(',')
      ->check(CLI::IsMember(fault_profile_names()))
      ->capture_default_str();
  cmd->add_option("--scene", o->scene, "meandros, labyrinth or rooms")
      ->check(CLI::IsMember({"meandros", "labyrinth", "rooms"}))
      ->capture_default_str();
  cmd->add_option("--map", o->map, "A MovingAI .map or ROS .yaml file instead of a scene");
  cmd->add_option("--seed", o->seed, "Planner seed")->capture_default_str();
  cmd->add_option("--time-scale", o->time_scale, "Simulated s per wall s")
      ->check(CLI::Range(0.01, 50.0))
      ->capture_default_str();
  cmd->add_option("--max-sim-time", o->max_sim_time_s, "Per run [s of simulated time]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--fault-at", o->fault_at_s,
                  "The fault begins this many wall-clock seconds after the simulator starts")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--domain", o->domain, "DDS domain id (inside the namespaces)")
      ->check(CLI::Range(0U, kMaxDomainId))
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "Directory for every run's reports and logs")
      ->capture_default_str();
  cmd->add_option("--json", o->json, "Write the table's figures here");
  cmd->callback([o]() {
    if (const int rc = run_bench(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
