// `grip explore` and `grip sim`: exploration of an unknown workspace (the paper's Sec. IV) with the
// simulator standing in for the vehicle.
//   grip explore  the simulator and the planner as two DDS participants in one process;
//   grip sim      the simulator alone, for a `grip planner` started elsewhere (host-in-the-loop).
// Both take the world (a built-in scene or a map file), the robot, the time scale, the limits,
// and write the same report and picture.

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

#include "commands.hpp"
#include "cycle_trace.hpp"
#include "dds_config.hpp"
#include "grip/planner/step_margin.hpp"
#include "grip/platform/overrun_watcher.hpp"
#include "grip/rt/dds/planner_participant.hpp"
#include "grip/scenes/scenes.hpp"
#include "grip/sim/map_file.hpp"
#include "grip/sim/sim_participant.hpp"
#include "grip/sim/start_pose.hpp"
#include "grip/tools/atomic_file.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "params_options.hpp"
#include "private_link.hpp"
#include "render.hpp"
#include "report_file.hpp"
#include "speed_profile.hpp"
#include "stop_signal.hpp"

namespace grip::tools {

namespace {

struct ExploreOptions {
  std::string scene = "rooms";
  std::string map;
  std::string start;
  int movingai_subdivision = sim::MapLoadOptions{}.movingai_subdivision;
  ParamsOptions params{"dd-vel"};
  std::uint64_t seed = 1;
  double time_scale = kDefaultTimeScale;
  double max_sim_time_s = kDefaultMaxSimTimeS;
  bool lockstep = false;
  double drop_plans = 0.0;
  std::string report;
  std::string image;
  std::string cycle_trace;          // grip explore: the planner's cycles, as CSV
  double startup_timeout_s = 30.0;  // grip explore --startup-timeout (params_options.hpp)
  bool private_link = false;        // grip explore --private
  std::string dds_config;           // grip sim: a Cyclone configuration of its own (else loopback)
};

struct World {
  std::string name;
  OccupancyGrid truth;
  sim::StartPose start;
};

Result<World> load_world(const ExploreOptions& o, const params::GripParams& p) {
  if (o.map.empty()) {
    auto scene = make_scene(o.scene);
    if (!scene) return scene.error();
    World world{scene->name,
                std::move(scene->grid),
                {scene->start_x_m, scene->start_y_m, scene->start_theta_rad}};
    if (!o.start.empty()) return invalid_argument("--start needs --map (scenes have their start)");
    return world;
  }
  sim::MapLoadOptions load;
  load.movingai_subdivision = o.movingai_subdivision;
  auto loaded = sim::load_map(o.map, load);
  if (!loaded) return loaded.error();
  // The chassis, and the collision margin the planner checks the start with (for its cycle's
  // integration step).
  const auto [footprint, planner_margin_m] = with_vehicle(p.vehicle, [&p](const auto& v) {
    return std::pair<Footprint, double>{
        v.footprint(), step_collision_margin_m(v, integration_step_for_cycle(p.planner.cycle_s))};
  });
  sim::StartPose start;
  if (o.start.empty()) {
    auto chosen = sim::choose_start(*loaded, footprint, planner_margin_m);
    if (!chosen) return chosen.error();
    start = *chosen;
  } else {
    auto given = sim::parse_start(o.start);
    if (!given) return given.error();
    if (Status s = sim::check_start(*loaded, footprint, planner_margin_m, *given); !s) {
      return s.error();
    }
    start = *given;
  }
  return World{o.map, std::move(loaded->grid), start};
}

nlohmann::json report_json(const ExploreOptions& o, const params::GripParams& p, const World& world,
                           const sim::SimRunReport& r) {
  nlohmann::json j;
  j["result"] = r.result;
  if (!r.reason.empty()) j["reason"] = r.reason;
  j["coverage"] = r.coverage;
  j["collisions"] = r.collisions;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& c : r.collision_events) {
    events.push_back(
        {{"time_s", c.time_s}, {"x_m", c.x_m}, {"y_m", c.y_m}, {"theta_rad", c.theta_rad}});
  }
  j["collision_events"] = events;
  j["cycles"] = r.cycles;
  j["deadline_misses"] = r.deadline_misses;
  j["sim_time_s"] = r.sim_time_s;
  j["wall_time_s"] = r.wall_time_s;
  j["distance_m"] = r.distance_m;
  j["retraced_fraction"] = r.retraced_fraction;
  j["mean_speed_fraction"] = r.mean_speed_fraction;
  j["braking_bound_fraction"] = r.braking_bound_fraction;
  j["turning_bound_fraction"] = r.turning_bound_fraction;
  j["without_plan_fraction"] = r.without_plan_fraction;
  j["reversing_fraction"] = r.reversing_fraction;
  j["plans_received"] = r.plans_received;
  j["plans_rejected"] = r.plans_rejected;
  j["contingency_stops"] = r.contingency_stops;
  j["empty_plans"] = r.empty_plans;
  j["start_mismatches"] = r.start_mismatches;
  j["plans_dropped"] = r.plans_dropped;
  j["max_start_error_m"] = r.max_start_error_m;
  j["planner_losses"] = r.planner_losses;
  j["world"] = world.name;
  j["robot"] = vehicle_name(vehicle_kind(p.vehicle));
  j["seed"] = o.seed;
  j["lockstep"] = o.lockstep;
  if (o.lockstep) {
    j["lockstep_edges"] = p.planner.lockstep_edges;
  } else {
    j["time_scale"] = o.time_scale;
  }
  j["safety"] = p.planner.safety;
  // The effective parameters, as a file `--params` reads back.
  j["parameters"] = params::to_yaml(p);
  j["start"] = {world.start.x_m, world.start.y_m, world.start.theta_rad};
  j["max_speed_m_s"] = r.max_speed_m_s;
  if (!r.trajectory.empty()) j["end"] = {r.trajectory.back()[0], r.trajectory.back()[1]};
  if (r.last_status) {
    // Where the planner was heading when the run ended (a stuck run: the frontier it could not
    // reach).
    const grip_msg_PlannerStatus& s = *r.last_status;
    j["planner"] = {{"exploring", s.exploring},
                    {"exploration_complete", s.exploration_complete},
                    {"frontier_groups", s.frontier_groups},
                    {"frontier_groups_given_up", s.frontier_groups_given_up},
                    {"frontier_groups_unreachable", s.frontier_groups_unreachable},
                    {"target", {s.target_x_m, s.target_y_m}},
                    {"tree_edges", s.tree_edges}};
  }
  // The velocity profile of the paper's Fig. 9, one sample per simulation tick, the speed
  // braking within the sensed region allowed at each, and within the route's turns (none for a
  // vehicle that stops at once), and how much of the time the vehicle went near its maximum speed
  // (`grip render
  // --speed-profile` draws it).
  nlohmann::json profile = nlohmann::json::array();
  for (const auto& sample : r.speed_profile) profile.push_back({sample[0], sample[1]});
  j["speed_profile"] = profile;
  j["braking_bound_profile"] = r.braking_bound_profile;
  j["turning_bound_profile"] = r.turning_bound_profile;
  // Coverage as it grew, and when it first reached half, 0.9 and complete's share: how much of a
  // run the last pockets took.
  nlohmann::json coverage = nlohmann::json::array();
  for (const auto& sample : r.coverage_profile) coverage.push_back({sample[0], sample[1]});
  j["coverage_profile"] = coverage;
  nlohmann::json reached = nlohmann::json::object();
  for (const auto& [key, share] :
       {std::pair{"0.5", 0.5}, std::pair{"0.9", 0.9}, std::pair{"0.97", sim::kCompleteCoverage}}) {
    const auto first = std::find_if(r.coverage_profile.begin(), r.coverage_profile.end(),
                                    [share](const auto& sample) { return sample[1] >= share; });
    reached[key] =
        first == r.coverage_profile.end() ? nlohmann::json() : nlohmann::json((*first)[0]);
  }
  j["time_to_coverage_s"] = reached;
  if (r.max_speed_m_s > 0.0) {
    const SpeedProfileSummary speed = summarize_speed_profile(r.speed_profile, r.max_speed_m_s);
    j["time_fraction_above_50pct_max_speed"] = speed.fraction_above_50;
    j["time_fraction_above_80pct_max_speed"] = speed.fraction_above_80;
  }
  return j;
}

// Fig. 1 / Fig. 8 of the paper: sensed free, obstacles, unknown, the trajectory, collisions,
// and, when the planner ran in this process, its last tree and the plan it had selected.
Status draw_run(const World& world, const sim::SimRunReport& r,
                const rt::dds::PlannerTreePicture& tree, const std::string& path) {
  auto canvas = MapCanvas::create(world.truth, 2);
  if (!canvas) return canvas.error();
  canvas->draw_grid(*r.known);
  const auto draw = [&](const std::vector<std::array<double, 2>>& points, double red, double green,
                        double blue, double width_px, double alpha) {
    std::vector<Point> line;
    line.reserve(points.size());
    for (const auto& p : points) line.push_back({p[0], p[1]});
    canvas->draw_polyline(line, red, green, blue, width_px, alpha);
  };
  for (const auto& edge : tree.edges) draw(edge, 0.2, 0.35, 0.85, 1.0, 0.45);
  draw(r.trajectory, 0.85, 0.15, 0.1, 2.0, 1.0);
  draw(tree.plan, 0.1, 0.65, 0.2, 3.0, 1.0);
  for (const auto& c : r.collision_events) canvas->draw_marker({c.x_m, c.y_m}, 6.0, 1.0, 0.0, 1.0);
  canvas->draw_marker({world.start.x_m, world.start.y_m}, 5.0, 0.95, 0.6, 0.0);
  if (!r.trajectory.empty()) {  // where it ended
    canvas->draw_marker({r.trajectory.back()[0], r.trajectory.back()[1]}, 5.0, 0.1, 0.3, 0.9);
  }
  if (r.last_status && r.last_status->exploring && !r.last_status->exploration_complete) {
    canvas->draw_marker({r.last_status->target_x_m, r.last_status->target_y_m}, 4.0, 0.1, 0.7,
                        0.2);  // the frontier it was heading for
  }
  std::ostringstream title;
  title << world.name << ", " << r.result << ", coverage " << std::fixed << std::setprecision(3)
        << r.coverage << ", collisions " << r.collisions << ", " << std::setprecision(0)
        << r.sim_time_s << " s";
  canvas->draw_label(title.str(), 8.0, 20.0, 14.0);
  return canvas->write_png(path);
}

// `planner`: the in-process planner's report, if it ran and ended well.
int finish(const ExploreOptions& o, const params::GripParams& p, const World& world,
           const Result<sim::SimRunReport>& run, const rt::dds::PlannerTreePicture& tree,
           const rt::dds::PlannerParticipantReport* planner, const nlohmann::json& link,
           const char* command) {
  if (!run) {
    std::cerr << command << ": " << run.error().message << "\n";
    return 1;
  }
  const sim::SimRunReport& r = *run;
  std::cout << command << ": " << r.result << (r.reason.empty() ? "" : " (" + r.reason + ")")
            << " after " << std::fixed << std::setprecision(1) << r.sim_time_s << " s simulated ("
            << r.wall_time_s << " s wall)\n  coverage " << std::setprecision(3) << r.coverage
            << ", collisions " << r.collisions << ", distance " << std::setprecision(1)
            << r.distance_m << " m (" << std::setprecision(2) << r.retraced_fraction
            << " of it retraced), mean speed " << std::setprecision(2) << r.mean_speed_fraction
            << " of top (braking within the sensed region allows " << r.braking_bound_fraction
            << ", and within its turns " << r.turning_bound_fraction << "; without a plan "
            << r.without_plan_fraction << " of the time, backing up " << r.reversing_fraction
            << ")\n  planner cycles " << r.cycles << ", deadline misses " << r.deadline_misses
            << ", plans " << r.plans_received << " (rejected " << r.plans_rejected << ", "
            << r.empty_plans << " empty, " << r.start_mismatches
            << " refused: not starting where the vehicle was"
            << (r.plans_dropped > 0 ? ", " + std::to_string(r.plans_dropped) + " dropped on purpose"
                                    : "")
            << "), contingency stops " << r.contingency_stops << "\n";
  if (!o.report.empty()) {
    nlohmann::json j = report_json(o, p, world, r);
    if (planner != nullptr && !o.lockstep) {  // what the machine granted the real-time run
      j["scheduling"] = {{"policy", planner->policy},
                         {"policy_fallback_reason", planner->policy_fallback},
                         {"publish_thread_policy", planner->publish_policy}};
    }
    if (planner != nullptr) {
      j["planner_startup"] = {{"map_sync_s", planner->map_sync_s},
                              {"planning_s", planner->startup_s}};
    }
    // The whole process's (simulator, planner, DDS): what a map of this size costs in memory.
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) == 0)
      j["peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
    if (!link.is_null()) j["link"] = link;
    if (!write_report(command, o.report, std::move(j), 1)) return 1;
  }
  if (!o.image.empty()) {
    if (Status s = draw_run(world, r, tree, o.image); !s) {
      std::cerr << command << ": " << s.error().message << "\n";
      return 1;
    }
  }
  return r.result == "complete" ? 0 : 3;
}

