#include "grip/tools/load_generator.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

namespace grip::tools {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

static_assert(!std::is_copy_constructible_v<LoadGenerator>);
static_assert(std::is_nothrow_move_constructible_v<LoadGenerator>);
static_assert(std::is_nothrow_move_assignable_v<LoadGenerator>);

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

int online_cpus() { return static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN)); }

// Threads of this process whose /proc/self/task/<tid>/comm is `name`.
int threads_named(const std::string& name) {
  int count = 0;
  std::error_code error;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error)) {
    std::ifstream comm(task.path() / "comm");
    std::string comm_name;
    if (std::getline(comm, comm_name) && comm_name == name) ++count;
  }
  return count;
}

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool stress_ng_installed() {
  const char* path = std::getenv("PATH");
  std::string directories = path != nullptr ? path : "";
  std::size_t begin = 0;
  while (begin <= directories.size()) {
    const std::size_t end = std::min(directories.find(':', begin), directories.size());
    const std::string candidate = directories.substr(begin, end - begin) + "/stress-ng";
    if (access(candidate.c_str(), X_OK) == 0) return true;
    begin = end + 1;
  }
  return false;
}

// "0.15.06" from `stress-ng --version`, read independently of the code under test.
std::string stress_ng_version() {
  std::FILE* pipe = popen("stress-ng --version", "r");
  if (pipe == nullptr) return "";
  std::array<char, 256> line{};
  const bool read = std::fgets(line.data(), static_cast<int>(line.size()), pipe) != nullptr;
  pclose(pipe);
  if (!read) return "";
  const std::string text = line.data();
  const std::size_t at = text.find("version ");
  if (at == std::string::npos) return "";
  const std::size_t first = at + 8;
  return text.substr(first, text.find(' ', first) - first);
}

