// `grip explore` and `grip sim` run for real on a small map: the report has every field the
// issue names, the vehicle moves on the planner's plans without a collision, and the picture is
// written; the simulator and the planner also work as two processes over loopback (the
// host-in-the-loop setup); bad maps and options are refused naming what is wrong.
// Nothing about time is asserted.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "grip_command.hpp"
#include "small_room_map.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::kGrip;

CommandRun run(const std::string& arguments) { return grip::testing::run_grip(arguments); }

std::string write_small_map() {
  return grip::testing::write_small_room_map("grip-explore-small.map");
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

void expect_a_sane_run(const nlohmann::json& r, const std::string& output) {
  for (const char* key :
       {"result", "coverage", "collisions", "cycles", "deadline_misses", "sim_time_s", "distance_m",
        "mean_speed_fraction", "plans_received", "contingency_stops", "speed_profile",
        "retraced_fraction", "braking_bound_fraction", "turning_bound_fraction",
        "without_plan_fraction", "reversing_fraction"}) {
    ASSERT_TRUE(r.contains(key)) << key << "\n" << output;
  }
  const std::string result = r.at("result");
  EXPECT_TRUE(result == "complete" || result == "timeout") << result << "\n" << output;
  EXPECT_EQ(r.at("collisions").get<int>(), 0) << r.at("collision_events").dump();
  EXPECT_GT(r.at("plans_received").get<int>(), 20) << output;
  EXPECT_GT(r.at("distance_m").get<double>(), 1.0) << "the vehicle never followed a plan";
  EXPECT_GT(r.at("coverage").get<double>(), 0.2);
  EXPECT_LE(r.at("coverage").get<double>(), 1.0);
  EXPECT_GE(r.at("retraced_fraction").get<double>(), 0.0);
  EXPECT_LT(r.at("retraced_fraction").get<double>(), 1.0);
  EXPECT_GT(r.at("speed_profile").size(), 100U);
  // Braking within the sensed region allows something, never more than the top speed (1 for
  // a vehicle that stops at once).
  EXPECT_GT(r.at("braking_bound_fraction").get<double>(), 0.0);
  EXPECT_LE(r.at("braking_bound_fraction").get<double>(), 1.0);
  // Within the route's turns, no more than that.
  EXPECT_GT(r.at("turning_bound_fraction").get<double>(), 0.0);
  EXPECT_LE(r.at("turning_bound_fraction").get<double>(),
            r.at("braking_bound_fraction").get<double>());
  EXPECT_GE(r.at("without_plan_fraction").get<double>(), 0.0);
  EXPECT_LT(r.at("without_plan_fraction").get<double>(), 1.0);
  EXPECT_GE(r.at("reversing_fraction").get<double>(), 0.0);
  EXPECT_LT(r.at("reversing_fraction").get<double>(), 1.0);
  // How much of the time the vehicle went faster than 50% and 80% of its maximum, per sample.
  const double max_speed = r.at("max_speed_m_s").get<double>();
  ASSERT_GT(max_speed, 0.0);
  std::size_t above_50 = 0;
  std::size_t above_80 = 0;
  for (const auto& p : r.at("speed_profile")) {
    above_50 += p.at(1).get<double>() > 0.5 * max_speed ? 1U : 0U;
    above_80 += p.at(1).get<double>() > 0.8 * max_speed ? 1U : 0U;
  }
  const auto n = static_cast<double>(r.at("speed_profile").size());
  EXPECT_DOUBLE_EQ(r.at("time_fraction_above_50pct_max_speed").get<double>(),
                   static_cast<double>(above_50) / n);
  EXPECT_DOUBLE_EQ(r.at("time_fraction_above_80pct_max_speed").get<double>(),
                   static_cast<double>(above_80) / n);
  // Coverage grew from the start's to the report's, in time; each mark's time is the first
  // sample at or above it, null when the run never got there.
  const auto& coverage = r.at("coverage_profile");
  ASSERT_FALSE(coverage.empty());
  EXPECT_EQ(coverage.front().at(0).get<double>(), 0.0);
  EXPECT_EQ(coverage.back().at(1).get<double>(), r.at("coverage").get<double>());
  EXPECT_LE(coverage.back().at(0).get<double>(), r.at("sim_time_s").get<double>());
  for (std::size_t i = 1; i < coverage.size(); ++i) {
    EXPECT_GT(coverage[i].at(0).get<double>(), coverage[i - 1].at(0).get<double>());
    EXPECT_GT(coverage[i].at(1).get<double>(), coverage[i - 1].at(1).get<double>());
  }
  for (const auto& [key, share] :
       {std::pair{"0.5", 0.5}, std::pair{"0.9", 0.9}, std::pair{"0.97", 0.97}}) {
    const nlohmann::json& reached = r.at("time_to_coverage_s").at(key);
    const auto first = std::find_if(coverage.begin(), coverage.end(), [&](const auto& sample) {
      return sample.at(1).template get<double>() >= share;
    });
    if (first == coverage.end()) {
      EXPECT_TRUE(reached.is_null()) << key;
    } else {
      EXPECT_EQ(reached.get<double>(), first->at(0).get<double>()) << key;
    }
  }
  if (r.at("result") == "complete") {
    EXPECT_FALSE(r.at("time_to_coverage_s").at("0.97").is_null());
  }
}

// A CSV line's fields, empty ones included.
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields(1);
  for (const char c : line) {
    if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// The cycle trace: a header and one row per planning cycle, numbered from 0, each row's phases
// within its compute time, its miss consistent with its lateness and a restart with its cause.
// Exploring within a map of map_side_m: the target inside it once there is one, and a choice
// without sight of it only of an end closer to it than the root (the path selector's rule).
void expect_a_cycle_trace(const std::string& path, std::uint64_t planner_cycles,
                          double map_side_m) {
  std::ifstream in(path);
  std::string line;
  ASSERT_TRUE(std::getline(in, line)) << path << " is empty";
  const std::vector<std::string> header = fields_of(line);
  const auto column = [&](const char* name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name << " missing from " << line;
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t cycle = column("cycle"), wake = column("wake_us"),
                    prepare = column("prepare_us"), retain = column("retain_us"),
                    grow = column("grow_us"), commit = column("commit_us"),
                    commit_reserve = column("commit_reserve_us"), compute = column("compute_us"),
                    lateness = column("lateness_us"), missed = column("missed"),
                    skipped = column("skipped"), restarted = column("restarted"),
                    committed = column("committed"), status = column("retain_status"),
                    cause = column("restart_cause"), start_x = column("start_x_m"),
                    start_y = column("start_y_m"), target_x = column("target_x_m"),
                    target_y = column("target_y_m"), root_rho = column("root_rho_m"),
                    choice = column("choice"), choice_d = column("choice_d_m"),
                    choice_length = column("choice_length_m");
  std::uint64_t rows = 0;
  std::uint64_t chosen_by_sight = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = fields_of(line);
    ASSERT_EQ(f.size(), header.size()) << line;
    // Every field a number but the names; an empty one (no figure) reads as NaN.
    std::vector<double> v;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const bool name = i == status || i == cause || i == choice;
      v.push_back(name ? 0.0 : f[i].empty() ? std::nan("") : std::stod(f[i]));
    }
    const std::string& status_name = f[status];
    const std::string& cause_name = f[cause];
    // Why the tree could not be kept or started; a committed plan comes from a tree that was.
    EXPECT_TRUE(status_name == "ok" || status_name == "root-not-in-tree" ||
                status_name == "root-in-collision" || status_name == "invalid-state" ||
                status_name == "goal-outside-grid" || status_name == "goal-without-free-cell")
        << line;
    if (v[committed] == 1.0) {
      EXPECT_EQ(status_name, "ok") << line;
    }
    if (status_name != "ok") {
      EXPECT_EQ(v[restarted], 1.0) << line;
    }
    // A restart says why; a kept tree has no cause.
    EXPECT_TRUE(cause_name == "none" || cause_name == "vehicle-off-plans" ||
                cause_name == "no-plan" || cause_name == "root-in-collision" ||
                cause_name == "retain-refused" || cause_name == "tree-full-without-plan")
        << line;
    EXPECT_EQ(v[restarted] == 1.0, cause_name != "none") << line;
    EXPECT_EQ(v[cycle], static_cast<double>(rows)) << line;
    EXPECT_GE(v[wake], 0.0) << line;
    EXPECT_GE(v[commit_reserve], 0.0) << line;
    EXPECT_LE(v[prepare] + v[retain] + v[grow] + v[commit], v[compute] + 1.0) << line;
    EXPECT_EQ(v[missed] == 1.0, v[lateness] > 0.0) << line;
    // A skipped cycle ran no body: it has no start and made no choice.
    if (v[skipped] == 1.0) {
      EXPECT_TRUE(std::isnan(v[start_x]) && std::isnan(v[start_y]) && f[choice].empty()) << line;
      ++rows;
      continue;
    }
    // The plan starts in the map.
    EXPECT_TRUE(v[start_x] >= 0.0 && v[start_x] <= map_side_m) << line;
    EXPECT_TRUE(v[start_y] >= 0.0 && v[start_y] <= map_side_m) << line;
    // Exploring: the target's centre lies in the map, and an end was chosen by sight of the
    // target or by rho, or none was (its figures then empty).
    EXPECT_EQ(std::isnan(v[target_x]), std::isnan(v[target_y])) << line;
    if (!std::isnan(v[target_x])) {
      EXPECT_TRUE(v[target_x] >= 0.0 && v[target_x] <= map_side_m) << line;
      EXPECT_TRUE(v[target_y] >= 0.0 && v[target_y] <= map_side_m) << line;
    }
    const std::string& chose = f[choice];
    EXPECT_TRUE(chose == "sight" || chose == "rho" || chose == "none") << line;
    if (chose == "none") {
      EXPECT_TRUE(std::isnan(v[root_rho]) && std::isnan(v[choice_d])) << line;
    } else {
      EXPECT_GE(v[choice_d], 0.0) << line;
      EXPECT_GE(v[choice_length], 0.0) << line;
      EXPECT_GE(v[root_rho], 0.0) << line;
    }
    if (chose == "rho") {
      EXPECT_LT(v[choice_d], v[root_rho]) << line;
    }
    if (chose == "sight") ++chosen_by_sight;
    ++rows;
  }
  // The planner runs on for a moment after the simulator has ended the run.
  EXPECT_GE(rows, planner_cycles);
  EXPECT_GT(chosen_by_sight, 0U) << "no plan ever headed for a target in sight";
}

TEST(ExploreCommand, ExploresASmallMapWithoutCollisionAndWritesReportAndPicture) {
  const std::string map = write_small_map();
  const std::string report = ::testing::TempDir() + "grip-explore-report.json";
  const std::string image = ::testing::TempDir() + "grip-explore.png";
  const std::string trace = ::testing::TempDir() + "grip-explore-cycles.csv";
  const CommandRun r =
      run("explore --map " + map +
          " --robot dd-vel --time-scale 2 --max-sim-time 20 --domain 81 --report " + report +
          " --image " + image + " --cycle-trace " + trace);
  ASSERT_TRUE(r.status == 0 || r.status == 3) << r.output;  // complete, or timed out
  const nlohmann::json j = read_json(report);
  expect_a_sane_run(j, r.output);
  std::ifstream png(image, std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  expect_a_cycle_trace(trace, j.at("cycles").get<std::uint64_t>(), 10.0);
  // What produced it: the parameters in force and what the machine granted the planning thread.
  EXPECT_NE(j.at("parameters").get<std::string>().find("model: dd-vel"), std::string::npos);
  const std::string policy = j.at("scheduling").at("policy");
  EXPECT_TRUE(policy == "deadline" || policy == "fifo" || policy == "other") << policy;
  EXPECT_TRUE(j.at("scheduling").contains("policy_fallback_reason"));
}

// At time scale 10, as in the example: the planner's wall-clock budget is 2.5 ms.
TEST(ExploreCommand, SimulatorAndPlannerWorkAsTwoProcesses) {
  const std::string map = write_small_map();
  const std::string report = ::testing::TempDir() + "grip-sim-report.json";
  auto planner = grip::testing::ChildProcess::spawn(
      {kGrip, "planner", "--robot", "dd-vel", "--domain", "82", "--startup-timeout", "60"});
  ASSERT_TRUE(planner.has_value());
  const CommandRun r =
      run("sim --map " + map +
          " --robot dd-vel --time-scale 10 --max-sim-time 60 --domain 82 --report " + report);
  planner->kill(SIGTERM);  // a planner stops on SIGTERM, like Ctrl-C
  const int status = planner->wait();
  ASSERT_TRUE(r.status == 0 || r.status == 3) << r.output;
  expect_a_sane_run(read_json(report), r.output);
  EXPECT_TRUE(WIFEXITED(status)) << "the planner did not stop cleanly on SIGTERM";
}

// Lockstep: the simulator waits for each plan and the planner grows a fixed number of edges
// per cycle, so the run completes whatever the machine's speed, and a seed reproduces it.
TEST(ExploreCommand, LockstepExplorationCompletesWithoutCollisionAndASeedReproducesIt) {
  const std::string map = write_small_map();
  nlohmann::json reports[2];
  for (int i = 0; i < 2; ++i) {
    const std::string report =
        ::testing::TempDir() + "grip-lockstep-" + std::to_string(i) + ".json";
    const CommandRun r = run("explore --map " + map +
                             " --robot dd-vel --lockstep --seed 3 --max-sim-time 300 --domain 83 "
                             "--report " +
                             report);
    ASSERT_EQ(r.status, 0) << r.output;  // complete
    reports[i] = read_json(report);
    expect_a_sane_run(reports[i], r.output);
    EXPECT_EQ(reports[i].at("result"), "complete");
    EXPECT_GE(reports[i].at("coverage").get<double>(), 0.97);
    EXPECT_EQ(reports[i].at("deadline_misses").get<int>(), 0);
    EXPECT_EQ(reports[i].at("start_mismatches").get<int>(), 0);
    // What the machine decides: times and memory.
    for (const char* key : {"wall_time_s", "planner_startup", "peak_rss_mb"}) reports[i].erase(key);
  }
  EXPECT_EQ(reports[0], reports[1]) << "the same seed gave two different runs";
}

// A vehicle that is not the paper's, defined only in a parameter file: a car 1.2 m x 0.6 m with
// a 0.9 m wheelbase, 2 m/s top speed and brakes of 1.2 m/s^2. Planner and simulator both take
// it from the file: the run stays within its top speed, and the report's parameters are the
// file's, in a form `--params` reads back.
TEST(ExploreCommand, AVehicleDefinedOnlyInAParameterFileExploresWithinItsLimits) {
  const std::string params = ::testing::TempDir() + "grip-compact-car.yaml";
  {
    std::ofstream out(params);
    out << "vehicle:\n  model: car\n  max_speed_m_s: 2.0\n  braking_decel_m_s2: 1.2\n"
           "  wheelbase_m: 0.9\n  footprint: {front_m: 0.95, rear_m: 0.25, half_width_m: 0.3}\n"
           "sensor:\n  range_m: 3.0\n";  // the default, a tenth of 10 m, ends at its bonnet
  }
  const std::string report = ::testing::TempDir() + "grip-compact-car.json";
  const CommandRun r =
      run("explore --map " + write_small_map() + " --params " + params +
          " --lockstep --seed 1 --max-sim-time 600 --domain 76 --report " + report);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = read_json(report);
  expect_a_sane_run(j, r.output);
  EXPECT_EQ(j.at("robot"), "car");
  EXPECT_DOUBLE_EQ(j.at("max_speed_m_s").get<double>(), 2.0);
  double fastest = 0.0;
  for (const auto& sample : j.at("speed_profile")) {
    fastest = std::max(fastest, sample.at(1).get<double>());
  }
  EXPECT_LE(fastest, 2.0) << "faster than the file's top speed";
  EXPECT_GT(j.at("distance_m").get<double>(), 10.0) << "the car hardly moved";

  const std::string effective = ::testing::TempDir() + "grip-compact-car-effective.yaml";
  {
    std::ofstream out(effective);
    out << j.at("parameters").get<std::string>();
  }
  const CommandRun printed = run("params --params " + effective);
  ASSERT_EQ(printed.status, 0) << printed.output;
  EXPECT_EQ(printed.output, j.at("parameters").get<std::string>());
  EXPECT_NE(printed.output.find("wheelbase_m: 0.9"), std::string::npos) << printed.output;

  const CommandRun contradicted = run("explore --robot dd-vel --params " + params);
  EXPECT_EQ(contradicted.status, 2) << contradicted.output;
  EXPECT_NE(contradicted.output.find("--robot dd-vel contradicts " + params), std::string::npos)
      << contradicted.output;
}

// A planner given another vehicle's file than the simulator's: the vehicle describes itself,
// and the planner refuses to plan for it, naming the field, as a configuration error (exit 2).
// A map_server map of a room with a corridor 1.0 m wide east of it and three branches 0.8 m
// wide off the corridor at right angles (22 m x 9 m at 0.1 m): the paper's car swings into
// them, a car 1.2 m long with a turning radius of 0.9 m cannot.
std::string write_comb_map() {
  constexpr int kWidth = 220;
  constexpr int kHeight = 90;
  std::vector<unsigned char> free(kWidth * kHeight, 0);
  const auto rect = [&](int x0, int y0, int x1, int y1) {  // cells [x0, x1) x [y0, y1)
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) free[static_cast<std::size_t>(y * kWidth + x)] = 1;
    }
  };
  rect(5, 5, 45, 65);
  rect(45, 15, 215, 25);
  for (const int x : {90, 130, 170}) rect(x, 25, x + 8, 75);
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream pgm(dir + "grip-comb.pgm", std::ios::binary);
    pgm << "P5\n" << kWidth << " " << kHeight << "\n255\n";
    for (int y = kHeight - 1; y >= 0; --y) {  // the image's first row is the map's top
      for (int x = 0; x < kWidth; ++x) {
        pgm.put(static_cast<char>(free[static_cast<std::size_t>(y * kWidth + x)] ? 254 : 0));
      }
    }
  }
  std::ofstream yaml(dir + "grip-comb.yaml");
  yaml << "image: grip-comb.pgm\nmode: trinary\nresolution: 0.1\norigin: [0.0, 0.0, 0]\n"
          "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n";
  return dir + "grip-comb.yaml";
}

