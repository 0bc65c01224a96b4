// `grip bench ompl`: GRIP against OMPL's control-based planners (PDST, KPIECE1, SST, RRT,
// EST) on every built-in scene and vehicle, same problem, same seeds, in one run. Prints a
// table and the targets, writes a JSON report and a Fig. 6-style PNG.
// A benchmark, not a test: it measures and prints; its exit code says only whether it ran.
//
// Every run is a fresh child process (fork): OMPL's seed generator is process-global and can
// only be seeded before its first use, and a run's memory and any crash stay its own. Runs go
// --jobs at a time; each run is single-threaded.

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ompl/util/Console.h>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "comparison.hpp"
#include "report.hpp"
#include "report_file.hpp"

namespace grip::tools {

namespace {

using ompl_bridge::RunResult;
using ompl_bridge::RunSpec;

struct BenchOmplOptions {
  std::uint32_t seeds = 3;
  double time_limit_s = 30.0;
  unsigned jobs = 1;
  std::vector<std::string> scenes{"meandros", "labyrinth", "rooms"};
  std::vector<std::string> vehicles{"dd-vel", "dd-accel", "car"};
  std::vector<std::string> planners = ompl_bridge::all_planners();
  std::string json;
  std::string png = "grip-bench-ompl.png";
  std::string from_json;  // report on the runs of an earlier --json instead of running
};

struct Child {
  pid_t pid;
  int fd;
  std::size_t run;
  std::string output;
};

// Runs spec in a child; the result comes back as one line of JSON on a pipe.
Child start_child(const RunSpec& spec, std::size_t index) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    close(fds[0]);
    // A planner that ignored its termination condition would be stopped here.
    alarm(static_cast<unsigned>(spec.time_limit_s * 3.0) + 120U);
    ::ompl::msg::setLogLevel(::ompl::msg::LOG_WARN);
    const std::string line = ompl_bridge::to_json(ompl_bridge::run_one(spec)).dump() + "\n";
    std::size_t written = 0;
    while (written < line.size()) {
      const ssize_t n = write(fds[1], line.data() + written, line.size() - written);
      if (n <= 0) _exit(3);
      written += static_cast<std::size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  return Child{pid, fds[0], index, {}};
}

RunResult finish_child(Child& child, const RunSpec& spec) {
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(child.fd, buffer, sizeof buffer);
    if (n > 0) {
      child.output.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(child.fd);
  int status = 0;
  while (waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
  }
  RunResult r;
  r.spec = spec;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    try {
      return ompl_bridge::run_result_from_json(nlohmann::json::parse(child.output));
    } catch (const std::exception& e) {
      r.error = std::string("unreadable result: ") + e.what();
    }
  } else if (WIFSIGNALED(status)) {
    r.error = std::string("crashed: ") + strsignal(WTERMSIG(status));
  } else {
    r.error = "exited with status " + std::to_string(WEXITSTATUS(status));
  }
  r.failure = "error";
  return r;
}

std::vector<RunResult> run_all(const std::vector<RunSpec>& specs, unsigned jobs) {
  std::vector<RunResult> results(specs.size());
  std::vector<Child> running;
  std::size_t next = 0;
  std::size_t done = 0;
  while (done < specs.size()) {
    while (next < specs.size() && running.size() < jobs) {
      running.push_back(start_child(specs[next], next));
      ++next;
    }
    // Read whichever child has output (a child's result fits in a pipe, so it never blocks on
    // it, but reading as it comes keeps that true for any size).
    std::vector<pollfd> fds;
    for (const Child& c : running) fds.push_back(pollfd{c.fd, POLLIN, 0});
    if (poll(fds.data(), fds.size(), -1) < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    }
    for (std::size_t i = 0; i < running.size();) {
      if ((fds[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) {
        ++i;
        continue;
      }
      Child& c = running[i];
      results[c.run] = finish_child(c, specs[c.run]);
      const RunResult& r = results[c.run];
      ++done;
      std::cerr << "  [" << done << "/" << specs.size() << "] " << r.spec.scene << " "
                << r.spec.vehicle << " " << r.spec.planner << " seed " << r.spec.seed << ": "
                << (r.verified ? "solved in " + std::to_string(r.solve_time_s) + " s"
                               : (r.error.empty() ? r.failure : r.error))
                << "\n";
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
      fds.erase(fds.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  return results;
}

int run_bench_ompl(const BenchOmplOptions& o) {
  std::vector<RunSpec> specs;
  // Seed-major, so that a partial run still covers every planner and problem.
  for (std::uint32_t seed = 1; seed <= o.seeds; ++seed) {
    for (const std::string& scene : o.scenes) {
      for (const std::string& vehicle : o.vehicles) {
        for (const std::string& planner : o.planners) {
          specs.push_back(RunSpec{scene, vehicle, planner, seed, o.time_limit_s});
        }
      }
    }
  }
  std::cout << "GRIP vs OMPL " << GRIP_OMPL_VERSION << " control planners: " << specs.size()
            << " runs (" << o.scenes.size() << " scenes x " << o.vehicles.size() << " vehicles x "
            << o.planners.size() << " planners x " << o.seeds << " seeds), time limit "
            << o.time_limit_s << " s, " << o.jobs << " at a time, one thread each\n";
  const nlohmann::json fairness = ompl_bridge::fairness_notes(o.time_limit_s);
  std::cout << "Held equal:\n";
  for (const auto& [key, value] : fairness.items()) {
    std::cout << "  " << key << ": "
              << (value.is_string() ? value.get<std::string>() : value.dump()) << "\n";
  }
  std::vector<RunResult> runs;
  if (o.from_json.empty()) {
    runs = run_all(specs, o.jobs);
  } else {
    std::ifstream in(o.from_json);
    const nlohmann::json earlier = nlohmann::json::parse(in, nullptr, false);
    if (!in || earlier.is_discarded() || !earlier.contains("runs")) {
      std::cerr << "grip bench ompl: cannot read runs from '" << o.from_json << "'\n";
      return 1;
    }
    for (const auto& r : earlier.at("runs")) runs.push_back(ompl_bridge::run_result_from_json(r));
    std::cout << "(the " << runs.size() << " runs of " << o.from_json << ", not run again)\n";
  }
  const auto summaries = ompl_bridge::summarize_runs(runs, o.planners);
  const auto targets = ompl_bridge::check_targets(runs, summaries);

  std::cout << "\nPer planner (solved = exact and passed the re-check; rej = exact but failed "
               "it; t: time to first solution,\nunsolved runs counted as beyond the limit; "
               "props/checks/tree/dur/len: medians over solved runs)\n";
  ompl_bridge::print_table(std::cout, summaries, o.time_limit_s);
  ompl_bridge::print_targets(std::cout, targets);
  for (const RunResult& r : runs) {
    if (!r.error.empty()) {
      std::cout << "error: " << r.spec.scene << " " << r.spec.vehicle << " " << r.spec.planner
                << " seed " << r.spec.seed << ": " << r.error << "\n";
    } else if (r.exact && !r.verified) {
      std::cout << "rejected: " << r.spec.scene << " " << r.spec.vehicle << " " << r.spec.planner
                << " seed " << r.spec.seed << ": " << r.failure << "\n";
    }
  }

  int rc = 0;
  if (!o.png.empty()) {
    if (auto s = ompl_bridge::write_chart(summaries, o.planners, o.time_limit_s, o.seeds, o.png);
        !s) {
      std::cerr << "grip bench ompl: " << s.error().message << "\n";
      rc = 1;
    } else {
      std::cout << "\nwrote " << o.png << "\n";
    }
  }
  if (!o.json.empty()) {
    nlohmann::json report;
    report["ompl_version"] = GRIP_OMPL_VERSION;
    report["seeds"] = o.seeds;
    report["time_limit_s"] = o.time_limit_s;
    report["jobs"] = o.jobs;
    report["held_equal"] = fairness;
    report["runs"] = nlohmann::json::array();
    for (const RunResult& r : runs) report["runs"].push_back(ompl_bridge::to_json(r));
    report["summary"] = nlohmann::json::array();
    for (const auto& s : summaries) report["summary"].push_back(ompl_bridge::to_json(s));
    report["targets"] = ompl_bridge::to_json(targets);
    if (!write_report("grip bench ompl", o.json, std::move(report))) return 1;
    std::cout << "wrote " << o.json << "\n";
  }
  return rc;
}

}  // namespace

void register_bench_ompl_command(CLI::App& bench) {
  auto o = std::make_shared<BenchOmplOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "ompl", "GRIP against OMPL's control planners (PDST, KPIECE1, SST, RRT, EST)");
  cmd->add_option("--seeds", o->seeds, "Seeds per scene, vehicle and planner")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--time-limit", o->time_limit_s, "Seconds per run")
      ->check(CLI::Range(0.01, 3600.0))
      ->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "Runs at a time (each single-threaded)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--scenes", o->scenes, "Any of meandros, labyrinth, rooms")
      ->check(CLI::IsMember({"meandros", "labyrinth", "rooms"}))
      ->capture_default_str();
  cmd->add_option("--vehicles", o->vehicles, "Any of dd-vel, dd-accel, car")
      ->check(CLI::IsMember({"dd-vel", "dd-accel", "car"}))
      ->capture_default_str();
  cmd->add_option("--planners", o->planners, "Any of grip, pdst, kpiece1, sst, rrt, est")
      ->check(CLI::IsMember(ompl_bridge::all_planners()))
      ->capture_default_str();
  cmd->add_option("--json", o->json, "Write the runs, summary and targets as JSON");
  cmd->add_option("--png", o->png, "The bar chart (empty: none)")->capture_default_str();
  cmd->add_option("--from-json", o->from_json,
                  "Report on the runs of an earlier --json file instead of running them "
                  "(give the same --seeds and --time-limit)")
      ->check(CLI::ExistingFile);
  cmd->callback([o]() {
    if (const int rc = run_bench_ompl(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
