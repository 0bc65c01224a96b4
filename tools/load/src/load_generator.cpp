#include "grip/tools/load_generator.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <utility>
#include <vector>

#include "grip/platform/clock.hpp"
#include "grip/platform/os_call.hpp"
#include "grip/platform/thread.hpp"
#include "grip/platform/proc_files.hpp"

namespace grip::tools {

using namespace platform;  // os calls, clocks, threads
namespace {

constexpr std::size_t kPageBytes = 4096;  // the built-in memory load writes one byte per page
constexpr std::size_t kMiB = std::size_t{1024} * 1024;
constexpr std::size_t kDefaultMemoryCap = std::size_t{2} * 1024 * kMiB;
constexpr TimePoint kStopGraceNs = 1'000'000'000;  // SIGTERM, then SIGKILL after this
constexpr TimePoint kStopPollNs = 10'000'000;      // how often stop() looks for the exit
// `stress-ng --version` must answer by then. Generous: it runs once, at start-up, and a fresh CI
// machine under a sanitized test suite once took more than 2 s to answer.
constexpr int kVersionTimeoutMs = 10'000;
constexpr const char* kCpuThreadName = "grip-load-cpu";
constexpr const char* kMemoryThreadName = "grip-load-mem";

bool wants_cpu(LoadKind kind) { return kind == LoadKind::kCpu || kind == LoadKind::kAll; }
bool wants_memory(LoadKind kind) { return kind == LoadKind::kMemory || kind == LoadKind::kAll; }

template <typename T>
Error os_error(const OsResult<T>& result) {
  return Error{ErrorCode::kIo, result.describe()};
}

void close_fd(int fd) noexcept {
  if (fd >= 0) (void)os_call("close", [fd] { return ::close(fd); });
}

std::string format_bytes(std::size_t bytes) {
  if (bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
  return std::to_string(bytes) + " bytes";
}

Result<int> online_cpus() {
  const auto cpus = os_call("sysconf", [] { return ::sysconf(_SC_NPROCESSORS_ONLN); });
  if (!cpus.ok()) return os_error(cpus);
  return static_cast<int>(std::max(1L, cpus.value));
}

// 1/8 of MemTotal, capped at 2 GiB, in whole pages.
Result<std::size_t> default_memory_bytes() {
  const Result<std::string> meminfo = platform::detail::read_small_file("/proc/meminfo");
  if (!meminfo.ok()) return meminfo.error();
  const std::optional<std::string_view> total = platform::detail::status_field(*meminfo, "MemTotal");
  std::uint64_t kib = 0;
  if (!total ||
      std::from_chars(total->data(), total->data() + total->size(), kib).ec != std::errc{}) {
    return Error{ErrorCode::kParse, "/proc/meminfo has no readable MemTotal line"};
  }
  const std::size_t eighth = static_cast<std::size_t>(kib) * 1024 / 8;
  return std::max(kPageBytes, std::min(eighth, kDefaultMemoryCap) / kPageBytes * kPageBytes);
}

// ---- stress-ng: finding it, and running it as a child process -------------------------------

// The first executable regular file named `program` in PATH (an empty entry is the current
// directory, as execvp reads it); nullopt when there is none.
std::optional<std::string> find_in_path(std::string_view program) {
  const char* path_variable = std::getenv("PATH");
  std::string_view path = path_variable != nullptr ? path_variable : "/usr/local/bin:/usr/bin:/bin";
  while (true) {
    const std::size_t colon = path.find(':');
    // Built piecewise: GCC 12 at -O3 warns falsely (-Wrestrict) on string literals joined to
    // strings here.
    std::string candidate(path.substr(0, colon));
    if (candidate.empty()) candidate.push_back('.');
    candidate.push_back('/');
    candidate.append(program);
    struct stat info {};
    const auto stated = os_call("stat", [&] { return ::stat(candidate.c_str(), &info); });
    const auto executable = os_call("access", [&] { return ::access(candidate.c_str(), X_OK); });
    if (stated.ok() && S_ISREG(info.st_mode) && executable.ok()) return candidate;
    if (colon == std::string_view::npos) return std::nullopt;
    path.remove_prefix(colon + 1);
  }
}

// Written by the vfork child, which shares our memory, when a step before exec fails; read by
// the parent once vfork returns (the parent is suspended until the child execs or exits).
// volatile: the compiler must not assume the parent's copy is untouched by the child.
struct ChildFailure {
  const char* volatile step = nullptr;
  volatile int error = 0;
};

struct SpawnRequest {
  const char* path;
  char* const* argv;  // NULL-terminated
  int null_fd;        // /dev/null, for stdin and stderr (and stdout unless stdout_fd >= 0)
  int stdout_fd;      // -1: /dev/null
  pid_t parent;
};

// Makes `target` (0, 1 or 2) refer to `fd`, open across exec.
bool redirect(int fd, int target) noexcept {
  if (fd == target) {
    return os_call("fcntl", [fd] { return ::fcntl(fd, F_SETFD, 0); }).ok();
  }
  return os_call("dup2", [fd, target] { return ::dup2(fd, target); }).ok();
}

// Runs in the vfork child, on the parent's stack, with every signal blocked: only plain system
// calls, no allocation, no return (exec or _exit). Never inlined: inlined into spawn(), the
// optimiser shares spawn()'s frame with it and the child's failure report was lost at -O3.
[[noreturn]] __attribute__((noinline)) void run_child(const SpawnRequest& request,
                                                      ChildFailure& failure) noexcept {
  const auto fail = [&failure](const char* step, int error) {
    failure.step = step;
    failure.error = error;
    ::_exit(127);
  };
  // The handler table is the child's own (vfork does not share it): no handler of ours may run
  // here, and stress-ng starts from default dispositions.
  for (int signal_number = 1; signal_number < NSIG; ++signal_number) {
    if (signal_number == SIGKILL || signal_number == SIGSTOP) continue;
    struct sigaction action {};
    action.sa_handler = SIG_DFL;
    // glibc refuses its internal signals (EINVAL): harmless.
    (void)os_call("sigaction", [&] { return ::sigaction(signal_number, &action, nullptr); });
  }
  const auto death_signal =
      os_call("prctl", [] { return ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0); });
  if (!death_signal.ok()) fail("prctl(PR_SET_PDEATHSIG)", death_signal.error);
  if (::getppid() != request.parent) fail("getppid (the parent exited)", ESRCH);
  const auto grouped = os_call("setpgid", [] { return ::setpgid(0, 0); });
  if (!grouped.ok()) fail("setpgid", grouped.error);
  if (::sched_getscheduler(0) != SCHED_OTHER) {  // a FIFO caller's policy is inherited
    sched_param param{};
    (void)os_call("sched_setscheduler",
                  [&] { return ::sched_setscheduler(0, SCHED_OTHER, &param); });
  }
  const int out = request.stdout_fd >= 0 ? request.stdout_fd : request.null_fd;
  if (!redirect(request.null_fd, STDIN_FILENO) || !redirect(out, STDOUT_FILENO) ||
      !redirect(request.null_fd, STDERR_FILENO)) {
    fail("dup2", errno);
  }
  // Descriptors opened without O_CLOEXEC elsewhere in grip must not leak into stress-ng. ENOSYS
  // on kernels before 5.9: harmless.
  (void)os_call("close_range", [] { return ::close_range(3, ~0U, 0); });
  sigset_t none;
  sigemptyset(&none);
  (void)os_call("sigprocmask", [&] { return ::sigprocmask(SIG_SETMASK, &none, nullptr); });
  const auto executed = os_call("execv", [&] { return ::execv(request.path, request.argv); });
  fail("execv", executed.error);
  ::_exit(127);  // not reached
}

// Starts `path` with `args` (args[0] is the program name) as a child process in its own process
// group. vfork, not fork: the child borrows our address space until exec instead of sharing
// every page copy-on-write (which would give the planner's locked pages write faults later).
Result<pid_t> spawn(const std::string& path, const std::vector<std::string>& args, int stdout_fd) {
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const auto null_fd = os_call("open", [] { return ::open("/dev/null", O_RDWR | O_CLOEXEC); });
  if (!null_fd.ok()) return Error{ErrorCode::kIo, "/dev/null: " + null_fd.describe()};
  const SpawnRequest request{path.c_str(), argv.data(), null_fd.value, stdout_fd, ::getpid()};
  ChildFailure failure;

  // No signal handler may run in the child while it shares our memory.
  sigset_t all;
  sigset_t previous;
  sigfillset(&all);
  const auto blocked = os_call_returning_error(
      "pthread_sigmask", [&] { return ::pthread_sigmask(SIG_SETMASK, &all, &previous); });
  if (!blocked.ok()) {
    close_fd(null_fd.value);
    return os_error(blocked);
  }
  // The one call not wrapped in os_call: the vfork child must not return from the function that
  // called vfork (it would pop frames the parent still needs), and os_call's lambda would be
  // that function. The error is captured the same way by hand.
  errno = 0;
  const pid_t pid = ::vfork();
  const OsResult<pid_t> forked{pid, pid == -1 ? errno : 0, "vfork"};
  if (forked.ok() && forked.value == 0) run_child(request, failure);
  (void)os_call_returning_error("pthread_sigmask",
                                [&] { return ::pthread_sigmask(SIG_SETMASK, &previous, nullptr); });
  close_fd(null_fd.value);

  if (!forked.ok()) return Error{ErrorCode::kIo, path + ": " + forked.describe()};
  if (failure.step != nullptr) {
    int status = 0;
    while (os_call("waitpid", [&] { return ::waitpid(forked.value, &status, 0); }).error == EINTR) {
    }
    return Error{ErrorCode::kIo,
                 path + ": " + std::string(failure.step) + ": " + describe_errno(failure.error)};
  }
  return forked.value;
}

// True when the child has exited (or is gone: already reaped by someone, e.g. with SIGCHLD
// ignored). Leaves it a zombie, so its pid and process group id cannot be reused yet.
bool child_exited(pid_t pid) noexcept {
  siginfo_t info{};
  const auto waited = os_call("waitid", [&] {
    return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT);
  });
  if (!waited.ok()) return waited.error != EINTR;  // ECHILD: gone
  return info.si_pid == pid;
}

void reap(pid_t pid) noexcept {
  int status = 0;
  while (os_call("waitpid", [&] { return ::waitpid(pid, &status, 0); }).error == EINTR) {
  }
}

// "stress-ng 0.15.06" from `stress-ng --version` ("stress-ng, version 0.15.06 (gcc ...)").
std::string stress_ng_version(const std::string& path) {
  const std::string unknown = "stress-ng, version unknown";
  std::array<int, 2> pipe_fds{-1, -1};
  if (!os_call("pipe2", [&] { return ::pipe2(pipe_fds.data(), O_CLOEXEC); }).ok()) return unknown;
  const Result<pid_t> child = spawn(path, {"stress-ng", "--version"}, pipe_fds[1]);
  close_fd(pipe_fds[1]);
  if (!child.ok()) {
    close_fd(pipe_fds[0]);
    return unknown;
  }
  std::string output;
  const TimePoint give_up = now_ns() + TimePoint{kVersionTimeoutMs} * 1'000'000;
  while (output.size() < 4096) {
    const TimePoint left_ns = give_up - now_ns();
    if (left_ns <= 0) break;
    pollfd readable{pipe_fds[0], POLLIN, 0};
    const int timeout_ms = static_cast<int>(left_ns / 1'000'000) + 1;
    const auto polled = os_call("poll", [&] { return ::poll(&readable, 1, timeout_ms); });
    if (!polled.ok() && polled.error == EINTR) continue;
    if (!polled.ok() || polled.value == 0) break;
    std::array<char, 512> chunk{};
    const auto got =
        os_call("read", [&] { return ::read(pipe_fds[0], chunk.data(), chunk.size()); });
    if (!got.ok() && got.error == EINTR) continue;
    if (!got.ok() || got.value == 0) break;
    output.append(chunk.data(), static_cast<std::size_t>(got.value));
  }
  close_fd(pipe_fds[0]);
  if (!child_exited(*child)) {
    (void)os_call("kill", [&] { return ::kill(-*child, SIGKILL); });
  }
  reap(*child);

  constexpr std::string_view kMarker = "version ";
  const std::size_t at = output.find(kMarker);
  if (at == std::string::npos) return unknown;
  const std::size_t first = at + kMarker.size();
  const std::size_t last = output.find_first_of(" \n\t", first);
  const std::string version = output.substr(first, last == std::string::npos ? last : last - first);
  return version.empty() ? unknown : "stress-ng " + version;
}

std::vector<std::string> stress_ng_arguments(LoadKind kind, int cpus, std::size_t memory_bytes,
                                             std::chrono::seconds max_duration) {
  std::vector<std::string> args{"stress-ng"};
  if (wants_cpu(kind)) args.insert(args.end(), {"--cpu", std::to_string(cpus)});
  if (wants_memory(kind)) {
    const std::string bytes = memory_bytes % kMiB == 0 ? std::to_string(memory_bytes / kMiB) + "m"
                                                       : std::to_string(memory_bytes);
    args.insert(args.end(), {"--vm", "1", "--vm-bytes", bytes});
  }
  args.insert(args.end(), {"--timeout", std::to_string(max_duration.count()) + "s", "--quiet"});
  return args;
}

}  // namespace