// Issue 23: frontiers a car cannot reach with its turning radius are recognised and the run
// says so. The compact car explores the room and the corridor and ends `stuck` naming the three
// branches, none of them set aside by the give-up clock (60 s a group of no progress). How long
// the room takes varies with the seed, from under a minute to several.
TEST(ExploreCommand, ACarEndsNamingTheFrontiersItCannotTurnInto) {
  const std::string params = ::testing::TempDir() + "grip-comb-car.yaml";
  {
    std::ofstream out(params);
    out << "vehicle:\n  model: car\n  max_speed_m_s: 2.0\n  braking_decel_m_s2: 1.2\n"
           "  wheelbase_m: 0.9\n  footprint: {front_m: 0.95, rear_m: 0.25, half_width_m: 0.3}\n";
  }
  const std::string report = ::testing::TempDir() + "grip-comb.json";
  const CommandRun r = run("explore --map " + write_comb_map() + " --params " + params +
                           " --start 2.5,3.5,0 --lockstep --max-sim-time 600 --domain 89 "
                           "--report " +
                           report);
  const nlohmann::json j = read_json(report);
  EXPECT_EQ(j.at("result"), "stuck") << r.output;
  EXPECT_NE(j.at("reason").get<std::string>().find(
                "3 frontier group(s) the vehicle cannot reach at its turning radius"),
            std::string::npos)
      << j.at("reason");
  EXPECT_EQ(j.at("planner").at("frontier_groups_unreachable"), 3);
  EXPECT_EQ(j.at("planner").at("frontier_groups_given_up"), 0);
  EXPECT_EQ(j.at("collisions"), 0);
  EXPECT_GT(j.at("coverage").get<double>(), 0.8) << "the room and the corridor are explored";
}