// The process group of `pid` from /proc/<pid>/stat; -1 if it is gone.
int process_group(int pid) {
  std::ifstream stat_file("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(stat_file, stat)) return -1;
  // "pid (comm) state ppid pgrp ...": comm may hold spaces, so start after the last ')'.
  std::string rest = stat.substr(stat.rfind(')') + 2);
  char state = 0;
  int ppid = 0;
  int pgrp = -1;
  if (std::sscanf(rest.c_str(), "%c %d %d", &state, &ppid, &pgrp) != 3) return -1;
  return pgrp;
}

// The state letter of `pid` from /proc/<pid>/stat ('R', 'S', 'Z', ...); 0 if it is gone.
char process_state(int pid) {
  std::ifstream stat_file("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(stat_file, stat)) return 0;
  return stat.substr(stat.rfind(')') + 2).front();
}

// Processes in process group `group`; zombies (exited, not yet reaped) count unless told not to.
int processes_in_group(int group, bool count_zombies = true) {
  int count = 0;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const int pid = std::stoi(name);
    if (process_group(pid) != group) continue;
    if (count_zombies || process_state(pid) != 'Z') ++count;
  }
  return count;
}

// How long a test waits for what a working load does within a second or so: long, because a
// loaded machine may starve the load's threads, and only a broken load ever reaches it.
constexpr std::chrono::milliseconds kPatience{30000};

// Polls `done` every 20 ms for up to `limit`; the seconds it took, or nullopt on time-out.
template <typename Done>
std::optional<double> seconds_until(Done done, std::chrono::milliseconds limit) {
  const Clock::time_point start = Clock::now();
  while (Clock::now() - start < limit) {
    if (done()) return seconds_since(start);
    std::this_thread::sleep_for(milliseconds(20));
  }
  return std::nullopt;
}

// A joined thread's OS task lingers a moment in /proc (the kernel wakes the joiner before it
// reaps the task), so a stopped load's threads are waited for rather than counted at once.
bool threads_gone(const std::string& name) {
  return seconds_until([&] { return threads_named(name) == 0; }, kPatience).has_value();
}

LoadOptions built_in() {
  LoadOptions options;
  options.prefer_stress_ng = false;
  return options;
}

TEST(LoadName, EveryKindRoundTripsThroughItsName) {
  for (const LoadKind kind : {LoadKind::kNone, LoadKind::kCpu, LoadKind::kMemory, LoadKind::kAll}) {
    const Result<LoadKind> parsed = parse_load(load_name(kind));
    ASSERT_TRUE(parsed.ok()) << load_name(kind);
    EXPECT_EQ(*parsed, kind);
  }
  EXPECT_EQ(load_name(LoadKind::kNone), "none");
  EXPECT_EQ(load_name(LoadKind::kCpu), "cpu");
  EXPECT_EQ(load_name(LoadKind::kMemory), "mem");
  EXPECT_EQ(load_name(LoadKind::kAll), "all");
}

TEST(LoadName, AnUnknownNameIsRefusedWithTheValidNames) {
  for (const char* bad : {"disk", "", "CPU", "memory"}) {
    const Result<LoadKind> parsed = parse_load(bad);
    ASSERT_FALSE(parsed.ok()) << bad;
    EXPECT_EQ(parsed.error().code, ErrorCode::kInvalidArgument);
    std::string quoted(1, '\'');  // not "'" + ...: GCC 12 -O3 warns falsely (-Wrestrict)
    quoted.append(bad).push_back('\'');
    EXPECT_TRUE(contains(parsed.error().message, quoted)) << parsed.error().message;
    EXPECT_TRUE(contains(parsed.error().message, "none | cpu | mem | all"))
        << parsed.error().message;
  }
}

TEST(LoadGenerator, NoneRunsNothingAndSaysNone) {
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kNone, {});
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_EQ(load->description(), "none");
  EXPECT_EQ(load->kind(), LoadKind::kNone);
  EXPECT_FALSE(load->running());
  EXPECT_FALSE(load->uses_stress_ng());
  EXPECT_EQ(load->child_pid(), -1);
  EXPECT_EQ(threads_named("grip-load-cpu") + threads_named("grip-load-mem"), 0);
  load->stop();
  load->stop();
  EXPECT_EQ(load->description(), "none");
}

TEST(LoadGenerator, BadOptionsAreRefusedBeforeAnythingStarts) {
  LoadOptions zero_duration = built_in();
  zero_duration.max_duration = std::chrono::seconds(0);
  LoadOptions tiny_buffer = built_in();
  tiny_buffer.memory_bytes = 100;

  const Result<LoadGenerator> no_time = LoadGenerator::start(LoadKind::kCpu, zero_duration);
  ASSERT_FALSE(no_time.ok());
  EXPECT_EQ(no_time.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(no_time.error().message, "max_duration must be >= 1 s (got 0 s)"))
      << no_time.error().message;
  const Result<LoadGenerator> no_memory = LoadGenerator::start(LoadKind::kMemory, tiny_buffer);
  ASSERT_FALSE(no_memory.ok());
  EXPECT_EQ(no_memory.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(no_memory.error().message, "memory_bytes")) << no_memory.error().message;
  EXPECT_EQ(threads_named("grip-load-cpu") + threads_named("grip-load-mem"), 0);
}

TEST(LoadGenerator, BuiltInCpuLoadSpinsOneNamedThreadPerCpuUntilStopped) {
  // GIVEN the built-in CPU load
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, built_in());
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_FALSE(load->uses_stress_ng());
  EXPECT_EQ(load->child_pid(), -1);
  EXPECT_EQ(load->description(), "built-in: " + std::to_string(online_cpus()) +
                                     (online_cpus() == 1 ? " CPU hog thread" : " CPU hog threads") +
                                     ", stopping after 3600 s");

  // WHEN this thread only waits
  const double cpu_before = cpu_seconds();

  // THEN the process burns CPU all the same (how fast depends on who else runs here), and the
  // hogs are visible under their name
  EXPECT_TRUE(seconds_until([&] { return cpu_seconds() - cpu_before >= 0.3; }, kPatience))
      << "the hogs burnt only " << cpu_seconds() - cpu_before << " s of CPU";
  EXPECT_TRUE(load->running());
  EXPECT_EQ(threads_named("grip-load-cpu"), online_cpus());

  // WHEN stopped THEN the threads are gone
  load->stop();
  EXPECT_FALSE(load->running());
  EXPECT_TRUE(threads_gone("grip-load-cpu"));
  EXPECT_TRUE(contains(load->description(), "built-in")) << "the description outlives stop()";
}

