// `grip bench dds`: plan delivery latency from the planner to its subscriber over loopback,
// against Cyclone's own ddsperf ping-pong with a payload of the plans' size, in one run.
//
// Ours: `grip planner` runs as a child process (its own Cyclone instance, so samples cross the
// loopback interface); this process is the vehicle side (state, map, goal) and takes the plans.
// The latency of a plan is the time from its commit on the planning thread
// (committed_monotonic_ns, CLOCK_MONOTONIC, shared by processes of one machine) to its take
// here: the planner's hand-off to its publish thread, serialisation, loopback, delivery. The
// plans of each round's first second are not measured, as ddsperf's first window is not.
// ddsperf: `ddsperf pong` and `ddsperf ping R size S`, two processes on the same loopback
// configuration, at the plans' rate R; ddsperf reports half the round trip, a one-way figure
// like ours.
// The two alternate in rounds (ours, then ddsperf, --rounds times), each side measured for a
// share of --duration per round, so that both meet the same states of a shared machine: a
// stall of the machine for a few seconds lands on one side of one round, not on one side of the
// whole run. Percentiles are compared pooled over all rounds. ddsperf prints only per-second
// summaries; the k-th largest of its per-second maxima (k = 1% of its round trips) is a lower bound
// of its pooled p99, since those maxima are k of its samples. Medians of per-second p99s would hide
// the machine's occasional stalls on ddsperf's side only, while ours are pooled.
// With --security DIR each round runs the planner side twice, without and then with DDS Security
// (the planner's and the vehicle's keys of DIR: authenticated, every grip topic encrypted), and
// the two pooled p99s are compared: the cost of encryption on plan delivery, in one run.
// A benchmark: it measures and prints, it asserts nothing.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "child.hpp"
#include "commands.hpp"
#include "dds_config.hpp"
#include "grip/link/vehicle_link.hpp"
#include "grip/platform/clock.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/rt/latency_histogram.hpp"
#include "grip/scenes/scenes.hpp"
#include "grip/sim/plan_executor.hpp"
#include "grip/sim/sim_participant.hpp"
#include "report_file.hpp"
#include "stats.hpp"