TEST(ExploreCommand, APlannerRefusesAVehicleThatIsNotTheOneItsParametersDescribe) {
  const std::string params = ::testing::TempDir() + "grip-slow-car.yaml";
  {
    std::ofstream out(params);
    out << "vehicle:\n  model: car\n  max_speed_m_s: 2.0\n";
  }
  auto simulator = grip::testing::ChildProcess::spawn({kGrip, "sim", "--map", write_small_map(),
                                                       "--params", params, "--lockstep", "--domain",
                                                       "75", "--max-sim-time", "60"});
  ASSERT_TRUE(simulator.has_value());
  const CommandRun planner = run("planner --robot car --domain 75 --startup-timeout 30");
  simulator->kill(SIGTERM);
  simulator->wait();
  EXPECT_EQ(planner.status, 2) << planner.output;
  EXPECT_NE(planner.output.find("the vehicle describes itself with vehicle.max_speed_m_s 2, this "
                                "planner's parameters say 3"),
            std::string::npos)
      << planner.output;
}

// Plans lost on the way (as if they came too late): the vehicle goes on with the plan it has,
// the planner sees from its states that it does not follow the plans it was sent, and plans
// from where it will be. A lost plan costs at most one refused plan after it, never a
// collision.
TEST(ExploreCommand, LostPlansAreNoticedAndCostAtMostOneRefusedPlanEach) {
  const std::string map = write_small_map();
  const std::string report = ::testing::TempDir() + "grip-lockstep-dropped.json";
  const CommandRun r = run("explore --map " + map +
                           " --robot dd-accel --lockstep --seed 3 --max-sim-time 60 "
                           "--drop-plans 0.1 --domain 87 --report " +
                           report);
  ASSERT_TRUE(r.status == 0 || r.status == 3) << r.output;
  const nlohmann::json j = read_json(report);
  expect_a_sane_run(j, r.output);
  const int dropped = j.at("plans_dropped").get<int>();
  EXPECT_GT(dropped, 20) << r.output;
  EXPECT_LE(j.at("start_mismatches").get<int>(), dropped) << r.output;
}