// ---- names ----------------------------------------------------------------------------------

std::string_view load_name(LoadKind kind) noexcept {
  switch (kind) {
    case LoadKind::kNone:
      return "none";
    case LoadKind::kCpu:
      return "cpu";
    case LoadKind::kMemory:
      return "mem";
    case LoadKind::kAll:
      return "all";
  }
  return "unknown";
}

Result<LoadKind> parse_load(std::string_view name) {
  for (const LoadKind kind : {LoadKind::kNone, LoadKind::kCpu, LoadKind::kMemory, LoadKind::kAll}) {
    if (name == load_name(kind)) return kind;
  }
  return invalid_argument("unknown load '" + std::string(name) +
                          "' (valid: none | cpu | mem | all)");
}

// ---- the generator --------------------------------------------------------------------------

namespace {

// What the built-in load threads share with the generator; lives in the generator's State, which
// outlives the threads (stop() joins them).
struct BuiltInLoad {
  TimePoint deadline_ns = 0;  // the safety timeout, CLOCK_MONOTONIC
  std::atomic<bool> stop{false};
  std::atomic<int> live_threads{0};
  std::atomic<std::uint64_t> sink{0};  // keeps the CPU hogs' arithmetic from being optimised out
  unsigned char* buffer = nullptr;
  std::size_t buffer_bytes = 0;