sim::SimRunConfig sim_config(const ExploreOptions& o, const params::GripParams& p,
                             const World& world, bool with_planner) {
  sim::SimRunConfig c = sim_run_config(p);
  c.world = world.name;
  c.start_x_m = world.start.x_m;
  c.start_y_m = world.start.y_m;
  c.start_theta_rad = world.start.theta_rad;
  c.time_scale = o.time_scale;
  c.lockstep = o.lockstep;
  c.max_sim_time_s = o.max_sim_time_s;
  c.drop_plans = o.drop_plans;
  c.drop_seed = o.seed;
  // grip sim waits for a planner elsewhere as long as told; grip explore's own planner ends the
  // run when it does not start in time, and the vehicle waits the one plan's wait beyond that.
  const auto timeout = startup_timeout(o.startup_timeout_s).value();  // validate() checked it
  c.first_plan_wait = !with_planner || timeout.count() == 0 ? timeout : timeout + c.planner_wait;
  return c;
}

std::function<void(const sim::SimProgress&)> progress_line() {
  if (isatty(STDERR_FILENO) != 1) return {};
  return [](const sim::SimProgress& p) {
    std::cerr << "\r[" << std::fixed << std::setprecision(1) << p.sim_time_s << " s] coverage "
              << std::setprecision(3) << p.coverage << ", speed " << std::setprecision(2)
              << p.speed_m_s << " m/s, cycle " << p.planner_cycle << ", misses " << p.planner_misses
              << ", collisions " << p.collisions << "    " << std::flush;
  };
}

