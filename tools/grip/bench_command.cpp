// `grip bench paper`: the paper's standalone experiments on this machine, seeded.
//   Fig. 5/6  edges added until the goal, per selection strategy, capped at 100,000 edges;
//   Table II  time to build a 250-edge GRIP tree, per vehicle, over scenes and seeds;
//   Fig. 7    tree size in one time budget, contingencies at time T only vs at every leaf.
// A benchmark, not a test: it measures and prints, it asserts nothing about time.

#include <atomic>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "report_file.hpp"
#include "standalone.hpp"
#include "stats.hpp"

namespace grip::tools {

namespace {

struct BenchOptions {
  std::uint64_t seeds = 10;
  std::uint64_t max_edges = 100'000;
  double fig7_budget_ms = 50.0;
  unsigned jobs = 0;
  std::vector<std::string> experiments{"fig5", "table2", "fig7"};
  std::string json;
  std::string image_dir;
};

nlohmann::json number_or_null(double v) {
  return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
}

// A count for the table, "-" where there is none (no run solved).
std::string count_or_dash(double v) {
  return std::isnan(v) ? "-" : std::to_string(std::llround(v));
}

struct EdgeRun {
  std::string scene;
  std::string robot;
  std::string planner;
  std::uint64_t seed;
  bool solved = false;
  std::uint64_t edges = 0;
  double seconds = 0.0;
  std::string error;
};

// Fig. 5/6: the runs are independent and count edges, not time, so they run in parallel.
nlohmann::json run_edges_to_goal(const BenchOptions& o) {
  const std::vector<std::pair<std::string, std::string>> experiments{{"meandros", "dd-accel"},
                                                                     {"labyrinth", "car"}};
  const std::vector<std::string> planners{"grip", "rrt-bias", "rrt", "random"};
  std::vector<EdgeRun> runs;
  for (const auto& [scene, robot] : experiments) {
    for (const auto& planner : planners) {
      for (std::uint64_t seed = 1; seed <= o.seeds; ++seed)
        runs.push_back(EdgeRun{scene, robot, planner, seed, false, 0, 0.0, {}});
    }
  }
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::mutex print;
  const auto worker = [&]() {
    for (std::size_t i = next++; i < runs.size(); i = next++) {
      EdgeRun& run = runs[i];
      auto scene = make_scene(run.scene);
      PlannerConfig config;
      config.selection = selection_from_name(run.planner).value();
      config.seed = run.seed;
      config = config_for_edge_cap(config, o.max_edges);
      const bool draw = !o.image_dir.empty() && run.seed == 1;
      with_default_vehicle(vehicle_kind_from_name(run.robot).value(), [&](const auto& vehicle) {
        auto r = run_standalone(vehicle, *scene, config, o.max_edges, 0.0, [&](const auto& p) {
          if (!draw) return;
          const std::string file =
              o.image_dir + "/fig5-" + run.scene + "-" + run.robot + "-" + run.planner + ".png";
          if (auto s = draw_planner(*scene, p, run.planner + " / " + run.robot + " / " + run.scene,
                                    file);
              !s) {
            run.error = s.error().message;
          }
        });
        if (!r) {
          run.error = r.error().message;
          return;
        }
        run.solved = r->solved;
        run.edges = r->edges_added;
        run.seconds = r->solve_time_s;
      });
      std::lock_guard lock(print);
      ++done;
      std::cerr << "\r  fig5: " << done << "/" << runs.size() << " runs" << std::flush;
    }
  };
  std::vector<std::thread> threads;
  const unsigned jobs = o.jobs != 0 ? o.jobs : std::max(1U, std::thread::hardware_concurrency());
  for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  std::cerr << "\n";

  nlohmann::json rows = nlohmann::json::array();
  std::cout << "\nFig. 5/6: edges added until the goal (cap " << o.max_edges << ", " << o.seeds
            << " seeds; median and mean over solved runs)\n";
  std::cout << std::left << std::setw(11) << "scene" << std::setw(10) << "robot" << std::setw(10)
            << "planner" << std::right << std::setw(8) << "solved" << std::setw(11) << "median"
            << std::setw(11) << "mean" << std::setw(12) << "time med s\n";
  for (const auto& [scene, robot] : experiments) {
    for (const auto& planner : planners) {
      std::vector<double> edges;
      std::vector<double> seconds;
      std::size_t count = 0;
      for (const auto& run : runs) {
        if (run.scene != scene || run.robot != robot || run.planner != planner) continue;
        if (!run.error.empty()) std::cerr << "  error: " << run.error << "\n";
        ++count;
        if (run.solved) {
          edges.push_back(static_cast<double>(run.edges));
          seconds.push_back(run.seconds);
        }
      }
      const Summary s = summarize(edges);
      const Summary t = summarize(seconds);
      std::cout << std::left << std::setw(11) << scene << std::setw(10) << robot << std::setw(10)
                << planner << std::right << std::setw(4) << edges.size() << "/" << std::setw(3)
                << count << std::setw(11) << count_or_dash(s.median) << std::setw(11)
                << count_or_dash(s.mean) << std::setw(11) << std::fixed << std::setprecision(3)
                << t.median << "\n";
      rows.push_back({{"scene", scene},
                      {"robot", robot},
                      {"planner", planner},
                      {"runs", count},
                      {"solved", edges.size()},
                      {"median", number_or_null(s.median)},
                      {"mean", number_or_null(s.mean)},
                      {"median_time_s", number_or_null(t.median)}});
    }
  }
  return rows;
}

// Table II: sequential, so that the runs do not compete for the cores they are timed on.
nlohmann::json run_time_250_edges(const BenchOptions& o) {
  nlohmann::json rows = nlohmann::json::array();
  std::cout << "\nTable II: time to build a 250-edge GRIP tree (" << all_scenes().size()
            << " scenes x " << o.seeds << " seeds)\n";
  std::cout << std::left << std::setw(10) << "robot" << std::right << std::setw(6) << "runs"
            << std::setw(13) << "median ms" << std::setw(11) << "mean ms" << std::setw(11)
            << "max ms\n";
  for (VehicleKind kind :
       {VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration, VehicleKind::kCar}) {
    std::vector<double> times;
    for (SceneId id : all_scenes()) {
      auto scene = make_scene(id);
      for (std::uint64_t seed = 1; seed <= o.seeds; ++seed) {
        PlannerConfig config;
        config.seed = seed;
        config.stop_at_goal = false;  // always a full 250-edge tree
        config = config_for_edge_cap(config, 250);
        with_default_vehicle(kind, [&](const auto& vehicle) {
          auto r = run_standalone(vehicle, *scene, config, 250, 0.0, [](const auto&) {});
          if (r && r->edges_added == 250) times.push_back(r->solve_time_s);
        });
      }
    }
    const Summary s = summarize(times);
    std::cout << std::left << std::setw(10) << vehicle_name(kind) << std::right << std::setw(6)
              << times.size() << std::setw(13) << std::fixed << std::setprecision(3)
              << s.median * 1e3 << std::setw(11) << s.mean * 1e3 << std::setw(11) << s.max * 1e3
              << "\n";
    rows.push_back({{"robot", vehicle_name(kind)},
                    {"runs", times.size()},
                    {"median_s", number_or_null(s.median)},
                    {"mean_s", number_or_null(s.mean)},
                    {"max_s", number_or_null(s.max)}});
  }
  return rows;
}

// Fig. 7: the same time budget with contingencies at T only versus at every new leaf.
nlohmann::json run_safety_overhead(const BenchOptions& o) {
  nlohmann::json rows = nlohmann::json::array();
  const double budget_s = o.fig7_budget_ms / 1e3;
  std::cout << "\nFig. 7: tree edges built in " << o.fig7_budget_ms
            << " ms, safety at time T only vs all leaves safe (mean over " << all_scenes().size()
            << " scenes x " << o.seeds << " seeds)\n";
  std::cout << std::left << std::setw(10) << "robot" << std::right << std::setw(10) << "T only"
            << std::setw(12) << "all leaves" << std::setw(8) << "ratio\n";
  for (VehicleKind kind :
       {VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration, VehicleKind::kCar}) {
    double sums[2] = {0.0, 0.0};
    std::size_t n = 0;
    for (SceneId id : all_scenes()) {
      auto scene = make_scene(id);
      for (std::uint64_t seed = 1; seed <= o.seeds; ++seed) {
        for (int variant = 0; variant < 2; ++variant) {
          PlannerConfig config;
          config.seed = seed;
          config.safety = variant == 0 ? SafetyCheck::kAtHorizon : SafetyCheck::kAllLeaves;
          config.stop_at_goal = false;  // the same budget for both: tree size is the measure
          config = config_for_edge_cap(config, o.max_edges);
          with_default_vehicle(kind, [&](const auto& vehicle) {
            auto r =
                run_standalone(vehicle, *scene, config, o.max_edges, budget_s, [](const auto&) {});
            if (r) sums[variant] += static_cast<double>(r->edges_added);
          });
        }
        ++n;
      }
    }
    const double t_only = sums[0] / static_cast<double>(n);
    const double all_leaves = sums[1] / static_cast<double>(n);
    std::cout << std::left << std::setw(10) << vehicle_name(kind) << std::right << std::setw(10)
              << std::fixed << std::setprecision(0) << t_only << std::setw(12) << all_leaves
              << std::setw(7) << std::setprecision(2) << t_only / std::max(all_leaves, 1.0) << "\n";
    rows.push_back({{"robot", vehicle_name(kind)},
                    {"t_only_edges", t_only},
                    {"all_leaves_edges", all_leaves},
                    {"budget_s", budget_s},
                    {"runs", n}});
  }
  return rows;
}

int run_bench_paper(const BenchOptions& o) {
  nlohmann::json report;
  report["seeds"] = o.seeds;
  report["edge_cap"] = o.max_edges;
  const auto wants = [&](const char* name) {
    return std::find(o.experiments.begin(), o.experiments.end(), name) != o.experiments.end();
  };
  if (wants("fig5")) report["edges_to_goal"] = run_edges_to_goal(o);
  if (wants("table2")) report["time_250_edges"] = run_time_250_edges(o);
  if (wants("fig7")) report["safety_overhead"] = run_safety_overhead(o);
  if (!o.json.empty()) {
    if (!write_report("grip bench paper", o.json, std::move(report))) return 1;
    std::cout << "\nwrote " << o.json << "\n";
  }
  return 0;
}

}  // namespace

void register_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  auto o = std::make_shared<BenchOptions>();
  CLI::App* paper = bench->add_subcommand("paper", "Reproduce the paper's standalone results");
  paper->add_option("--seeds", o->seeds, "Seeds per configuration")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  paper->add_option("--json", o->json, "Write the results as JSON");
  paper->add_option("--max-edges", o->max_edges, "Edge cap for Fig. 5/6 and Fig. 7")
      ->check(CLI::Range(250, 10'000'000))
      ->capture_default_str();
  paper->add_option("--fig7-budget-ms", o->fig7_budget_ms, "Time budget of the Fig. 7 runs")
      ->check(CLI::Range(1.0, 60'000.0))
      ->capture_default_str();
  paper->add_option("--jobs", o->jobs, "Parallel runs for Fig. 5/6 (default: all cores)");
  paper->add_option("--experiments", o->experiments, "Any of fig5, table2, fig7")
      ->check(CLI::IsMember({"fig5", "table2", "fig7"}))
      ->capture_default_str();
  paper->add_option("--image-dir", o->image_dir, "Draw the seed-1 trees of Fig. 5 into this folder")
      ->check(CLI::ExistingDirectory);
  paper->callback([o]() {
    if (const int rc = run_bench_paper(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
  register_bench_dds_command(*bench);
  register_bench_explore_command(*bench);
  register_bench_faults_command(*bench);
  register_bench_ompl_command(*bench);
  register_bench_scale_command(*bench);
}

}  // namespace grip::tools