  bool should_stop() const noexcept {
    return stop.load(std::memory_order_relaxed) || now_ns() >= deadline_ns;
  }
};

// xorshift64 rounds: integer work that stays in registers and cannot be folded away.
void hog_cpu(BuiltInLoad& load) noexcept {
  std::uint64_t x = 0x9E3779B97F4A7C15ULL;
  for (std::uint64_t round = 1; !load.stop.load(std::memory_order_relaxed); ++round) {
    for (int i = 0; i < 4096; ++i) {  // a few microseconds between looks at the stop flag
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
    }
    load.sink.store(x, std::memory_order_relaxed);
    if (round % 64 == 0 && now_ns() >= load.deadline_ns) break;
  }
  load.live_threads.fetch_sub(1, std::memory_order_release);
}

void touch_memory(BuiltInLoad& load) noexcept {
  volatile unsigned char* const bytes = load.buffer;
  unsigned char value = 1;
  while (!load.should_stop()) {
    for (std::size_t offset = 0; offset < load.buffer_bytes; offset += kPageBytes) {
      bytes[offset] = value;
      if ((offset / kPageBytes) % 256 == 255 && load.should_stop()) break;
    }
    ++value;
    // Give the pages back so the next pass faults them in again. A buffer that mlockall()
    // locked after start() refuses MADV_DONTNEED (EINVAL) until it is unlocked.
    const auto dropped = os_call(
        "madvise", [&] { return ::madvise(load.buffer, load.buffer_bytes, MADV_DONTNEED); });
    if (!dropped.ok() && dropped.error == EINVAL) {
      (void)os_call("munlock", [&] { return ::munlock(load.buffer, load.buffer_bytes); });
      (void)os_call("madvise",
                    [&] { return ::madvise(load.buffer, load.buffer_bytes, MADV_DONTNEED); });
    }
  }
  load.live_threads.fetch_sub(1, std::memory_order_release);
}

// Starts one load thread running `body`; counted in live_threads before it exists, so that
// running() never sees a load that is starting as finished.
Status start_thread(BuiltInLoad& load, std::vector<RealtimeThread>& threads, const char* name,
                    void (*body)(BuiltInLoad&) noexcept) {
  RealtimeThreadConfig config;
  config.name = name;
  config.scheduling.request = PolicyRequest::kOther;
  config.lock_memory = false;
  config.stack_prefault_bytes = 0;
  config.stack_size_bytes = std::size_t{256} * 1024;
  BuiltInLoad* raw_load = &load;
  load.live_threads.fetch_add(1, std::memory_order_relaxed);
  Result<RealtimeThread> thread = RealtimeThread::start(
      config, [raw_load, body](const RealtimeThreadInfo&) { body(*raw_load); });
  if (!thread.ok()) {
    load.live_threads.fetch_sub(1, std::memory_order_relaxed);  // the body never ran
    return thread.error();
  }
  threads.push_back(std::move(thread).value());
  return Ok{};
}

}  // namespace