Status validate(const ExploreOptions& o) {
  if (!(o.time_scale > 0.0 && o.time_scale <= 50.0)) {
    return invalid_argument("--time-scale must be in (0, 50] (got " + std::to_string(o.time_scale) +
                            ")");
  }
  if (!(o.max_sim_time_s > 0.0)) return invalid_argument("--max-sim-time must be > 0");
  if (auto timeout = startup_timeout(o.startup_timeout_s); !timeout) return timeout.error();
  // An output that cannot be written is refused now, not after the run.
  const std::pair<const std::string*, const char*> outputs[] = {
      {&o.report, "--report"}, {&o.image, "--image"}, {&o.cycle_trace, "--cycle-trace"}};
  for (const auto& [path, option] : outputs) {
    if (path->empty()) continue;
    if (Status s = check_writable(*path, option); !s) return s;
  }
  return Ok{};
}

int run_explore(const ExploreOptions& o, bool with_planner) {
  const char* command = with_planner ? "grip explore" : "grip sim";
  auto p = effective_params(o.params);
  if (!p) {
    std::cerr << command << ": " << p.error().message << "\n";
    return 2;
  }
  if (Status s = validate(o); !s) {
    std::cerr << command << ": " << s.error().message << "\n";
    return 2;
  }
  auto world = load_world(o, *p);
  if (!world) {
    std::cerr << command << ": " << world.error().message << "\n";
    return 2;
  }
  // Before any thread (Cyclone's included): SIGXCPU must be blocked everywhere.
  std::optional<platform::OverrunWatcher> overruns;
  if (with_planner) {
    auto watcher = platform::OverrunWatcher::start();
    if (!watcher) {
      std::cerr << command << ": " << watcher.error().message << "\n";
      return 2;
    }
    overruns.emplace(std::move(watcher).value());
  }
  // One process is one identity (platform/dds/security.hpp): grip explore takes the role
  // allowed both sides.
  auto security = security_files(p->link.security_dir, with_planner ? "explore" : "vehicle");
  if (!security) {
    std::cerr << command << ": " << security.error().message << "\n";
    return 2;
  }
  if (*security) {
    log_refused_peers([command](const std::string& line) {
      std::cerr << command + std::string(": ") + line + "\n" << std::flush;
    });
  }
  if (!with_planner && !*security) {
    std::cerr << command << ": warning: " << unauthenticated_link_warning() << "\n";
  }
  stop_on_signals();

  std::unique_ptr<rt::dds::PlannerParticipant> planner;
  std::thread planner_thread;
  std::optional<Result<rt::dds::PlannerParticipantReport>> planner_result;
  std::optional<CycleTrace> trace;
  if (!o.cycle_trace.empty()) {
    auto opened = CycleTrace::open(o.cycle_trace);
    if (!opened) {
      std::cerr << command << ": " << opened.error().message << "\n";
      return 2;
    }
    trace.emplace(std::move(opened).value());
  }
  // grip explore is private unless told where its topics are (private_link.hpp); grip sim
  // talks to a planner elsewhere, on the loopback configuration.
  const ExploreLink link =
      with_planner ? choose_explore_link(o.params, *p, o.private_link) : ExploreLink{false, {}, {}};
  std::optional<LinkWatch> watch;
  if (with_planner) {
    rt::dds::PlannerParticipantConfig pc = planner_participant_config(*p);
    // One process: the planner is sized for the map its simulator sends, however large.
    pc.max_map_cells = std::max(
        pc.max_map_cells, static_cast<std::uint32_t>(world->truth.width() * world->truth.height()));
    pc.dds_config = link.dds_config;
    if (trace) pc.on_cycle = [&trace](const rt::CycleRecord& r) { trace->write(r); };
    pc.seed = o.seed;
    pc.startup_timeout = startup_timeout(o.startup_timeout_s).value();  // validate() checked it
    pc.security = *security;
    auto created = rt::dds::PlannerParticipant::create(pc);
    if (!created) {
      std::cerr << command << ": " << created.error().message << "\n";
      return 2;
    }
    planner = std::move(created).value();
    auto watching =
        LinkWatch::start(p->link.domain, link.dds_config, p->link.topic_prefix, *security);
    if (!watching) {
      std::cerr << command << ": " << watching.error().message << "\n";
      return 2;
    }
    watch.emplace(std::move(watching).value());
  }
  // A planner that fails before the simulation has finished (at start-up, say) ends the run
  // as an error at once, with its reason, rather than leaving the vehicle waiting for plans.
  std::atomic<bool> sim_finished{false};
  std::atomic<bool> planner_failed{false};
  if (planner) {
    planner_thread = std::thread([&] {
      planner_result = planner->run();
      if (!planner_result->ok() && !sim_finished.load()) {
        planner_failed.store(true);
        stop_flag().store(true);  // the planner of grip explore failed on its own
      }
    });
  }
  sim::SimRunConfig config = sim_config(o, *p, *world, with_planner);
  config.dds_config = link.dds_config;
  config.security = *security;
  if (!o.dds_config.empty()) {
    auto dds_config = choose_dds_config(o.dds_config);
    if (!dds_config) {
      std::cerr << command << ": " << dds_config.error().message << "\n";
      return 2;
    }
    config.dds_config = *dds_config;
  }
  config.on_finished = [&] {
    sim_finished.store(true);
    if (planner) planner->request_stop();
  };
  auto run = sim::run_simulation(config, world->truth, stop_flag(), progress_line());
  if (isatty(STDERR_FILENO) == 1) std::cerr << "\n";
  if (planner) {
    sim_finished.store(true);
    planner->request_stop();
    planner_thread.join();
    if (planner_result && !planner_result->ok()) {
      const std::string why = "planner: " + planner_result->error().message;
      if (run && planner_failed.load()) {
        run->result = "error";
        run->reason = why;
      } else {
        std::cerr << command << ": " << why << "\n";
      }
    }
  }
  if (trace) {
    if (Status s = trace->close(); !s) std::cerr << command << ": " << s.error().message << "\n";
  }
  const rt::dds::PlannerTreePicture tree =
      planner ? planner->last_tree() : rt::dds::PlannerTreePicture{};
  const rt::dds::PlannerParticipantReport* planner_report =
      planner_result && planner_result->ok() ? &planner_result->value() : nullptr;
  nlohmann::json link_section;
  if (watch) {
    auto other = watch->other_writers();
    if (!other) {
      std::cerr << command << ": " << other.error().message << "\n";
      return 1;
    }
    nlohmann::json rejected = {{"plans", run ? run->plans_rejected : 0}};
    if (planner_report != nullptr) {
      rejected["vehicle_states"] = planner_report->rejected_vehicle_state;
      rejected["map_updates"] = planner_report->rejected_map_update;
      rejected["goals"] = planner_report->rejected_goal;
    }
    link_section = link_json(p->link, link, *other, rejected);
  }
  return finish(o, *p, *world, run, tree, planner_report, link_section, command);
}

