// `grip stress`: the deadline-miss stress test users run on a vehicle computer before trusting
// it. The real planner runs on the real planning thread in replanning mode: the vehicle follows
// the committed plans (the start state moves), obstacles appear and disappear (the map
// changes, through a lock-free hand-off as map updates will arrive) and the target changes. It
// measures and reports; it does not judge, except with --max-miss-rate for a vehicle image's CI.

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "commands.hpp"
#include "grip/common/random.hpp"
#include "grip/platform/alloc_counter.hpp"
#include "grip/platform/clock.hpp"
#include "grip/platform/machine.hpp"
#include "grip/platform/overrun_watcher.hpp"
#include "grip/rt/cycle_sizing.hpp"
#include "grip/rt/map_changes.hpp"
#include "grip/rt/periodic_loop.hpp"
#include "grip/rt/replanning_cycle.hpp"
#include "grip/rt/triple_buffer.hpp"
#include "grip/tools/atomic_file.hpp"
#include "grip/tools/load_generator.hpp"
#include "latency_json.hpp"
#include "params_options.hpp"
#include "report_file.hpp"
#include "standalone.hpp"

namespace grip::tools {

namespace {

struct StressOptions {
  double duration_s = 10.0;
  ParamsOptions params{"car"};  // the vehicle, the cycle and the policy
  std::string load = "none";
  std::string scene = "rooms";
  std::uint64_t seed = 1;
  std::string report;
  double max_miss_rate = -1.0;
  bool static_world = false;  // no map or target changes: shows what retainment keeps
};

// A change of the map: a rectangle of cells set to one value (as a map update patch).
struct MapPatch {
  int x0, y0, x1, y1;  // inclusive cell bounds
  Cell value;
};

struct VehiclePose {
  double x_m = 0.0;
  double y_m = 0.0;
};

Status validate(const StressOptions& o) {
  const auto bad = [](const std::string& m) { return Status(invalid_argument(m)); };
  if (!std::isfinite(o.duration_s) || o.duration_s <= 0.0 || o.duration_s > 7 * 24 * 3600.0) {
    return bad("--duration must be in (0, 604800] s (got " + std::to_string(o.duration_s) + ")");
  }
  if (o.max_miss_rate != -1.0 && (!(o.max_miss_rate >= 0.0) || o.max_miss_rate > 1.0)) {
    return bad("--max-miss-rate must be in [0, 1] (got " + std::to_string(o.max_miss_rate) + ")");
  }
  if (!o.report.empty()) return check_writable(o.report, "--report");
  return Ok{};
}

double per(std::uint64_t total, std::uint64_t count) {
  return count > 0 ? static_cast<double>(total) / static_cast<double>(count) : 0.0;
}

// The environment the planner faces: obstacles appear away from the vehicle and vanish again,
// and the target moves. Runs on an ordinary thread; hands changes over lock-free.
class Environment {
 public:
  // Keeps its own copy of the map: the planning thread owns and changes the planner's.
  Environment(OccupancyGrid ground, std::uint64_t seed) : ground_(std::move(ground)), rng_(seed) {}

  MapPatch next_patch(const VehiclePose& vehicle) {
    if (placed_.size() >= 8) {
      MapPatch old = placed_.front();
      placed_.pop_front();
      old.value = Cell::kFree;
      return old;
    }
    for (int attempt = 0; attempt < 50; ++attempt) {
      const int cx = static_cast<int>(rng_.below(static_cast<std::uint32_t>(ground_.width())));
      const int cy = static_cast<int>(rng_.below(static_cast<std::uint32_t>(ground_.height())));
      const double dx = ground_.cell_center_x(cx) - vehicle.x_m;
      const double dy = ground_.cell_center_y(cy) - vehicle.y_m;
      if (dx * dx + dy * dy < 4.0 * 4.0 || !free_block(cx, cy)) continue;
      const MapPatch patch{cx, cy, cx + 5, cy + 5, Cell::kObstacle};
      placed_.push_back(patch);
      return patch;
    }
    return MapPatch{0, 0, -1, -1, Cell::kFree};  // nothing this time
  }