struct LoadGenerator::State {
  LoadKind kind = LoadKind::kNone;
  std::string description = "none";
  bool stopped = false;
  pid_t child = -1;  // stress-ng, also its process group id; -1 once reaped or when built-in
  BuiltInLoad built_in;
  std::vector<RealtimeThread> threads;  // the built-in load's
};

LoadGenerator::LoadGenerator(std::unique_ptr<State> state) noexcept : state_(std::move(state)) {}
LoadGenerator::LoadGenerator(LoadGenerator&& other) noexcept = default;

LoadGenerator& LoadGenerator::operator=(LoadGenerator&& other) noexcept {
  if (this != &other) {
    stop();
    state_ = std::move(other.state_);
  }
  return *this;
}

LoadGenerator::~LoadGenerator() { stop(); }

const std::string& LoadGenerator::description() const noexcept {
  static const std::string kNoneDescription = "none";
  return state_ != nullptr ? state_->description : kNoneDescription;
}

LoadKind LoadGenerator::kind() const noexcept {
  return state_ != nullptr ? state_->kind : LoadKind::kNone;
}

bool LoadGenerator::uses_stress_ng() const noexcept {
  return state_ != nullptr && state_->child >= 0;
}

int LoadGenerator::child_pid() const noexcept { return state_ != nullptr ? state_->child : -1; }