void add_common_options(CLI::App* cmd, ExploreOptions& o) {
  cmd->add_option("--scene", o.scene, "meandros, labyrinth or rooms")->capture_default_str();
  cmd->add_option("--map", o.map,
                  "A MovingAI .map or ROS map_server .yaml file instead of a scene");
  cmd->add_option("--start", o.start, "X,Y[,THETA] with --map (default: chosen)");
  cmd->add_option("--movingai-subdivision", o.movingai_subdivision,
                  "Grid cells per side of a MovingAI map cell (1 m): the map's resolution")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  add_vehicle_options(*cmd, o.params);
  add_sensor_option(*cmd, o.params);
  cmd->add_option("--seed", o.seed, "Planner seed")->capture_default_str();
  cmd->add_option("--time-scale", o.time_scale, "Simulated seconds per wall-clock second")
      ->capture_default_str();
  cmd->add_option("--max-sim-time", o.max_sim_time_s, "Give up after this much simulated time [s]")
      ->capture_default_str();
  cmd->add_flag(
      "--lockstep", o.lockstep,
      "Deterministic: the simulator waits for each plan, the planner grows a fixed number "
      "of edges per cycle; as fast as the machine allows (--time-scale unused)");
  cmd->add_option("--drop-plans", o.drop_plans,
                  "Fault injection: the vehicle loses each plan with this probability (as if it "
                  "came too late; drawn from --seed)")
      ->check(CLI::Range(0.0, 0.5))
      ->capture_default_str();
  add_domain_option(*cmd, o.params);
  add_security_option(*cmd, o.params);
  cmd->add_option("--report", o.report, "Write the JSON report here");
  cmd->add_option("--image", o.image, "Draw the run into this PNG");
}

}  // namespace