  Goal next_goal(const VehiclePose& vehicle) {
    for (int attempt = 0; attempt < 200; ++attempt) {
      const int cx = static_cast<int>(rng_.below(static_cast<std::uint32_t>(ground_.width())));
      const int cy = static_cast<int>(rng_.below(static_cast<std::uint32_t>(ground_.height())));
      const double x = ground_.cell_center_x(cx);
      const double y = ground_.cell_center_y(cy);
      const double dx = x - vehicle.x_m;
      const double dy = y - vehicle.y_m;
      if (dx * dx + dy * dy < 8.0 * 8.0 || !free_block(cx - 7, cy - 7, 15)) continue;
      return Goal::disk(x, y, 1.0);
    }
    return Goal::disk(ground_.width_m() - 2.5, ground_.height_m() - 2.5, 1.0);
  }

 private:
  bool free_block(int cx, int cy, int size = 6) const {
    for (int y = cy; y < cy + size; ++y) {
      for (int x = cx; x < cx + size; ++x) {
        if (!ground_.in_bounds(x, y) || ground_.at(x, y) != Cell::kFree) return false;
      }
    }
    return true;
  }

  OccupancyGrid ground_;
  Random rng_;
  std::deque<MapPatch> placed_;
};

template <VehicleModel V>
int run_stress(const StressOptions& o, const params::GripParams& p, const V& vehicle, Scene scene,
               platform::OverrunWatcher& overruns, LoadGenerator& load) {
  // In real time at scale 1: vehicle time is wall-clock time.
  const double period_s = p.planner.cycle_s;
  const double period_ms = period_s * 1e3;
  const double budget_ms = p.planner.budget_s * 1e3;
  rt::CycleBudget budget;
  budget.cycle_s = period_s;
  budget.budget_ms = budget_ms;
  budget.margin_ms = p.planner.margin_s < 0.0 ? -1.0 : p.planner.margin_s * 1e3;
  budget.max_edges = p.planner.max_edges;
  budget.tuning = p.planner.tuning;
  budget.safety = p.planner.safety;
  budget.seed = o.seed;
  auto sized = rt::size_cycle(budget);
  if (!sized) {
    std::cerr << "grip stress: " << sized.error().message << "\n";
    return 2;
  }
  const PlannerConfig& planner_config = sized->planner;
  const rt::CycleConfig& cycle_config = sized->cycle;
  const double margin_ms = sized->margin_ms;
  auto cycle = rt::ReplanningCycle<V>::create(vehicle, scene.grid, planner_config, cycle_config);
  if (!cycle) {
    std::cerr << "grip stress: " << cycle.error().message << "\n";
    return 2;
  }
  Environment environment(scene.grid, o.seed);
  const auto start = vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad);
  const Goal first_goal = o.static_world
                              ? Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m)
                              : environment.next_goal({scene.start_x_m, scene.start_y_m});
  if (auto s = cycle->start(start, first_goal); !s) {
    std::cerr << "grip stress: " << s.error().message << "\n";
    return 2;
  }

  // Hand-offs: map patches and targets in, the vehicle's position out; none ever blocks.
  auto patches = std::make_unique<rt::SpscRing<MapPatch, 256>>();
  auto goals = std::make_unique<rt::SpscRing<Goal, 16>>();  // disks: nothing they view
  auto pose = std::make_unique<rt::TripleBuffer<VehiclePose>>();
  OccupancyGrid& grid = scene.grid;
  auto body = [&, patches = patches.get(), goals = goals.get(), pose = pose.get()](
                  std::int64_t, std::int64_t deadline) noexcept {
    MapPatch patch{};
    rt::MapChanges changes;  // the clearance is refreshed near the patches only, as on a vehicle
    while (patches->try_pop(patch)) {
      changes.apply(grid, CellBox{patch.x0, patch.y0, patch.x1, patch.y1}, patch.value);
    }
    rt::note_map_changes(*cycle, changes);
    Goal goal{};
    while (goals->try_pop(goal)) cycle->set_goal(goal);
    const rt::CycleOutcome out = cycle->run([] { return platform::now_ns(); }, deadline);
    const auto& q = cycle->plan_start();
    pose->write(VehiclePose{state_x(q), state_y(q)});
    return out;
  };

