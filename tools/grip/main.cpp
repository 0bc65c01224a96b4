// grip: the command of the GRIP real-time planning runtime.

#include <string>

#include <CLI/CLI.hpp>

#include "build_info.hpp"
#include "commands.hpp"
#include "grip/platform/memory.hpp"

int main(int argc, char** argv) {
  // First, before anything allocates: it may start the process again.
  grip::platform::prefer_huge_pages(argv);
  CLI::App app{"grip: GRIP (Greedy, Incremental, Path-directed) kinodynamic replanning runtime"};
  app.set_version_flag("--version", "grip " + std::string(grip::tools::grip_version()) +
                                        " (revision " + std::string(grip::tools::grip_revision()) +
                                        ")");
  app.require_subcommand(1);
  grip::tools::register_scene_command(app);
  grip::tools::register_plan_command(app);
  grip::tools::register_bench_command(app);
  grip::tools::register_stress_command(app);
  grip::tools::register_planner_command(app);
  grip::tools::register_explore_commands(app);
  grip::tools::register_render_command(app);
  grip::tools::register_echo_command(app);
  grip::tools::register_goal_command(app);
  grip::tools::register_params_command(app);
  grip::tools::register_keys_command(app);
  grip::tools::register_fault_delayer_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return 0;
}