TEST(LoadGenerator, BuiltInMemoryLoadKeepsFaultingPagesIn) {
  // GIVEN the built-in memory load on a 64 MiB buffer (16384 pages per pass)
  LoadOptions options = built_in();
  options.memory_bytes = std::size_t{64} * 1024 * 1024;
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kMemory, options);
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_TRUE(contains(load->description(), "built-in: 1 thread touching 64 MiB"))
      << load->description();

  // WHEN it runs
  const long faults_before = minor_faults();

  // THEN pages keep faulting in: two whole passes over the buffer
  EXPECT_TRUE(seconds_until([&] { return minor_faults() - faults_before >= 2 * 16384; }, kPatience))
      << "only " << minor_faults() - faults_before << " pages faulted in";
  EXPECT_EQ(threads_named("grip-load-mem"), 1);
  EXPECT_EQ(threads_named("grip-load-cpu"), 0);

  load->stop();
  EXPECT_FALSE(load->running());
  EXPECT_TRUE(threads_gone("grip-load-mem"));
}

TEST(LoadGenerator, BuiltInAllRunsBothLoadsAndDescribesBoth) {
  LoadOptions options = built_in();
  options.memory_bytes = std::size_t{16} * 1024 * 1024;
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kAll, options);
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_EQ(load->kind(), LoadKind::kAll);
  EXPECT_EQ(threads_named("grip-load-cpu"), online_cpus());
  EXPECT_EQ(threads_named("grip-load-mem"), 1);
  EXPECT_TRUE(contains(load->description(), " CPU hog thread")) << load->description();
  EXPECT_TRUE(contains(load->description(), " + 1 thread touching 16 MiB")) << load->description();
  load->stop();
  EXPECT_TRUE(threads_gone("grip-load-cpu"));
  EXPECT_TRUE(threads_gone("grip-load-mem"));
}

TEST(LoadGenerator, StressNgRunsAsAChildGroupAndStopLeavesNoProcess) {
  LoadOptions options;
  options.memory_bytes = std::size_t{32} * 1024 * 1024;
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kAll, options);
  ASSERT_TRUE(load.ok()) << load.error().message;

  if (!stress_ng_installed()) {
    // THEN the preferred stress-ng is replaced by the built-in load, and the report says so
    EXPECT_FALSE(load->uses_stress_ng());
    EXPECT_TRUE(contains(load->description(), "built-in: ")) << load->description();
    EXPECT_TRUE(contains(load->description(), "(stress-ng not found in PATH)"))
        << load->description();
    EXPECT_EQ(threads_named("grip-load-cpu"), online_cpus());
    return;
  }

  // THEN stress-ng runs as our child, leading its own process group
  ASSERT_TRUE(load->uses_stress_ng()) << load->description();
  const int pid = load->child_pid();
  ASSERT_GT(pid, 0);
  EXPECT_EQ(kill(pid, 0), 0);
  EXPECT_EQ(process_group(pid), pid);
  EXPECT_NE(getpgrp(), pid);
  EXPECT_TRUE(load->running());
  EXPECT_EQ(threads_named("grip-load-cpu") + threads_named("grip-load-mem"), 0);
  // AND the description is the exact command with the version stress-ng reports
  const std::string version = stress_ng_version();
  ASSERT_FALSE(version.empty());
  EXPECT_EQ(load->description(), "stress-ng --cpu " + std::to_string(online_cpus()) +
                                     " --vm 1 --vm-bytes 32m --timeout 3600s --quiet (stress-ng " +
                                     version + ")");
  // AND its workers join the group (stress-ng forks them after starting)
  const std::optional<double> workers =
      seconds_until([&] { return processes_in_group(pid) >= 3; }, kPatience);
  EXPECT_TRUE(workers.has_value()) << processes_in_group(pid) << " processes in the group";

  // WHEN stopped THEN the child is reaped and nothing of its group is left
  load->stop();
  EXPECT_FALSE(load->running());
  EXPECT_EQ(load->child_pid(), -1);
  errno = 0;
  EXPECT_EQ(kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH) << "a zombie would still answer kill(pid, 0)";
  EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), -1) << "already reaped";
  EXPECT_EQ(processes_in_group(pid), 0);
  EXPECT_TRUE(contains(load->description(), "stress-ng --cpu")) << "outlives stop()";
}