  rt::PeriodicLoopConfig loop_config;
  loop_config.period = std::chrono::nanoseconds(static_cast<std::int64_t>(period_ms * 1e6));
  loop_config.budget = std::chrono::nanoseconds(static_cast<std::int64_t>(budget_ms * 1e6));
  loop_config.policy = p.runtime.policy;
  loop_config.fifo_priority = p.runtime.fifo_priority;
  loop_config.cpu = p.runtime.cpu;
  loop_config.lock_memory = p.runtime.lock_memory;
  loop_config.cycles = static_cast<std::uint64_t>(std::llround(o.duration_s / period_s));

  // The environment thread, started before the real-time threads (a SCHED_DEADLINE thread
  // cannot create threads, and the overrun watcher must see every thread block SIGXCPU).
  std::atomic<bool> environment_stop{false};
  std::thread environment_thread([&] {
    VehiclePose vehicle_pose{scene.start_x_m, scene.start_y_m};
    std::int64_t next = platform::now_ns();
    std::int64_t next_goal = next + 3'000'000'000;
    while (!o.static_world && !environment_stop.load(std::memory_order_acquire)) {
      next += loop_config.period.count();
      platform::sleep_until_ns(next);
      (void)pose->read(vehicle_pose);
      const MapPatch patch = environment.next_patch(vehicle_pose);
      if (patch.x1 >= patch.x0) (void)patches->push_or_count_drop(patch);
      if (platform::now_ns() >= next_goal) {
        (void)goals->push_or_count_drop(environment.next_goal(vehicle_pose));
        next_goal += 3'000'000'000;
      }
    }
  });

