#pragma once
// The subcommands of `grip`. Each registers its options on the CLI11 app and runs when chosen.

#include <CLI/CLI.hpp>
#include <cstdint>

namespace grip::tools {

// Exploration defaults shared by `grip explore`, `grip sim` and `grip bench explore` (the
// planner's own are the parameter file's).
inline constexpr double kDefaultTimeScale =
    2.0;  // at 4 the planner runs short of budget on 2 cores
inline constexpr double kDefaultMaxSimTimeS = 1800.0;  // the car needs up to about 1,000 s

void register_scene_command(CLI::App& app);
void register_plan_command(CLI::App& app);
void register_bench_command(CLI::App& app);
void register_stress_command(CLI::App& app);
void register_planner_command(CLI::App& app);
void register_explore_commands(CLI::App& app);       // `grip explore` and `grip sim`
void register_render_command(CLI::App& app);         // figures from their reports
void register_echo_command(CLI::App& app);           // a topic's samples as JSON lines
void register_goal_command(CLI::App& app);           // a goal for the planner
void register_params_command(CLI::App& app);         // a vehicle's parameter file, completed
void register_keys_command(CLI::App& app);           // DDS Security keys (`grip keys init`)
void register_fault_delayer_command(CLI::App& app);  // hidden: the delay of `grip bench faults`
// Benchmarks registered on `bench` besides `paper`: `dds`, `explore`, `faults`, `ompl`
// (tools/ompl; a stub there when built without OMPL) and `scale`.
void register_bench_dds_command(CLI::App& bench);
void register_bench_explore_command(CLI::App& bench);
void register_bench_faults_command(CLI::App& bench);
void register_bench_ompl_command(CLI::App& bench);
void register_bench_scale_command(CLI::App& bench);

}  // namespace grip::tools