TEST(LoadGenerator, StressNgDiesWithTheProcessThatStartedIt) {
  // GIVEN a child process of this test that starts the preferred load, reports the stress-ng
  // pid (-1 for the built-in fallback) and dies without stopping it
  std::array<int, 2> report{-1, -1};
  ASSERT_EQ(pipe(report.data()), 0);
  const pid_t starter = fork();
  ASSERT_GE(starter, 0);
  if (starter == 0) {
    close(report[0]);
    Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, {});
    const int pid = load.ok() ? load->child_pid() : -2;
    (void)!write(report[1], &pid, sizeof(pid));
    _exit(0);  // no destructor: the load is not stopped
  }
  close(report[1]);
  int stress_ng = -3;
  const ssize_t got = read(report[0], &stress_ng, sizeof(stress_ng));
  close(report[0]);
  ASSERT_EQ(waitpid(starter, nullptr, 0), starter);
  ASSERT_EQ(got, static_cast<ssize_t>(sizeof(stress_ng)));
  ASSERT_NE(stress_ng, -2) << "start() failed in the child";
  if (!stress_ng_installed()) {
    EXPECT_EQ(stress_ng, -1) << "without stress-ng the load is threads, which die with it";
    return;
  }
  ASSERT_GT(stress_ng, 0);

  // THEN PR_SET_PDEATHSIG kills stress-ng, and its workers follow (nothing of the group keeps
  // running; an orphan may stay a zombie if this machine's init does not reap)
  const std::optional<double> gone = seconds_until(
      [&] { return processes_in_group(stress_ng, /*count_zombies=*/false) == 0; }, kPatience);
  EXPECT_TRUE(gone.has_value()) << processes_in_group(stress_ng, false)
                                << " stress-ng processes still alive";
}

TEST(LoadGenerator, WithoutStressNgInPathTheBuiltInLoadRunsAndSaysWhy) {
  // GIVEN a PATH in which no stress-ng can be found
  const char* saved = std::getenv("PATH");
  const std::string original = saved != nullptr ? saved : "";
  const std::filesystem::path empty_dir =
      std::filesystem::temp_directory_path() / ("grip-load-test-" + std::to_string(getpid()));
  std::filesystem::create_directories(empty_dir);
  setenv("PATH", empty_dir.c_str(), 1);

  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, {});

  setenv("PATH", original.c_str(), 1);
  std::filesystem::remove(empty_dir);
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_FALSE(load->uses_stress_ng());
  EXPECT_TRUE(load->running());
  EXPECT_EQ(load->description(), "built-in: " + std::to_string(online_cpus()) +
                                     (online_cpus() == 1 ? " CPU hog thread" : " CPU hog threads") +
                                     ", stopping after 3600 s (stress-ng not found in PATH)");
  EXPECT_EQ(threads_named("grip-load-cpu"), online_cpus());
}