namespace grip::tools {

namespace {

struct BenchDdsOptions {
  double duration_s = 30.0;  // of each side, over all rounds
  unsigned rounds = 4;
  unsigned domain = 90;  // ddsperf uses domain + 1
  std::string json;
  std::string planner_report;  // the planner processes' reports, one per round (a JSON array)
  std::string security_dir;    // --security: a secured planner run too, in every round
};

nlohmann::json summary_us(const rt::LatencyHistogram& h) {
  const auto us = [](std::int64_t ns) { return static_cast<double>(ns) / 1e3; };
  return {{"count", h.count()},
          {"p50", us(h.percentile(0.5))},
          {"p90", us(h.percentile(0.9))},
          {"p99", us(h.percentile(0.99))},
          {"max", us(h.max())}};
}

struct PlannerSide {
  rt::LatencyHistogram latency;
  // The planner processes' own (hand-off and write times, misses, allocations), one per round.
  std::vector<nlohmann::json> reports;
  double plan_bytes = 0.0;
  std::uint64_t plans = 0;
  double distance_m = 0.0;  // driven by the vehicle side
  std::uint64_t goals_reached = 0;
  std::uint64_t refused = 0;  // plans not starting where the vehicle was
  // Each round's slowest plans, one entry per round as for `reports`: [seconds into the round's
  // measurement, latency us], slowest first. When they came says whether a tail is one stall
  // or spread over the round.
  std::vector<nlohmann::json> slowest;
  static constexpr std::size_t kSlowestKept = 3;
  // A plan of the last round.
  void note(double at_s, double latency_us) {
    nlohmann::json& kept = slowest.back();
    const auto at = std::find_if(kept.begin(), kept.end(), [&](const nlohmann::json& k) {
      return k[1].get<double>() < latency_us;
    });
    kept.insert(at, nlohmann::json::array({at_s, latency_us}));
    if (kept.size() > kSlowestKept) kept.erase(kept.end() - 1);
  }
  double mean_plan_bytes() const {
    return plans == 0 ? 0.0 : plan_bytes / static_cast<double>(plans);
  }
  void add(const PlannerSide& round) {
    latency.merge(round.latency);
    reports.insert(reports.end(), round.reports.begin(), round.reports.end());
    slowest.insert(slowest.end(), round.slowest.begin(), round.slowest.end());
    plan_bytes += round.plan_bytes;
    plans += round.plans;
    distance_m += round.distance_m;
    goals_reached += round.goals_reached;
    refused += round.refused;
  }
};

// The vehicle side of one round of the planner run, `seconds` long: a dd-vel robot starting at
// rest at the start of "rooms".
// With `secured`, both ends use the keys of --security.
Result<PlannerSide> measure_planner(const BenchDdsOptions& o, int seconds, bool secured = false) {
  Scene scene = make_scene("rooms").value();
  link::VehicleLinkConfig config;
  config.domain = o.domain;
  if (secured) {
    auto security = security_files(o.security_dir, "vehicle");
    if (!security) return security.error();
    config.security = *security;
  }
  config.vehicle = default_vehicle_params(VehicleKind::kDdVelocity);
  auto link = link::VehicleLink::create(config, scene.grid);
  if (!link) return link.error();
  auto self = self_executable();
  if (!self) return self.error();
  std::vector<std::string> args{*self,
                                "planner",
                                "--robot",
                                "dd-vel",
                                "--domain",
                                std::to_string(o.domain),
                                "--duration",
                                std::to_string(seconds),
                                "--startup-timeout",
                                "30"};
  if (secured) {
    args.push_back("--security");
    args.push_back(o.security_dir);
  }
  const std::string report_path =
      "/tmp/grip-bench-dds-planner-" + std::to_string(getpid()) + ".json";
  args.push_back("--report");
  args.push_back(report_path);
  auto planner = Child::spawn(std::move(args), {}, "/dev/null");
  if (!planner) return planner.error();

  // The vehicle follows the plans as a controller does (PlanExecutor, refusing plans that do
  // not start where it is), so that the planner replans as it would on a vehicle: a vehicle
  // that stood still while claiming to follow them would be planned for afresh every cycle.
  // It shuttles between the scene's goal and its start, so that the planner always has a way
  // to plan, for the whole run.
  const DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  sim::ExecutorConfig executor_config;
  executor_config.refuse_start_mismatch = true;
  auto executor = sim::PlanExecutor<DdVelocity>::create(
      robot, scene.grid, robot.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad),
      platform::now_ns(), executor_config);
  if (!executor) return executor.error();
  std::vector<PlanStep> steps;
  steps.reserve(grip_msg_kMaxPlanSteps);
  const std::array<std::array<double, 2>, 2> goals{
      {{scene.goal_x_m, scene.goal_y_m}, {scene.start_x_m, scene.start_y_m}}};
  std::size_t goal_index = 0;
  std::uint64_t goals_sent = 0;
  const auto publish_goal = [&] {
    grip_msg_Goal goal{};
    goal.sequence_number = ++goals_sent;
    goal.x_m = goals[goal_index][0];
    goal.y_m = goals[goal_index][1];
    goal.radius_m = scene.goal_radius_m;
    goal.stamp_ns = static_cast<std::uint64_t>(executor->now_ns());
    return (*link)->publish_goal(goal);
  };
  if (Status s = publish_goal(); !s) return s.error();
  PlannerSide out;
  out.slowest.emplace_back(nlohmann::json::array());  // this round's
  std::uint64_t sequence = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(seconds + 35);
  bool seen_plans = false;
  // Plans committed in the round's first second are not measured: like ddsperf's first window,
  // they meet a link still settling (the first samples of a reliable writer, cold caches).
  std::int64_t measure_from_ns = 0;
  while (std::chrono::steady_clock::now() < until) {
    // A plan first: it is what the wake-up was for, and the latency is taken when it is
    // taken, not after this tick's state went out.
    bool planner_done = false;
    if (const grip_msg_Plan* plan = (*link)->take_plan()) {
      const auto committed = static_cast<std::int64_t>(plan->committed_monotonic_ns);
      if (!seen_plans) measure_from_ns = committed + 1'000'000'000;
      if (committed >= measure_from_ns) {
        const std::int64_t latency_ns = platform::now_ns() - committed;
        out.latency.record(latency_ns);
        out.note(static_cast<double>(committed - measure_from_ns) * 1e-9,
                 static_cast<double>(latency_ns) * 1e-3);
      }
      out.plan_bytes += static_cast<double>(sizeof(grip_msg_Plan) - sizeof(plan->steps) + 4 +
                                            plan->steps._length * sizeof(grip_msg_PlanStep));
      ++out.plans;
      static_cast<void>(sim::submit_wire_plan(*executor, *plan, steps));
      seen_plans = true;
    } else {
      planner_done = seen_plans && !(*link)->planner_alive();
    }
    const std::int64_t now = platform::now_ns();
    if (now >= executor->now_ns() + executor->step_ns()) {
      executor->run_until(now);
      const DdVelocity::State& q = executor->state();
      grip_msg_VehicleState state{};
      state.stamp_ns = static_cast<std::uint64_t>(executor->now_ns());
      state.sequence_number = ++sequence;
      state.kind = grip_msg_DD_VELOCITY;
      link::state_to_wire<DdVelocity>(q, state.state, state.state_dim);
      state.time_scale = 1.0;
      state.plan_cycle = executor->executing_tag();
      static_cast<void>((*link)->publish_state(state));
      (*link)->answer_map_requests(state.stamp_ns);
      const auto& goal = goals[goal_index];
      if (std::hypot(q[0] - goal[0], q[1] - goal[1]) <= scene.goal_radius_m) {
        goal_index = 1 - goal_index;
        ++out.goals_reached;
        static_cast<void>(publish_goal());
      }
    }
    if (planner_done) break;  // the planner finished its duration
    // Woken by the plan's arrival, as a controller would be (ddsperf waits the same way).
    (*link)->wait_for_plan_or_request(std::chrono::nanoseconds(std::clamp<std::int64_t>(
        executor->now_ns() + executor->step_ns() - platform::now_ns(), 0, 50'000'000)));
  }
  out.distance_m = executor->stats().distance_m;
  out.refused = executor->stats().plans_refused;
  // It ends after its duration, having written its report.
  if (const int status = planner->wait(); status != 0) {
    return Error{ErrorCode::kIo, "the planner process ended with status " + std::to_string(status)};
  }
  if (out.latency.count() == 0) {
    return Error{ErrorCode::kIo, "no plan arrived from the planner after its first second"};
  }
  {
    std::ifstream in(report_path);
    nlohmann::json report = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (!report.is_object()) {
      return Error{ErrorCode::kIo,
                   "the planner process wrote no readable report to " + report_path};
    }
    out.reports.push_back(std::move(report));
  }
  std::remove(report_path.c_str());
  return out;
}

struct DdsperfSide {
  std::vector<double> p50_us, p90_us, p99_us, max_us, round_trips;  // one entry per second
  std::uint64_t count() const {
    double n = 0.0;
    for (const double c : round_trips) n += c;
    return static_cast<std::uint64_t>(n);
  }
  // k: 1% of the round trips, at least 1 and at most one per second.
  std::size_t pooled_p99_rank() const {
    const auto k = static_cast<std::size_t>(std::ceil(0.01 * static_cast<double>(count())));
    return std::min(std::max<std::size_t>(k, 1), max_us.size());
  }
  // A lower bound of the p99 over all round trips: the k-th largest per-second maximum.
  double pooled_p99_at_least_us() const {
    std::vector<double> maxima = max_us;
    std::sort(maxima.begin(), maxima.end(), std::greater<>());
    return maxima.empty() ? 0.0 : maxima[pooled_p99_rank() - 1];
  }
  void add(const DdsperfSide& round) {
    for (auto [to, from] : {std::pair{&p50_us, &round.p50_us}, std::pair{&p90_us, &round.p90_us},
                            std::pair{&p99_us, &round.p99_us}, std::pair{&max_us, &round.max_us},
                            std::pair{&round_trips, &round.round_trips}}) {
      to->insert(to->end(), from->begin(), from->end());
    }
  }
};

// Tables show 0 for no samples.
double median(const std::vector<double>& v) { return tools::median(v, 0.0); }

// One round of ddsperf, `seconds` long.
Result<DdsperfSide> measure_ddsperf(const BenchDdsOptions& o, int seconds,
                                    std::size_t payload_bytes, unsigned rate_hz) {
  const std::string config_path = "/tmp/grip-bench-dds-" + std::to_string(getpid()) + ".xml";
  {
    std::ofstream config(config_path);
    config << platform::dds::loopback_config();
    if (!config) return Error{ErrorCode::kIo, "cannot write " + config_path};
  }
  const std::vector<std::string> env{"CYCLONEDDS_URI=file://" + config_path};
  const std::string domain = std::to_string(o.domain + 1);
  const std::string duration = std::to_string(seconds + 2);
  const std::string ping_out = config_path + ".ping.txt";
  auto pong =
      Child::spawn({"ddsperf", "-i", domain, "-D", duration, "pong", "waitset"}, env, "/dev/null");
  if (!pong) return pong.error();
  auto ping = Child::spawn(
      {"ddsperf", "-i", domain, "-D", std::to_string(seconds), "ping",
       std::to_string(rate_hz) + "Hz", "size", std::to_string(payload_bytes), "waitset"},
      env, ping_out);
  if (!ping) return ping.error();
  ping->wait();
  std::ifstream in(ping_out);
  DdsperfSide out;
  std::string line;
  // "[pid] 3.000  host:pid size 2048 mean 131us min 86us 50% 130us 90% 148us 99% 161us max 161us
  // cnt 20"
  while (std::getline(in, line)) {
    const auto field = [&](const std::string& key) -> double {
      const auto at = line.find(" " + key + " ");
      return at == std::string::npos ? -1.0 : std::atof(line.c_str() + at + key.size() + 2);
    };
    if (field("50%") < 0.0 || field("99%") < 0.0 || field("cnt") <= 0.0) continue;
    out.p50_us.push_back(field("50%"));
    out.p90_us.push_back(field("90%"));
    out.p99_us.push_back(field("99%"));
    out.max_us.push_back(field("max"));
    out.round_trips.push_back(field("cnt"));
  }
  std::remove(ping_out.c_str());
  std::remove(config_path.c_str());
  // The first window includes discovery; it is not steady state.
  if (out.p99_us.size() > 1) {
    for (auto* v : {&out.p50_us, &out.p90_us, &out.p99_us, &out.max_us, &out.round_trips}) {
      v->erase(v->begin());
    }
  }
  if (out.p99_us.empty())
    return Error{ErrorCode::kIo, "ddsperf reported no latency (is cyclonedds-tools installed?)"};
  return out;
}

int run_bench_dds(const BenchDdsOptions& o) {
  // ddsperf counts whole seconds, and drops its first (discovery) second of each round.
  const int seconds = static_cast<int>(std::lround(o.duration_s / o.rounds));
  if (seconds < 3) {
    std::cerr << "grip bench dds: --duration " << o.duration_s << " over --rounds " << o.rounds
              << " leaves " << seconds << " s per round and side; at least 3 are needed\n";
    return 2;
  }
  PlannerSide ours;
  PlannerSide secured;  // with --security
  DdsperfSide theirs;
  std::size_t payload = 0;
  unsigned rate_hz = 0;
  const auto us = [](std::int64_t ns) { return static_cast<double>(ns) / 1e3; };
  // Where the planner's side spends it, in the planner process's report of one round.
  const auto part = [](const nlohmann::json& report, const char* key) {
    const nlohmann::json& p = report.value(key, nlohmann::json());
    return p.is_object() ? p : nlohmann::json{{"p50", 0.0}, {"p99", 0.0}, {"max", 0.0}};
  };
  for (unsigned round = 1; round <= o.rounds; ++round) {
    std::cerr << "grip bench dds: round " << round << " of " << o.rounds
              << ": planner -> subscriber for " << seconds << " s ...\n";
    auto planner = measure_planner(o, seconds);
    if (!planner) {
      std::cerr << "grip bench dds: " << planner.error().message << "\n";
      return 1;
    }
    if (round == 1) {
      // The plans' own size and rate, so that both sides carry as much and wake as often.
      payload = static_cast<std::size_t>(planner->mean_plan_bytes());
      rate_hz = static_cast<unsigned>(
          std::max(1.0, std::round(static_cast<double>(planner->plans) / seconds)));
    }
    if (!o.security_dir.empty()) {
      std::cerr << "grip bench dds: round " << round << " of " << o.rounds
                << ": planner -> subscriber with DDS Security for " << seconds << " s ...\n";
      auto with_security = measure_planner(o, seconds, /*secured=*/true);
      if (!with_security) {
        std::cerr << "grip bench dds: with DDS Security: " << with_security.error().message << "\n";
        return 1;
      }
      std::printf("round %u: with DDS Security, plan delivery p99 %.1f us (%llu plans measured)\n",
                  round, us(with_security->latency.percentile(0.99)),
                  static_cast<unsigned long long>(with_security->latency.count()));
      secured.add(*with_security);
    }
    std::cerr << "grip bench dds: round " << round << " of " << o.rounds << ": ddsperf ping-pong, "
              << payload << " bytes at " << rate_hz << " Hz, for " << seconds << " s ...\n";
    auto ddsperf = measure_ddsperf(o, seconds, payload, rate_hz);
    if (!ddsperf) {
      std::cerr << "grip bench dds: " << ddsperf.error().message << "\n";
      return 1;
    }
    const nlohmann::json& report = planner->reports.front();
    std::string slowest;
    for (const nlohmann::json& k : planner->slowest.front()) {
      char one[48];
      std::snprintf(one, sizeof one, "%s%.0f us at %.1f s", slowest.empty() ? "" : ", ",
                    k[1].get<double>(), k[0].get<double>());
      slowest += one;
    }
    std::printf(
        "round %u: plan delivery p99 %.1f us (%llu plans measured; commit -> publish thread p99 "
        "%.1f us, dds_write p99 %.1f us; slowest %s); ddsperf p99 at least %.1f us\n",
        round, us(planner->latency.percentile(0.99)),
        static_cast<unsigned long long>(planner->latency.count()),
        part(report, "plan_handoff_us").value("p99", 0.0),
        part(report, "plan_write_us").value("p99", 0.0), slowest.c_str(),
        ddsperf->pooled_p99_at_least_us());
    ours.add(*planner);
    theirs.add(*ddsperf);
  }

  const double our_p99 = us(ours.latency.percentile(0.99));
  const double their_p99 = theirs.pooled_p99_at_least_us();
  std::printf(
      "plan delivery, planner -> subscriber (%llu plans measured, mean %.0f bytes), pooled:\n"
      "  p50 %.1f us, p90 %.1f us, p99 %.1f us, max %.1f us\n"
      "ddsperf ping-pong one-way (%llu round trips, %zu bytes, %u Hz):\n"
      "  medians of its per-second windows: p50 %.1f us, p90 %.1f us, p99 %.1f us\n"
      "  pooled p99 at least %.1f us (rank %zu of its per-second maxima, largest first); max %.1f "
      "us\n"
      "p99 ratio planner / ddsperf, pooled over %u rounds: at most %.2f (target <= 1.5)\n",
      static_cast<unsigned long long>(ours.latency.count()), ours.mean_plan_bytes(),
      us(ours.latency.percentile(0.5)), us(ours.latency.percentile(0.9)), our_p99,
      us(ours.latency.max()), static_cast<unsigned long long>(theirs.count()), payload, rate_hz,
      median(theirs.p50_us), median(theirs.p90_us), median(theirs.p99_us), their_p99,
      theirs.pooled_p99_rank(), *std::max_element(theirs.max_us.begin(), theirs.max_us.end()),
      o.rounds, our_p99 / their_p99);
  if (!o.security_dir.empty()) {
    std::printf(
        "with DDS Security (%llu plans measured, rounds alternating with the run above), pooled:\n"
        "  p50 %.1f us, p90 %.1f us, p99 %.1f us, max %.1f us\n"
        "p99 ratio with / without DDS Security, same rounds: %.2f (target <= 1.5)\n",
        static_cast<unsigned long long>(secured.latency.count()),
        us(secured.latency.percentile(0.5)), us(secured.latency.percentile(0.9)),
        us(secured.latency.percentile(0.99)), us(secured.latency.max()),
        us(secured.latency.percentile(0.99)) / our_p99);
  }
  // What the plans were for: a vehicle that follows them (the planner replans from where they
  // put it, not from scratch).
  std::uint64_t off_plans = 0;
  for (const nlohmann::json& report : ours.reports) {
    off_plans += report.value("resyncs", std::uint64_t{0});
  }
  std::printf(
      "the vehicle followed them: %.1f m driven, %llu goals reached, %llu plans refused; the "
      "planner found it off its plans %llu times\n",
      ours.distance_m, static_cast<unsigned long long>(ours.goals_reached),
      static_cast<unsigned long long>(ours.refused), static_cast<unsigned long long>(off_plans));
  if (!o.planner_report.empty()) {
    if (!write_report("grip bench dds", o.planner_report, nlohmann::json(ours.reports))) {
      return 1;
    }
  }
  if (!o.json.empty()) {
    nlohmann::json j;
    j["planner"] = summary_us(ours.latency);
    j["planner"]["mean_plan_bytes"] = ours.mean_plan_bytes();
    nlohmann::json rounds = nlohmann::json::array();
    for (std::size_t r = 0; r < ours.reports.size(); ++r) {
      rounds.push_back({{"handoff_us", part(ours.reports[r], "plan_handoff_us")},
                        {"write_us", part(ours.reports[r], "plan_write_us")},
                        {"slowest_s_us", ours.slowest[r]}});
    }
    j["planner"]["rounds"] = rounds;
    j["vehicle"] = {{"distance_m", ours.distance_m},
                    {"goals_reached", ours.goals_reached},
                    {"plans_refused", ours.refused},
                    {"planner_found_it_off_its_plans", off_plans}};
    j["ddsperf"] = {{"payload_bytes", payload},
                    {"round_trips", theirs.count()},
                    {"p50_us_median", median(theirs.p50_us)},
                    {"p90_us_median", median(theirs.p90_us)},
                    {"rate_hz", rate_hz},
                    {"p99_us_median", median(theirs.p99_us)},
                    {"p99_us_pooled_at_least", their_p99},
                    {"p99_us_per_second", theirs.p99_us},
                    {"max_us_per_second", theirs.max_us}};
    j["p99_ratio"] = our_p99 / their_p99;
    if (!o.security_dir.empty()) {
      j["secured"] = summary_us(secured.latency);
      j["secured"]["mean_plan_bytes"] = secured.mean_plan_bytes();
      j["secured_p99_ratio"] = us(secured.latency.percentile(0.99)) / our_p99;
    }
    j["duration_s"] = o.duration_s;
    j["rounds"] = o.rounds;
    if (!write_report("grip bench dds", o.json, std::move(j))) return 1;
  }
  return 0;
}

}  // namespace

void register_bench_dds_command(CLI::App& bench) {
  auto o = std::make_shared<BenchDdsOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "dds", "Plan delivery latency planner -> subscriber on loopback, against ddsperf ping-pong");
  cmd->add_option("--duration", o->duration_s,
                  "Seconds of each side's measurement, over all rounds")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--rounds", o->rounds,
                  "Rounds of the two sides in turn (ours, then ddsperf), each duration/rounds long")
      ->capture_default_str()
      ->check(CLI::Range(1U, 100U));
  cmd->add_option("--domain", o->domain, "DDS domain of the planner run (ddsperf uses the next)")
      ->check(CLI::Range(0U, kMaxDomainId - 1))
      ->capture_default_str();
  cmd->add_option("--json", o->json, "Write the figures as JSON here");
  cmd->add_option("--planner-report", o->planner_report,
                  "Write the planner process's reports here, one per round (allocations, misses)");
  add_security_option(*cmd, o->security_dir,
                      "none; with it, each round measures the planner side without and with it");
  cmd->callback([o]() {
    if (const int rc = run_bench_dds(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