bool LoadGenerator::running() const noexcept {
  if (state_ == nullptr || state_->stopped) return false;
  if (state_->child >= 0) return !child_exited(state_->child);
  return state_->built_in.live_threads.load(std::memory_order_acquire) > 0;
}

void LoadGenerator::stop() noexcept {
  if (state_ == nullptr || state_->stopped) return;
  State& state = *state_;
  state.stopped = true;
  if (state.child >= 0) {
    const pid_t group = state.child;
    (void)os_call("kill", [group] { return ::kill(-group, SIGTERM); });
    const TimePoint give_up = now_ns() + kStopGraceNs;
    while (!child_exited(group) && now_ns() < give_up) sleep_until_ns(now_ns() + kStopPollNs);
    // The leader is at worst a zombie, so the group id is still ours: kill what is left of it
    // (the leader if it ignored SIGTERM, workers it left behind), then reap.
    (void)os_call("kill", [group] { return ::kill(-group, SIGKILL); });
    reap(group);
    state.child = -1;
    return;
  }
  BuiltInLoad& load = state.built_in;
  load.stop.store(true, std::memory_order_relaxed);
  for (RealtimeThread& thread : state.threads) thread.join();
  if (load.buffer != nullptr) {
    (void)os_call("munmap", [&] { return ::munmap(load.buffer, load.buffer_bytes); });
    load.buffer = nullptr;
  }
}

