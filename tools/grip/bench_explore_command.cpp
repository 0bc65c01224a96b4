// `grip bench explore`: exploration over scenes (and map files) x robots x seeds, the issue's
// matrix, each run a private `grip explore` child process (or on its own DDS domain with
// --domain) with its report (and
// picture and log) kept in one directory. Prints a line per run as it ends, then a table per
// world and robot against the targets: every run with zero collisions and coverage of at least
// 0.97 (and how many ended complete: no reachable frontier left), or with --no-safety, how
// many runs collided and how soon.
// A benchmark: it measures and prints, it asserts nothing.

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_children.hpp"
#include "commands.hpp"
#include "dds_config.hpp"
#include "grip/params/params.hpp"
#include "grip/sim/sim_participant.hpp"
#include "report_file.hpp"
#include "stats.hpp"
#include "vehicle_arg.hpp"

namespace grip::tools {

namespace {

struct BenchExploreOptions {
  std::vector<std::string> scenes{"meandros", "labyrinth", "rooms"};
  std::vector<std::string> maps;
  std::vector<std::string> robots{"dd-vel", "dd-accel", "car"};
  unsigned seeds = 10;
  std::uint64_t first_seed = 1;
  bool lockstep = false;
  std::uint32_t lockstep_edges = params::PlannerParams{}.lockstep_edges;
  double time_scale = kDefaultTimeScale;
  double max_sim_time_s = kDefaultMaxSimTimeS;
  bool no_safety = false;
  unsigned jobs = 1;
  // Unset: every run private (tools/grip/private_link.hpp); set: runs use domain, domain + 1,
  // ... (one per job), shared with whatever else is on them.
  std::optional<unsigned> domain;
  std::string out_dir = "bench-explore";
  std::string json;
  bool images = false;
  bool cycle_traces = false;
};

struct Run {
  std::string world;  // a scene name or a map file
  bool is_map = false;
  std::string robot;
  std::uint64_t seed = 0;
  std::string stem;  // of its report, log and picture in out_dir
  int exit_status = -1;
  nlohmann::json report;  // empty when the run left none
};

std::string world_label(const Run& r) {
  return r.is_map ? std::filesystem::path(r.world).filename().string() : r.world;
}

std::vector<std::string> explore_args(const BenchExploreOptions& o, const Run& r,
                                      const std::string& self, std::optional<unsigned> domain) {
  std::vector<std::string> args{self,
                                "explore",
                                r.is_map ? "--map" : "--scene",
                                r.world,
                                vehicle_args(r.robot)[0],
                                r.robot,
                                "--seed",
                                std::to_string(r.seed),
                                "--max-sim-time",
                                std::to_string(o.max_sim_time_s),
                                "--report",
                                o.out_dir + "/" + r.stem + ".json"};
  if (domain) {
    args.insert(args.end(), {"--domain", std::to_string(*domain)});
  } else {
    args.emplace_back("--private");  // even with a parameter file that names a domain
  }
  if (o.lockstep) {
    args.insert(args.end(), {"--lockstep", "--lockstep-edges", std::to_string(o.lockstep_edges)});
  } else {
    args.insert(args.end(), {"--time-scale", std::to_string(o.time_scale)});
  }
  if (o.no_safety) args.emplace_back("--no-safety");
  if (o.images) args.insert(args.end(), {"--image", o.out_dir + "/" + r.stem + ".png"});
  if (o.cycle_traces) {
    args.insert(args.end(), {"--cycle-trace", o.out_dir + "/" + r.stem + ".cycles.csv"});
  }
  return args;
}

std::string run_line(const Run& r) {
  std::ostringstream line;
  line << world_label(r) << " " << vehicle_label(r.robot) << " seed " << r.seed << ": ";
  if (r.report.is_null()) {
    line << "no report (exit " << r.exit_status << ")";
    return line.str();
  }
  const nlohmann::json& j = r.report;
  line << j.value("result", "?") << ", coverage " << std::fixed << std::setprecision(3)
       << j.value("coverage", 0.0) << ", collisions " << j.value("collisions", 0) << ", "
       << std::setprecision(0) << j.value("sim_time_s", 0.0) << " s simulated, "
       << j.value("wall_time_s", 0.0) << " s wall";
  return line.str();
}

// Tables show 0 for no samples.
double median(const std::vector<double>& v) { return tools::median(v, 0.0); }

// One row of the table: the runs of one world and robot.
struct Row {
  std::string world;
  std::string robot;
  int runs = 0;
  int complete = 0;
  int with_report = 0;
  int collided = 0;  // runs with at least one collision
  std::uint64_t collisions = 0;
  double min_coverage = 1.0;
  std::vector<double> coverage, sim_time, wall_time, speed, bound, turning_bound, retraced,
      reversing, first_collision;
  bool target_met(bool no_safety) const {
    if (no_safety) return collided > 0;  // the ablation shows why the safety step exists
    // The target; whether each run also ended by itself is the `complete` column.
    return with_report == runs && collisions == 0 && min_coverage >= sim::kCompleteCoverage;
  }
};

std::vector<Row> tabulate(const std::vector<Run>& runs) {
  std::vector<Row> rows;
  for (const Run& r : runs) {
    auto row = std::find_if(rows.begin(), rows.end(), [&](const Row& x) {
      return x.world == world_label(r) && x.robot == r.robot;
    });
    if (row == rows.end()) {
      Row fresh;
      fresh.world = world_label(r);
      fresh.robot = r.robot;
      rows.push_back(std::move(fresh));
      row = rows.end() - 1;
    }
    ++row->runs;
    if (r.report.is_null()) {
      row->min_coverage = 0.0;
      continue;
    }
    const nlohmann::json& j = r.report;
    ++row->with_report;
    row->complete += j.value("result", "") == "complete" ? 1 : 0;
    const auto collisions = j.value("collisions", std::uint64_t{0});
    row->collisions += collisions;
    if (collisions > 0) {
      ++row->collided;
      const auto& events = j.at("collision_events");
      if (!events.empty()) row->first_collision.push_back(events[0].value("time_s", 0.0));
    }
    row->min_coverage = std::min(row->min_coverage, j.value("coverage", 0.0));
    row->coverage.push_back(j.value("coverage", 0.0));
    row->sim_time.push_back(j.value("sim_time_s", 0.0));
    row->wall_time.push_back(j.value("wall_time_s", 0.0));
    row->speed.push_back(j.value("mean_speed_fraction", 0.0));
    row->bound.push_back(j.value("braking_bound_fraction", 0.0));
    row->turning_bound.push_back(j.value("turning_bound_fraction", 0.0));
    row->retraced.push_back(j.value("retraced_fraction", 0.0));
    row->reversing.push_back(j.value("reversing_fraction", 0.0));
  }
  return rows;
}

void print_table(const BenchExploreOptions& o, const std::vector<Row>& rows) {
  std::cout << "\n"
            << std::left << std::setw(26) << "world" << std::setw(10) << "robot" << std::right
            << std::setw(9) << "complete" << std::setw(11) << "collisions" << std::setw(9)
            << "collided" << std::setw(10) << "cov min" << std::setw(10) << "cov med"
            << std::setw(11) << "sim s med" << std::setw(12) << "wall s med" << std::setw(11)
            << "speed med" << std::setw(11) << "bound med" << std::setw(12) << "turns med"
            << std::setw(14) << "retraced med" << std::setw(11) << "1st coll s"
            << "  target\n";
  std::size_t short_of_target = 0;
  for (const Row& r : rows) {
    const bool met = r.target_met(o.no_safety);
    short_of_target += met ? 0 : 1;
    std::ostringstream complete;
    complete << r.complete << "/" << r.runs;
    // A world name longer than its column still leaves a space before the robot.
    std::cout << std::left << std::setw(26) << r.world + " " << std::setw(10)
              << vehicle_label(r.robot) << std::right << std::setw(9) << complete.str()
              << std::setw(11) << r.collisions << std::setw(9) << r.collided << std::fixed
              << std::setprecision(3) << std::setw(10) << r.min_coverage << std::setw(10)
              << median(r.coverage) << std::setprecision(1) << std::setw(11) << median(r.sim_time)
              << std::setw(12) << median(r.wall_time) << std::setprecision(2) << std::setw(11)
              << median(r.speed) << std::setw(11) << median(r.bound) << std::setw(12)
              << median(r.turning_bound) << std::setw(14) << median(r.retraced)
              << std::setprecision(1) << std::setw(11);
    if (r.first_collision.empty()) {
      std::cout << "-";
    } else {
      std::cout << median(r.first_collision);
    }
    std::cout << "  " << (met ? "met" : "NOT met") << "\n";
  }
  std::cout << "\ntarget ("
            << (o.no_safety ? "--no-safety: collisions appear"
                            : "every run: 0 collisions, coverage >= 0.97")
            << "): ";
  if (short_of_target == 0) {
    std::cout << "met on all " << rows.size() << " world/robot pairs\n";
  } else {
    std::cout << "NOT met on " << short_of_target << " of " << rows.size()
              << " world/robot pairs\n";
  }
}

int run_bench(const BenchExploreOptions& o) {
  if (o.domain && *o.domain + std::max(1U, o.jobs) - 1 > kMaxDomainId) {
    std::cerr << "grip bench explore: --domain " << *o.domain << " with --jobs " << o.jobs
              << " would use domains above " << kMaxDomainId << "\n";
    return 2;
  }
  std::string self;
  if (const int rc = prepare_bench_children("grip bench explore", o.out_dir, self); rc != 0) {
    return rc;
  }
  for (const std::string& map : o.maps) {
    if (!std::filesystem::is_regular_file(map)) {
      std::cerr << "grip bench explore: " << map << ": no such map file\n";
      return 2;
    }
  }
  std::vector<Run> runs;
  const auto add_world = [&](const std::string& world, bool is_map) {
    for (const std::string& robot : o.robots) {
      for (std::uint64_t seed = o.first_seed; seed < o.first_seed + o.seeds; ++seed) {
        Run r;
        r.world = world;
        r.is_map = is_map;
        r.robot = robot;
        r.seed = seed;
        std::string label = world_label(r);
        std::replace(label.begin(), label.end(), '.', '_');
        r.stem = label + "-" + vehicle_label(robot) + "-" + std::to_string(seed);
        runs.push_back(std::move(r));
      }
    }
  };
  for (const std::string& scene : o.scenes) {
    if (!scene.empty()) add_world(scene, false);
  }
  for (const std::string& map : o.maps) add_world(map, true);

  std::cout << "grip bench explore: " << runs.size() << " runs, "
            << (o.lockstep ? "lockstep (" + std::to_string(o.lockstep_edges) + " edges a cycle)"
                           : "real time, time scale " + std::to_string(o.time_scale))
            << (o.no_safety ? ", no safety check" : "") << ", " << o.jobs
            << " at a time; reports in " << o.out_dir << "/\n";
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::mutex print;
  const auto worker = [&](unsigned slot) {
    for (std::size_t i = next++; i < runs.size(); i = next++) {
      Run& r = runs[i];
      const std::string report = o.out_dir + "/" + r.stem + ".json";
      std::error_code ec;
      std::filesystem::remove(report, ec);
      auto child = Child::spawn(
          explore_args(o, r, self,
                       o.domain ? std::optional<unsigned>(*o.domain + slot) : std::nullopt),
          {}, o.out_dir + "/" + r.stem + ".log", true);
      if (child) r.exit_status = child->wait();
      r.report = read_child_report(report);
      const std::lock_guard<std::mutex> lock(print);
      std::cout << "[" << ++done << "/" << runs.size() << "] " << run_line(r)
                << (child ? "" : " (" + child.error().message + ")") << std::endl;
    }
  };
  std::vector<std::thread> workers;
  for (unsigned slot = 0; slot < std::max(1U, o.jobs); ++slot) workers.emplace_back(worker, slot);
  for (auto& w : workers) w.join();

  const std::vector<Row> rows = tabulate(runs);
  print_table(o, rows);
  if (!o.json.empty()) {
    nlohmann::json j;
    j["mode"] = o.lockstep ? "lockstep" : "real time";
    if (o.lockstep) {
      j["lockstep_edges"] = o.lockstep_edges;
    } else {
      j["time_scale"] = o.time_scale;
    }
    j["safety"] = !o.no_safety;
    j["max_sim_time_s"] = o.max_sim_time_s;
    nlohmann::json list = nlohmann::json::array();
    for (const Run& r : runs) {
      nlohmann::json e{{"world", world_label(r)},
                       {"robot", vehicle_label(r.robot)},
                       {"seed", r.seed},
                       {"exit_status", r.exit_status},
                       {"report", o.out_dir + "/" + r.stem + ".json"}};
      if (!r.report.is_null()) {
        for (const char* key :
             {"result", "coverage", "collisions", "sim_time_s", "wall_time_s",
              "mean_speed_fraction", "braking_bound_fraction", "turning_bound_fraction",
              "without_plan_fraction", "distance_m", "retraced_fraction", "empty_plans",
              "start_mismatches", "cycles", "deadline_misses"}) {
          if (r.report.contains(key)) e[key] = r.report.at(key);
        }
      }
      list.push_back(e);
    }
    j["runs"] = list;
    nlohmann::json table = nlohmann::json::array();
    for (const Row& r : rows) {
      table.push_back({{"world", r.world},
                       {"robot", vehicle_label(r.robot)},
                       {"runs", r.runs},
                       {"complete", r.complete},
                       {"collisions", r.collisions},
                       {"runs_with_collision", r.collided},
                       {"min_coverage", r.min_coverage},
                       {"median_coverage", median(r.coverage)},
                       {"median_sim_time_s", median(r.sim_time)},
                       {"median_wall_time_s", median(r.wall_time)},
                       {"median_mean_speed_fraction", median(r.speed)},
                       {"median_braking_bound_fraction", median(r.bound)},
                       {"median_turning_bound_fraction", median(r.turning_bound)},
                       {"median_retraced_fraction", median(r.retraced)},
                       {"median_reversing_fraction", median(r.reversing)},
                       {"target_met", r.target_met(o.no_safety)}});
    }
    j["table"] = table;
    if (!write_report("grip bench explore", o.json, std::move(j), 1)) return 1;
  }
  return 0;
}

}  // namespace

void register_bench_explore_command(CLI::App& bench) {
  auto o = std::make_shared<BenchExploreOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "explore", "Exploration over scenes x robots x seeds (each run a `grip explore`)");
  cmd->add_option("--scenes", o->scenes, "Built-in scenes (none: --scenes '')")
      ->delimiter(',')
      ->check(CLI::IsMember({"meandros", "labyrinth", "rooms", ""}))
      ->capture_default_str();
  cmd->add_option("--map", o->maps, "A MovingAI .map or ROS .yaml file to explore too (repeat)");
  cmd->add_option("--robots", o->robots,
                  "Vehicles: dd-vel, dd-accel, car, or parameter files (.yaml)")
      ->delimiter(',')
      ->check(CLI::IsMember({"dd-vel", "dd-accel", "car"}) | CLI::ExistingFile)
      ->capture_default_str();
  cmd->add_option("--seeds", o->seeds, "Seeds per world and robot")
      ->check(CLI::Range(1U, 1000U))
      ->capture_default_str();
  cmd->add_option("--first-seed", o->first_seed, "The first seed")->capture_default_str();
  cmd->add_flag("--lockstep", o->lockstep, "Lockstep runs (deterministic, as fast as possible)");
  cmd->add_option("--lockstep-edges", o->lockstep_edges, "Edges per cycle in lockstep")
      ->check(CLI::Range(1U, 200'000U))
      ->capture_default_str();
  cmd->add_option("--time-scale", o->time_scale, "Real-time runs: simulated s per wall s")
      ->check(CLI::Range(0.01, 50.0))
      ->capture_default_str();
  cmd->add_option("--max-sim-time", o->max_sim_time_s, "Per run [s of simulated time]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--no-safety", o->no_safety, "The ablation: no contingency check");
  cmd->add_option("--jobs", o->jobs, "Runs at a time")
      ->check(CLI::Range(1U, 64U))
      ->capture_default_str();
  cmd->add_option("--domain", o->domain,
                  "First DDS domain id (one per job; default: every run private to itself)")
      ->check(CLI::Range(0U, kMaxDomainId));
  cmd->add_option("--out", o->out_dir, "Directory for every run's report and log")
      ->capture_default_str();
  cmd->add_flag("--images", o->images, "Also draw every run's picture into --out");
  cmd->add_flag("--cycle-traces", o->cycle_traces,
                "Also write every run's planning cycles into --out (CSV, as --cycle-trace)");
  cmd->add_option("--json", o->json, "Write the table and every run's figures here");
  cmd->callback([o]() {
    if (const int rc = run_bench(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
