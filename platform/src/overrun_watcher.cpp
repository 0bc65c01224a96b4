#include "grip/platform/overrun_watcher.hpp"

#include <dirent.h>
#include <poll.h>
#include <pthread.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <unistd.h>
#include <csignal>

#include <array>
#include <atomic>
#include <charconv>
#include <optional>
#include <string>
#include <string_view>

#include "grip/common/assert.hpp"
#include "grip/platform/os_call.hpp"
#include "grip/platform/thread.hpp"
#include "grip/platform/proc_files.hpp"

namespace grip::platform {

struct OverrunWatcher::State {
  std::atomic<std::uint64_t> overruns{0};
  int signal_fd = -1;  // readable when SIGXCPU is pending for the process
  int wake_fd = -1;    // eventfd: readable when stop() asks the thread to end
  std::optional<RealtimeThread> thread;
};

namespace {

Error os_error(const OsResult<int>& result) { return Error{ErrorCode::kIo, result.describe()}; }

void close_fd(int& fd) noexcept {
  if (fd < 0) return;
  (void)os_call("close", [&] { return ::close(fd); });
  fd = -1;
}

// True iff the SigBlk mask in a /proc/<pid>/task/<tid>/status text contains SIGXCPU.
bool blocks_sigxcpu(std::string_view status) {
  const std::optional<std::string_view> mask_text = detail::status_field(status, "SigBlk");
  if (!mask_text) return false;
  std::uint64_t mask = 0;
  const auto [end, ec] =
      std::from_chars(mask_text->data(), mask_text->data() + mask_text->size(), mask, 16);
  return ec == std::errc{} && (mask & (std::uint64_t{1} << (SIGXCPU - 1))) != 0;
}

// Every thread of this process other than the caller must block SIGXCPU; names one that does
// not.
Status check_other_threads_block_sigxcpu() {
  const std::string self = std::to_string(::gettid());
  const auto opened = os_call_pointer("opendir", [] { return ::opendir("/proc/self/task"); });
  if (!opened.ok()) return Error{ErrorCode::kIo, "/proc/self/task: " + opened.describe()};
  Status verdict = Ok{};
  while (verdict.ok()) {
    // NOLINTNEXTLINE(concurrency-mt-unsafe): the stream is ours alone
    const auto entry = os_call_pointer("readdir", [&] { return ::readdir(opened.value); });
    if (!entry.ok()) {
      verdict = Error{ErrorCode::kIo, "/proc/self/task: " + entry.describe()};
      break;
    }
    if (entry.value == nullptr) break;  // the end of the directory
    const std::string tid = entry.value->d_name;
    if (tid == "." || tid == ".." || tid == self) continue;
    const Result<std::string> status =
        detail::read_small_file("/proc/self/task/" + tid + "/status");
    if (!status.ok() || blocks_sigxcpu(*status)) continue;  // gone meanwhile, or fine
    const std::string name(detail::status_field(*status, "Name").value_or("?"));
    verdict = invalid_argument(
        "OverrunWatcher::start must run before any other thread starts: thread " + tid + " (" +
        name +
        ") does not block SIGXCPU, so a deadline overrun could be delivered to it and "
        "kill the process");
  }
  (void)os_call("closedir", [&] { return ::closedir(opened.value); });
  return verdict;
}

}  // namespace

namespace {
std::atomic<int> g_running_watchers{0};
}  // namespace

bool OverrunWatcher::active() noexcept {
  return g_running_watchers.load(std::memory_order_acquire) > 0;
}

Result<OverrunWatcher> OverrunWatcher::start() {
  sigset_t sigxcpu;
  (void)os_call("sigemptyset", [&] { return ::sigemptyset(&sigxcpu); });
  (void)os_call("sigaddset", [&] { return ::sigaddset(&sigxcpu, SIGXCPU); });
  const auto blocked = os_call_returning_error(
      "pthread_sigmask", [&] { return ::pthread_sigmask(SIG_BLOCK, &sigxcpu, nullptr); });
  if (!blocked.ok()) return os_error(blocked);
  if (Status others = check_other_threads_block_sigxcpu(); !others.ok()) return others.error();

  auto state = std::make_unique<State>();
  const auto signal_fd =
      os_call("signalfd", [&] { return ::signalfd(-1, &sigxcpu, SFD_NONBLOCK | SFD_CLOEXEC); });
  if (!signal_fd.ok()) return os_error(signal_fd);
  state->signal_fd = signal_fd.value;
  const auto wake_fd = os_call("eventfd", [] { return ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC); });
  if (!wake_fd.ok()) {
    close_fd(state->signal_fd);
    return os_error(wake_fd);
  }
  state->wake_fd = wake_fd.value;

  RealtimeThreadConfig config;
  config.name = "grip-overrun";
  config.scheduling.request = PolicyRequest::kOther;
  config.lock_memory = false;
  config.stack_prefault_bytes = 0;
  config.stack_size_bytes = std::size_t{256} * 1024;
  State* raw_state = state.get();
  Result<RealtimeThread> thread =
      RealtimeThread::start(config, [raw_state](const RealtimeThreadInfo&) { watch(*raw_state); });
  if (!thread.ok()) {
    close_fd(state->signal_fd);
    close_fd(state->wake_fd);
    return thread.error();
  }
  state->thread.emplace(std::move(thread).value());
  g_running_watchers.fetch_add(1, std::memory_order_acq_rel);
  return OverrunWatcher(std::move(state));
}

void OverrunWatcher::watch(State& state) noexcept {
  while (true) {
    std::array<pollfd, 2> fds{{{state.signal_fd, POLLIN, 0}, {state.wake_fd, POLLIN, 0}}};
    const auto polled = os_call("poll", [&] { return ::poll(fds.data(), fds.size(), -1); });
    if (!polled.ok()) {
      GRIP_ASSERT(polled.error == EINTR);  // anything else means a broken descriptor
      continue;
    }
    // Drain before looking at the wake-up, so that what was pending at stop() is counted.
    while (true) {
      signalfd_siginfo info{};
      const auto got =
          os_call("read", [&] { return ::read(state.signal_fd, &info, sizeof(info)); });
      if (!got.ok() || got.value != static_cast<ssize_t>(sizeof(info))) break;  // EAGAIN: drained
      state.overruns.fetch_add(1, std::memory_order_relaxed);
    }
    if ((fds[1].revents & POLLIN) != 0) return;
  }
}

OverrunWatcher::OverrunWatcher(std::unique_ptr<State> state) noexcept : state_(std::move(state)) {}

OverrunWatcher::OverrunWatcher(OverrunWatcher&& other) noexcept = default;

OverrunWatcher& OverrunWatcher::operator=(OverrunWatcher&& other) noexcept {
  if (this != &other) {
    stop();
    state_ = std::move(other.state_);
  }
  return *this;
}

OverrunWatcher::~OverrunWatcher() { stop(); }

std::uint64_t OverrunWatcher::overruns() const noexcept {
  return state_ != nullptr ? state_->overruns.load(std::memory_order_relaxed) : 0;
}

void OverrunWatcher::stop() noexcept {
  if (state_ == nullptr || !state_->thread) return;
  const std::uint64_t one = 1;
  const auto woken = os_call("write", [&] { return ::write(state_->wake_fd, &one, sizeof(one)); });
  GRIP_ASSERT(woken.ok());  // an eventfd at 1 cannot overflow
  state_->thread->join();
  state_->thread.reset();
  g_running_watchers.fetch_sub(1, std::memory_order_acq_rel);
  close_fd(state_->signal_fd);
  close_fd(state_->wake_fd);
}

}  // namespace grip::platform