void register_explore_commands(CLI::App& app) {
  auto explore = std::make_shared<ExploreOptions>();
  CLI::App* e = app.add_subcommand(
      "explore",
      "Explore an unknown workspace: simulator and planner as two DDS participants, private to "
      "the run unless --domain, --topic-prefix or the parameter file's link section place it");
  add_common_options(e, *explore);
  add_lockstep_options(*e, explore->params);
  e->add_option("--cycle-trace", explore->cycle_trace,
                "Write every planning cycle's timing and outcome here (CSV)");
  add_startup_timeout_option(*e, explore->startup_timeout_s);
  e->add_flag("--private", explore->private_link,
              "Keep the run's DDS traffic to itself even with --domain, --topic-prefix or a "
              "parameter file's link section (the default without them: a discovery tag of "
              "its own, so other runs are never discovered)");
  e->callback([explore]() {
    if (const int rc = run_explore(*explore, true); rc != 0) throw CLI::RuntimeError(rc);
  });

  auto sim_options = std::make_shared<ExploreOptions>();
  CLI::App* s = app.add_subcommand(
      "sim", "The simulator alone, standing in for the vehicle of a `grip planner` elsewhere");
  add_common_options(s, *sim_options);
  s->add_option("--dds-config", sim_options->dds_config,
                "Cyclone DDS XML configuration file (default: the built-in loopback-only one)");
  s->add_option("--startup-timeout", sim_options->startup_timeout_s,
                "Give up if no planner's first plan has come after this many seconds (0: wait); "
                "a planner syncing a large map or authenticating takes seconds")
      ->capture_default_str();
  s->callback([sim_options]() {
    if (const int rc = run_explore(*sim_options, false); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