// A lockstep simulator repeats the state it waits on, so a planner that starts later still
// gets it (and a snapshot of the map sensed so far).
TEST(ExploreCommand, LockstepSimulatorWaitsForAPlannerThatStartsLater) {
  const std::string map = write_small_map();
  const std::string report = ::testing::TempDir() + "grip-sim-lockstep.json";
  auto planner = grip::testing::ChildProcess::spawn(
      {"/bin/sh", "-c",
       "sleep 2 && exec " + kGrip + " planner --robot dd-vel --domain 84 --startup-timeout 60"});
  ASSERT_TRUE(planner.has_value());
  const CommandRun r =
      run("sim --map " + map +
          " --robot dd-vel --lockstep --max-sim-time 300 --domain 84 --report " + report);
  planner->kill(SIGTERM);
  planner->wait();
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = read_json(report);
  expect_a_sane_run(j, r.output);
  EXPECT_EQ(j.at("result"), "complete");
  EXPECT_TRUE(j.at("lockstep").get<bool>());
}

TEST(ExploreCommand, BadMapsAndOptionsAreRefusedNamingWhatIsWrong) {
  const std::string bad_map = ::testing::TempDir() + "grip-explore-bad.map";
  {
    std::ofstream out(bad_map);
    out << "type octile\nheight 3\nwidth 4\nmap\n@@@@\n@..\n@@@@\n";
  }
  CommandRun r = run("explore --map " + bad_map);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(bad_map + ":6"), std::string::npos) << r.output;  // file and line

  r = run("explore --map /nonexistent/grip.map");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/grip.map"), std::string::npos) << r.output;

  r = run("explore --map " + write_small_map() + " --start 4.5,5.5");  // inside the pillar
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("4.5"), std::string::npos) << r.output;

  r = run("explore --lockstep --lockstep-edges 0");
  EXPECT_NE(r.status, 0) << r.output;  // CLI11's own exit code for a value out of range
  EXPECT_NE(r.output.find("--lockstep-edges"), std::string::npos) << r.output;

  r = run("explore --cycle-trace /nonexistent/grip-cycles.csv");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/grip-cycles.csv"), std::string::npos) << r.output;

  r = run("explore --time-scale 0");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--time-scale"), std::string::npos) << r.output;

  r = run("explore --sensor-range -1");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("sensor.range_m must be finite and >= 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(set by --sensor-range)"), std::string::npos) << r.output;

  for (const char* timeout : {"-1", "inf", "nan"}) {
    r = run(std::string("explore --startup-timeout ") + timeout);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("--startup-timeout must be in [0, 86400] s"), std::string::npos)
        << r.output;
  }
}

TEST(ExploreCommand, APlannerThatCannotStartInItsTimeoutEndsTheRunSayingWhatItWaitedFor) {
  // A planner cannot start within a millisecond: at the least, it waits for a goal for a while
  // before it explores. What it still waited for is named, whatever that was at the time.
  const CommandRun r =
      run("explore --map " + write_small_map() + " --lockstep --startup-timeout 0.001");
  EXPECT_EQ(r.status, 3) << r.output;  // the run ended, as an error
  EXPECT_NE(r.output.find("start-up timed out waiting for a"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("()"), std::string::npos) << r.output;
}

}  // namespace
