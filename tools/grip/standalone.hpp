#pragma once
// Standalone planning runs (no replanning) shared by `grip plan` and `grip bench paper`.

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "grip/planner/planner.hpp"
#include "grip/scenes/scenes.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "render.hpp"

namespace grip::tools {

struct StandaloneOutcome {
  bool solved = false;
  std::uint64_t edges_added = 0;
  double solve_time_s = 0.0;
  PlannerStats stats;
  StopReason reason = StopReason::kTerminationCondition;
  std::uint32_t tree_edges = 0;
};

// Budget for a run that may add `edge_cap` edges: one trajectory per edge, two edge records.
inline PlannerConfig config_for_edge_cap(PlannerConfig config, std::uint64_t edge_cap) {
  config.max_trajectories = static_cast<std::uint32_t>(edge_cap + 2);
  config.max_edges = static_cast<std::uint32_t>(2 * edge_cap + 4);
  return config;
}

inline Goal scene_goal(const Scene& scene) {
  return Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m);
}

// Builds a planner for the scene, sets the problem (not timed) and solves until the goal, the
// edge cap or the time budget (0 = none). The planner is handed to `after` for drawing.
template <VehicleModel V, typename After>
Result<StandaloneOutcome> run_standalone(const V& vehicle, const Scene& scene,
                                         const PlannerConfig& config, std::uint64_t edge_cap,
                                         double time_budget_s, After&& after) {
  auto planner = Planner<V>::create(vehicle, scene.grid, config);
  if (!planner) return planner.error();
  const auto start = vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad);
  if (auto s = planner->set_problem(start, scene_goal(scene)); !s) return s.error();

  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto deadline = t0 + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(time_budget_s));
  const PlannerStats& stats = planner->stats();
  std::uint32_t calls = 0;
  const auto should_stop = [&]() {
    if (stats.edges_added >= edge_cap) return true;
    // Reading the clock every 16 iterations keeps its cost out of the measurement.
    return time_budget_s > 0.0 && (++calls & 15U) == 0 && Clock::now() >= deadline;
  };
  const SolveResult result = planner->solve(should_stop);
  const auto t1 = Clock::now();

  StandaloneOutcome out;
  out.solved = result.status == SolveStatus::kExactSolution;
  out.edges_added = stats.edges_added;
  out.solve_time_s = std::chrono::duration<double>(t1 - t0).count();
  out.stats = stats;
  out.reason = result.reason;
  out.tree_edges = planner->tree().edge_count();
  after(*planner);
  return out;
}

// Draws the grid, the tree (thin) and the path to the best state (thick) of a planner.
template <VehicleModel V>
Status draw_planner(const Scene& scene, const Planner<V>& planner, const std::string& title,
                    const std::string& path) {
  auto canvas = MapCanvas::create(scene.grid, 3);
  if (!canvas) return canvas.error();
  canvas->draw_grid(scene.grid);
  canvas->draw_disk({scene.goal_x_m, scene.goal_y_m}, scene.goal_radius_m, 0.1, 0.7, 0.2, 0.35);
  const auto& tree = planner.tree();
  std::vector<Point> line;
  planner.visit_edges([&](EdgeHandle, const Edge& edge) {
    line.clear();
    for (int k = edge.first; k <= edge.last; ++k) {
      const auto& q = tree.state(edge.trajectory, static_cast<std::uint32_t>(k));
      line.push_back({state_x(q), state_y(q)});
    }
    canvas->draw_polyline(line, 0.2, 0.35, 0.85, 1.0, 0.55);
  });
  line.clear();
  planner.visit_path(planner.best_state(), [&](const auto& q) {
    line.push_back({state_x(q), state_y(q)});
  });
  canvas->draw_polyline(line, 0.9, 0.2, 0.1, 3.0);
  canvas->draw_marker({scene.start_x_m, scene.start_y_m}, 6.0, 0.95, 0.6, 0.0);
  canvas->draw_label(title, 10.0, 24.0, 16.0);
  return canvas->write_png(path);
}

}  // namespace grip::tools