TEST(LoadGenerator, AStressNgThatCannotRunIsReplacedByTheBuiltInLoad) {
  // GIVEN a PATH whose stress-ng is executable but not a program (execv fails with ENOEXEC)
  const char* saved = std::getenv("PATH");
  const std::string original = saved != nullptr ? saved : "";
  const std::filesystem::path fake_dir =
      std::filesystem::temp_directory_path() / ("grip-load-fake-" + std::to_string(getpid()));
  std::filesystem::create_directories(fake_dir);
  const std::filesystem::path fake = fake_dir / "stress-ng";
  std::ofstream(fake) << "not an executable format\n";
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  setenv("PATH", fake_dir.c_str(), 1);

  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, {});

  setenv("PATH", original.c_str(), 1);
  std::filesystem::remove_all(fake_dir);
  // THEN the exec failure reported by the child is not an error: the built-in load runs and the
  // description names the failed step
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_FALSE(load->uses_stress_ng());
  EXPECT_EQ(threads_named("grip-load-cpu"), online_cpus());
  EXPECT_TRUE(contains(load->description(),
                       "(stress-ng could not be started: " + fake.string() + ": execv: ENOEXEC"))
      << load->description();
}

TEST(LoadGenerator, BuiltInLoadStopsByItselfAfterMaxDuration) {
  LoadOptions options = built_in();
  options.max_duration = std::chrono::seconds(1);
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, options);
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_TRUE(contains(load->description(), "stopping after 1 s")) << load->description();

  const std::optional<double> ended = seconds_until([&] { return !load->running(); }, kPatience);
  ASSERT_TRUE(ended.has_value()) << "still running long after a 1 s safety timeout";
  EXPECT_GE(*ended, 0.9);
  // A load thread counts itself out just before it returns: the OS task goes a moment later.
  EXPECT_TRUE(threads_gone("grip-load-cpu")) << "the threads did not end; stop() only joins them";
  load->stop();
}

TEST(LoadGenerator, PreferredStressNgAlsoStopsByItselfAfterMaxDuration) {
  // stress-ng when installed, else the built-in fallback: either way the timeout holds
  LoadOptions options;
  options.max_duration = std::chrono::seconds(1);
  Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, options);
  ASSERT_TRUE(load.ok()) << load.error().message;
  EXPECT_EQ(load->uses_stress_ng(), stress_ng_installed()) << load->description();
  const int pid = load->child_pid();

  const std::optional<double> ended = seconds_until([&] { return !load->running(); }, kPatience);
  ASSERT_TRUE(ended.has_value()) << "still running long after a 1 s safety timeout";
  EXPECT_GE(*ended, 0.9);
  load->stop();
  if (pid > 0) {
    EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), -1) << "stop() reaped the child that exited";
    EXPECT_EQ(processes_in_group(pid), 0);
  }
}

TEST(LoadGenerator, MovingHandsOverTheLoadAndAssigningOverOneStopsIt) {
  Result<LoadGenerator> first = LoadGenerator::start(LoadKind::kCpu, built_in());
  ASSERT_TRUE(first.ok()) << first.error().message;
  const std::string description = first->description();

  LoadGenerator moved(std::move(*first));
  EXPECT_FALSE(first->running());  // NOLINT(bugprone-use-after-move): the moved-from state
  EXPECT_EQ(first->description(), "none");
  EXPECT_EQ(first->kind(), LoadKind::kNone);
  EXPECT_TRUE(moved.running());
  EXPECT_EQ(moved.description(), description);

  Result<LoadGenerator> none = LoadGenerator::start(LoadKind::kNone, {});
  ASSERT_TRUE(none.ok());
  moved = std::move(*none);
  EXPECT_TRUE(threads_gone("grip-load-cpu")) << "assigning over a load stops it";
  EXPECT_EQ(moved.description(), "none");
}

}  // namespace
}  // namespace grip::tools