  auto loop = rt::PeriodicLoop::start(loop_config, body);
  if (!loop) {
    environment_stop = true;
    environment_thread.join();
    std::cerr << "grip stress: " << loop.error().message << "\n";
    return 2;
  }
  rt::LatencyHistogram wake;
  rt::LatencyHistogram lateness;  // end minus deadline, 0 when on time
  rt::LatencyHistogram slack;     // deadline minus end, 0 when late
  rt::LatencyHistogram compute;
  rt::LatencyHistogram retain;  // tree retainment at the start of each cycle
  rt::LatencyHistogram commit;  // plan choice and extraction at its end
  std::uint64_t cycles = 0, misses = 0, skipped = 0, kept_previous = 0, no_plan = 0, restarts = 0;
  std::uint64_t edges_added = 0, max_tree = 0, max_trajectories = 0, exhausted = 0, solved = 0;
  std::uint64_t retained_sum = 0;
  std::map<std::string, std::uint64_t> refused;  // cycles whose tree could not be kept or started
  std::map<std::string, std::uint64_t> restarts_by_cause;
  // Estimated arrival at the target (release of the plan + its duration) once a plan reaches
  // it; on a static map retainment should never make it later.
  double first_arrival_s = -1.0;
  double last_arrival_s = -1.0;
  std::uint64_t arrival_later = 0;
  const bool tty = isatty(STDERR_FILENO) == 1;
  std::int64_t next_print = platform::now_ns();
  rt::CycleRecord record;
  const auto print_live = [&](bool final_line) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(1) << "[" << static_cast<double>(cycles) * period_s
         << " s] cycles " << cycles << ", misses " << misses << ", wake p99 "
         << (wake.count() > 0 ? static_cast<double>(wake.percentile(0.99)) / 1e3 : 0.0)
         << " us, compute p99 "
         << (compute.count() > 0 ? static_cast<double>(compute.percentile(0.99)) / 1e6 : 0.0)
         << " ms, tree " << max_tree << " edges, overruns " << overruns.overruns();
    if (tty) {
      std::cerr << "\r" << line.str() << "    " << (final_line ? "\n" : "") << std::flush;
    } else {
      std::cerr << line.str() << "\n";
    }
  };
  while (true) {
    const bool done = (*loop)->finished();
    while ((*loop)->poll(record)) {
      ++cycles;
      wake.record(record.wake_latency_ns);
      lateness.record(std::max<std::int64_t>(record.lateness_ns, 0));
      slack.record(std::max<std::int64_t>(-record.lateness_ns, 0));
      compute.record(record.compute_ns);
      retain.record(record.outcome.retain_ns);
      commit.record(record.outcome.commit_ns);
      misses += record.missed ? 1 : 0;
      skipped += record.skipped ? 1 : 0;
      kept_previous += record.outcome.kept_previous ? 1 : 0;
      no_plan += record.outcome.plan_available ? 0 : 1;
      if (record.outcome.restarted()) {
        ++restarts;
        ++restarts_by_cause[std::string(rt::restart_cause_name(record.outcome.restart_cause))];
      }
      if (record.outcome.retain_status != RetainStatus::kOk) {
        ++refused[std::string(retain_status_name(record.outcome.retain_status))];
      }
      exhausted += record.outcome.pool_exhausted ? 1 : 0;
      solved += record.outcome.solved ? 1 : 0;
      if (record.outcome.solved) {
        const double arrival =
            static_cast<double>(record.cycle + 1) * period_s + record.outcome.plan_duration_s;
        if (first_arrival_s < 0.0) first_arrival_s = arrival;
        if (last_arrival_s >= 0.0 && arrival > last_arrival_s + 1e-6) ++arrival_later;
        last_arrival_s = arrival;
      }
      edges_added += record.outcome.edges_added;
      retained_sum += record.outcome.edges_retained;
      max_tree = std::max<std::uint64_t>(max_tree, record.outcome.tree_edges);
      max_trajectories =
          std::max<std::uint64_t>(max_trajectories, record.outcome.trajectories_used);
    }
    if (done) break;
    if (platform::now_ns() >= next_print) {
      print_live(false);
      next_print += tty ? 250'000'000 : 5'000'000'000;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const rt::PeriodicLoopResult& result = (*loop)->join();
  environment_stop = true;
  environment_thread.join();
  print_live(true);
  load.stop();

  const auto& sched = result.planner_thread.scheduling;
  const double miss_rate =
      result.cycles > 0 ? static_cast<double>(result.misses) / static_cast<double>(result.cycles)
                        : 0.0;
  const double wake_p99_us = us(wake.percentile(0.99));
  const double reference_p99_us = us(result.reference_wake_latency.percentile(0.99));
  nlohmann::json report;
  report["policy"] = platform::policy_name(sched.policy);
  report["policy_requested"] = platform::request_name(p.runtime.policy);
  report["policy_fallback_reason"] = sched.fallback_reason;
  report["memory_locked"] = result.planner_thread.memory.locked;
  report["memory_lock_reason"] = result.planner_thread.memory.reason;
  report["cycles"] = result.cycles;
  report["misses"] = result.misses;
  report["skipped"] = skipped;  // releases woken after the next was due (among the misses)
  report["miss_rate"] = miss_rate;
  report["wake_latency_us"] = latency_json_us(wake);
  report["reference_wake_latency_us"] = latency_json_us(result.reference_wake_latency);
  report["reference_policy"] =
      result.reference_thread
          ? nlohmann::json(platform::policy_name(result.reference_thread->scheduling.policy))
          : nlohmann::json(nullptr);
  report["wake_latency_p99_over_reference"] =
      reference_p99_us > 0.0 ? nlohmann::json(wake_p99_us / reference_p99_us) : nullptr;
  report["lateness_us"] = latency_json_us(lateness);  // end - deadline, clamped at 0
  report["slack_us"] = latency_json_us(slack);        // deadline - end, clamped at 0
  report["compute_us"] = latency_json_us(compute);
  report["retain_us"] = latency_json_us(retain);
  report["commit_us"] = latency_json_us(commit);
  report["overruns"] = overruns.overruns();
  report["page_faults_in_loop"] =
      result.usage_in_loop.minor_faults + result.usage_in_loop.major_faults;
  report["involuntary_context_switches_in_loop"] = result.usage_in_loop.involuntary_switches;
  report["heap_allocations_in_loop"] =
      result.allocations_counted ? nlohmann::json(result.heap_allocations_in_loop) : nullptr;
  report["heap_allocations_counted"] = result.allocations_counted;
  const std::string kernel = platform::describe_machine().kernel;
  report["kernel"] = kernel;
  report["load"] = {{"kind", o.load}, {"description", load.description()}};
  report["records_dropped"] = result.records_dropped;
  report["parameters"] = params::to_yaml(p);
  report["planner"] = {{"robot", vehicle_name(vehicle_kind(p.vehicle))},
                       {"scene", o.scene},
                       {"edges_added", edges_added},
                       {"edges_per_cycle", per(edges_added, cycles)},
                       {"edges_retained_per_cycle", per(retained_sum, cycles)},
                       {"max_tree_edges", max_tree},
                       {"edge_pool", planner_config.max_edges},
                       {"max_trajectories_used", max_trajectories},
                       {"trajectory_pool", planner_config.max_trajectories},
                       {"cycles_pool_exhausted", exhausted},
                       {"cycles_previous_plan_kept", kept_previous},
                       {"cycles_without_plan", no_plan},
                       {"restarts", restarts},
                       {"restarts_by_cause", restarts_by_cause},
                       {"cycles_refused_by_status", refused},
                       {"cycles_with_plan_to_target", solved},
                       {"first_arrival_s", first_arrival_s >= 0.0 ? nlohmann::json(first_arrival_s)
                                                                  : nlohmann::json(nullptr)},
                       {"last_arrival_s", last_arrival_s >= 0.0 ? nlohmann::json(last_arrival_s)
                                                                : nlohmann::json(nullptr)},
                       {"cycles_arrival_later", arrival_later}};
  report["world"] = o.static_world ? "static" : "changing";
  report["config"] = {{"duration_s", o.duration_s},
                      {"period_ms", period_ms},
                      {"budget_ms", budget_ms},
                      {"margin_ms", margin_ms},
                      {"seed", o.seed},
                      {"integration_step_s", planner_config.integration_step_s}};

  std::cout << "grip stress: " << result.cycles << " cycles of " << period_ms << " ms (budget "
            << budget_ms << " ms, margin " << margin_ms << " ms) on " << kernel << "\n"
            << "  policy " << platform::policy_name(sched.policy)
            << (sched.fallback_reason.empty() ? "" : " (fallback: " + sched.fallback_reason + ")")
            << ", memory "
            << (result.planner_thread.memory.locked
                    ? "locked"
                    : "not locked: " + result.planner_thread.memory.reason)
            << "\n  load: " << load.description() << "\n"
            << "  misses " << result.misses << " (" << std::setprecision(4) << miss_rate * 100
            << " %, " << skipped << " of them skipped after stalls longer than a period), "
            << "SCHED_DEADLINE overruns " << overruns.overruns() << "\n"
            << std::fixed << std::setprecision(1) << "  wake-up latency us: p50 "
            << us(wake.percentile(0.5)) << ", p99 " << wake_p99_us << ", p99.9 "
            << us(wake.percentile(0.999)) << ", max " << us(wake.max()) << "\n"
            << "  reference timer us: p50 " << us(result.reference_wake_latency.percentile(0.5))
            << ", p99 " << reference_p99_us << ", max " << us(result.reference_wake_latency.max())
            << "\n"
            << "  lateness past the deadline us: p99 " << us(lateness.percentile(0.99)) << ", max "
            << us(lateness.max()) << "; slack before it us: min " << us(slack.min()) << ", p50 "
            << us(slack.percentile(0.5)) << "\n"
            << "  retainment us: p50 " << us(retain.percentile(0.5)) << ", p99 "
            << us(retain.percentile(0.99)) << ", max " << us(retain.max()) << "; commit us: p99 "
            << us(commit.percentile(0.99)) << ", max " << us(commit.max()) << "\n"
            << "  planning thread after warm-up: page faults "
            << result.usage_in_loop.minor_faults + result.usage_in_loop.major_faults
            << ", heap allocations "
            << (result.allocations_counted ? std::to_string(result.heap_allocations_in_loop)
                                           : std::string("not counted (sanitizer build)"))
            << ", involuntary switches " << result.usage_in_loop.involuntary_switches << "\n"
            << "  planner: " << per(edges_added, cycles) << " edges per cycle, "
            << per(retained_sum, cycles) << " carried over, tree up to " << max_tree << " of "
            << planner_config.max_edges << ", " << no_plan << " cycles without a plan, "
            << kept_previous << " kept the previous plan\n";
  if (first_arrival_s >= 0.0) {
    std::cout << "  target reached by the plan: arrival estimated at " << first_arrival_s
              << " s when first found, " << last_arrival_s << " s at the end, later than the "
              << "cycle before in " << arrival_later << " cycles\n";
  }
  for (const auto& [status, count] : refused) {
    std::cout << "  " << count << " cycles could not plan: " << status << "\n";
  }
  if (!o.report.empty()) {
    if (!write_report("grip stress", o.report, std::move(report))) return 1;
    std::cout << "  report: " << o.report << "\n";
  }
  if (o.max_miss_rate >= 0.0 && miss_rate > o.max_miss_rate) {
    std::cerr << "grip stress: miss rate " << miss_rate << " exceeds --max-miss-rate "
              << o.max_miss_rate << "\n";
    return 3;
  }
  return 0;
}

int run_stress_command(const StressOptions& o) {
  if (auto s = validate(o); !s) {
    std::cerr << "grip stress: " << s.error().message << "\n";
    return 2;
  }
  auto load_kind = parse_load(o.load);
  auto params = effective_params(o.params);
  auto scene = make_scene(o.scene);
  for (const Error* e : {load_kind ? nullptr : &load_kind.error(),
                         params ? nullptr : &params.error(), scene ? nullptr : &scene.error()}) {
    if (e != nullptr) {
      std::cerr << "grip stress: " << e->message << "\n";
      return 2;
    }
  }
  // First, before any other thread: SCHED_DEADLINE overruns arrive as SIGXCPU.
  auto overruns = platform::OverrunWatcher::start();
  if (!overruns) {
    std::cerr << "grip stress: " << overruns.error().message << "\n";
    return 2;
  }
  LoadOptions load_options;
  load_options.max_duration = std::chrono::seconds(static_cast<long>(o.duration_s) + 30);
  auto load = LoadGenerator::start(*load_kind, load_options);
  if (!load) {
    std::cerr << "grip stress: " << load.error().message << "\n";
    return 2;
  }
  return with_vehicle(params->vehicle, [&](const auto& vehicle) {
    return run_stress(o, *params, vehicle, std::move(scene).value(), *overruns, *load);
  });
}

}  // namespace

void register_stress_command(CLI::App& app) {
  auto o = std::make_shared<StressOptions>();
  CLI::App* cmd = app.add_subcommand(
      "stress", "Deadline-miss stress test: the real planner on the real planning thread");
  cmd->add_option("--duration", o->duration_s, "Seconds to run")->capture_default_str();
  add_vehicle_options(*cmd, o->params);
  add_cycle_options(*cmd, o->params);
  cmd->add_option("--load", o->load, "none, cpu, mem or all")->capture_default_str();
  cmd->add_option("--scene", o->scene, "meandros, labyrinth or rooms")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the planner and of the changing world")
      ->capture_default_str();
  cmd->add_option("--report", o->report, "Write the JSON report here");
  cmd->add_flag(
      "--static", o->static_world,
      "Keep the map and the target (the scene's goal) fixed: shows what retainment keeps");
  cmd->add_option("--max-miss-rate", o->max_miss_rate,
                  "Exit with status 3 when the miss rate exceeds this fraction");
  cmd->callback([o]() {
    if (const int rc = run_stress_command(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
