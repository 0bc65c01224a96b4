// `grip plan`: one standalone solve on a built-in scene, printed and optionally drawn.

#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "params_options.hpp"
#include "standalone.hpp"

namespace grip::tools {

namespace {
struct PlanOptions {
  std::string scene = "meandros";
  ParamsOptions params{"dd-accel"};
  std::string planner = "grip";
  std::uint64_t seed = 1;
  std::uint64_t max_edges = 100'000;
  double time_limit_s = 0.0;
  bool all_leaves_safe = false;
  // Overrides of the parameters' planner section.
  std::optional<double> score_base_a;
  std::optional<double> min_plan_duration_s;
  std::optional<double> max_plan_duration_s;
  double rho_clearance_m = PlannerConfig{}.rho_clearance_m;
  std::string image;
};

int run_plan(const PlanOptions& o) {
  auto scene = make_scene(o.scene);
  auto params = effective_params(o.params);
  auto selection = selection_from_name(o.planner);
  for (const Error* e : {scene ? nullptr : &scene.error(), params ? nullptr : &params.error(),
                         selection ? nullptr : &selection.error()}) {
    if (e != nullptr) {
      std::cerr << "grip plan: " << e->message << "\n";
      return 2;
    }
  }
  if (o.max_edges == 0 || o.max_edges > 10'000'000) {
    std::cerr << "grip plan: --max-edges must be in [1, 10000000] (got " << o.max_edges << ")\n";
    return 2;
  }
  PlannerConfig config;
  config.selection = *selection;
  config.seed = o.seed;
  GripTuning& tuning = params->planner.tuning;
  tuning.score_base_a = o.score_base_a.value_or(tuning.score_base_a);
  tuning.min_plan_duration_s = o.min_plan_duration_s.value_or(tuning.min_plan_duration_s);
  tuning.max_plan_duration_s = o.max_plan_duration_s.value_or(tuning.max_plan_duration_s);
  tuning.apply_to(config);
  config.rho_clearance_m = o.rho_clearance_m;
  config.safety = o.all_leaves_safe ? SafetyCheck::kAllLeaves : SafetyCheck::kAtHorizon;
  config = config_for_edge_cap(config, o.max_edges);
  const std::string robot(vehicle_name(vehicle_kind(params->vehicle)));
  return with_vehicle(params->vehicle, [&](const auto& vehicle) {
    Status drawn = Ok{};
    auto outcome = run_standalone(
        vehicle, *scene, config, o.max_edges, o.time_limit_s, [&](const auto& planner) {
          if (o.image.empty()) return;
          drawn =
              draw_planner(*scene, planner, o.planner + " / " + robot + " / " + o.scene, o.image);
        });
    if (!outcome) {
      std::cerr << "grip plan: " << outcome.error().message << "\n";
      return 2;
    }
    const auto& r = *outcome;
    std::cout << o.planner << " on " << o.scene << " with " << robot << " (seed " << o.seed
              << "): " << (r.solved ? "reached the goal" : "did not reach the goal") << " after "
              << r.edges_added << " edges in " << r.solve_time_s << " s ("
              << stop_reason_name(r.reason) << ")\n"
              << "  iterations " << r.stats.iterations << ", propagation steps "
              << r.stats.propagations << ", collision checks " << r.stats.collision_checks
              << ", contingency checks " << r.stats.contingency_checks << ", tree edges "
              << r.tree_edges << "\n";
    if (!drawn) {
      std::cerr << "grip plan: " << drawn.error().message << "\n";
      return 1;
    }
    if (!o.image.empty()) std::cout << "  drawn to " << o.image << "\n";
    return 0;
  });
}
}  // namespace

void register_plan_command(CLI::App& app) {
  auto o = std::make_shared<PlanOptions>();
  CLI::App* cmd = app.add_subcommand("plan", "Solve one standalone problem on a built-in scene");
  cmd->add_option("--scene", o->scene, "meandros, labyrinth or rooms")->capture_default_str();
  add_vehicle_options(*cmd, o->params);
  cmd->add_option("--planner", o->planner, "grip, rrt, rrt-bias or random")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  cmd->add_option("--max-edges", o->max_edges, "Stop after this many edges")->capture_default_str();
  cmd->add_option("--time-limit", o->time_limit_s, "Stop after this many seconds (0: none)")
      ->check(CLI::Range(0.0, 86400.0));
  cmd->add_option("--score-base-a", o->score_base_a,
                  "GRIP's a > 1 in s(e) = a^p(e) rho(e, F) (planner.score_base_a)");
  cmd->add_option("--min-plan-duration", o->min_plan_duration_s,
                  "Shortest random plan [s] (planner.min_plan_duration_s)");
  cmd->add_option("--max-plan-duration", o->max_plan_duration_s,
                  "Longest random plan [s] (planner.max_plan_duration_s)");
  cmd->add_option("--rho-clearance", o->rho_clearance_m,
                  "rho_A* is computed for a disk of this radius [m]")
      ->capture_default_str();
  cmd->add_flag("--all-leaves-safe", o->all_leaves_safe,
                "Check every new leaf's contingency instead of only states at time T");
  cmd->add_option("--image", o->image, "Write a PNG of the tree and the path");
  cmd->callback([o]() {
    if (const int rc = run_plan(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