Result<LoadGenerator> LoadGenerator::start(LoadKind kind, const LoadOptions& options) {
  auto state = std::make_unique<State>();
  state->kind = kind;
  if (kind == LoadKind::kNone) return LoadGenerator(std::move(state));

  if (options.max_duration < std::chrono::seconds(1)) {
    return invalid_argument("load max_duration must be >= 1 s (got " +
                            std::to_string(options.max_duration.count()) + " s)");
  }
  if (options.memory_bytes != 0 && options.memory_bytes < kPageBytes) {
    return invalid_argument("load memory_bytes must be 0 (automatic) or >= 4096 (got " +
                            std::to_string(options.memory_bytes) + ")");
  }
  const Result<int> cpus = online_cpus();
  if (!cpus.ok()) return cpus.error();
  std::size_t memory_bytes = options.memory_bytes / kPageBytes * kPageBytes;
  if (wants_memory(kind) && memory_bytes == 0) {
    const Result<std::size_t> automatic = default_memory_bytes();
    if (!automatic.ok()) return automatic.error();
    memory_bytes = *automatic;
  }

  std::string why_not_stress_ng;
  if (options.prefer_stress_ng) {
    const std::optional<std::string> path = find_in_path("stress-ng");
    if (!path) {
      why_not_stress_ng = "stress-ng not found in PATH";
    } else {
      const std::string version = stress_ng_version(*path);
      const std::vector<std::string> args =
          stress_ng_arguments(kind, *cpus, memory_bytes, options.max_duration);
      const Result<pid_t> child = spawn(*path, args, -1);
      if (child.ok()) {
        state->child = *child;
        state->description.clear();
        for (const std::string& arg : args) {
          if (!state->description.empty()) state->description += ' ';
          state->description += arg;
        }
        state->description += " (" + version + ")";
        return LoadGenerator(std::move(state));
      }
      why_not_stress_ng = "stress-ng could not be started: " + child.error().message;
    }
  }

  // Built-in load.
  BuiltInLoad& load = state->built_in;
  load.deadline_ns = now_ns() + TimePoint{options.max_duration.count()} * 1'000'000'000;
  std::string what;
  if (wants_memory(kind)) {
    const auto mapped = os_call_pointer("mmap", [&]() -> void* {
      void* address = ::mmap(nullptr, memory_bytes, PROT_READ | PROT_WRITE,
                             MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
      return address == MAP_FAILED ? nullptr : address;
    });
    if (!mapped.ok()) {
      return Error{ErrorCode::kIo,
                   "load buffer of " + format_bytes(memory_bytes) + ": " + mapped.describe()};
    }
    load.buffer = static_cast<unsigned char*>(mapped.value);
    load.buffer_bytes = memory_bytes;
    // One fault per 4 KiB page, not one per 2 MiB transparent huge page. Refused (EINVAL) on a
    // kernel without THP: harmless.
    (void)os_call("madvise", [&] { return ::madvise(load.buffer, memory_bytes, MADV_NOHUGEPAGE); });
  }
  // From here on, an error return destroys `generator`, which stops what already started.
  LoadGenerator generator(std::move(state));
  std::vector<RealtimeThread>& threads = generator.state_->threads;
  if (wants_cpu(kind)) {
    for (int cpu = 0; cpu < *cpus; ++cpu) {
      Status started = start_thread(load, threads, kCpuThreadName, &hog_cpu);
      if (!started.ok()) return started.error();
    }
    what = "built-in: " + std::to_string(*cpus) + " CPU hog thread" + (*cpus == 1 ? "" : "s");
  }
  if (wants_memory(kind)) {
    Status started = start_thread(load, threads, kMemoryThreadName, &touch_memory);
    if (!started.ok()) return started.error();
    what += what.empty() ? "built-in: " : " + ";
    what += "1 thread touching " + format_bytes(memory_bytes) +
            " (one write per 4 KiB page, MADV_DONTNEED after each pass)";
  }
  what += ", stopping after " + std::to_string(options.max_duration.count()) + " s";
  if (!why_not_stress_ng.empty()) what += " (" + why_not_stress_ng + ")";
  generator.state_->description = std::move(what);
  return generator;
}

}  // namespace grip::tools
