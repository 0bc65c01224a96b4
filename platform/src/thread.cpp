#include "grip/platform/thread.hpp"

#include <pthread.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <optional>
#include <semaphore>
#include <utility>

#include "grip/common/assert.hpp"
#include "grip/platform/os_call.hpp"

namespace grip::platform {
namespace {

constexpr std::size_t kMaxNameLength = 15;                      // TASK_COMM_LEN - 1
constexpr std::size_t kStackHeadroom = std::size_t{64} * 1024;  // left free by the prefault

Status validate_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameLength) {
    return invalid_argument("thread name '" + std::string(name) +
                            "' must have 1 to 15 characters (got " + std::to_string(name.size()) +
                            ")");
  }
  return Ok{};
}

}  // namespace

Status set_thread_name(std::string_view name) {
  if (Status valid = validate_name(name); !valid.ok()) return valid;
  std::array<char, kMaxNameLength + 1> terminated{};
  std::memcpy(terminated.data(), name.data(), name.size());
  const auto named = os_call_returning_error("pthread_setname_np", [&] {
    return ::pthread_setname_np(::pthread_self(), terminated.data());
  });
  if (!named.ok()) return Error{ErrorCode::kIo, named.describe()};
  return Ok{};
}

struct RealtimeThread::State {
  // Written by start() before the thread exists, read-only afterwards.
  std::string name;
  SchedulingRequest scheduling;
  std::size_t stack_prefault_bytes = 0;
  Body body;
  // Written by the thread before it releases `ready`, read-only afterwards.
  RealtimeThreadInfo info;
  std::optional<Error> setup_error;
  std::binary_semaphore ready{0};

  pthread_t handle{};
  bool joinable = false;
};

void* RealtimeThread::run(void* argument) noexcept {
  auto& state = *static_cast<RealtimeThread::State*>(argument);
  if (Status named = set_thread_name(state.name); !named.ok()) {
    state.setup_error = named.error();
    state.ready.release();
    return nullptr;
  }
  // Before the policy: under SCHED_DEADLINE the page faults would spend the first period's
  // runtime and raise a spurious overrun.
  prefault_stack(state.stack_prefault_bytes);
  Result<SchedulingOutcome> scheduled = apply_scheduling(state.scheduling);
  if (!scheduled.ok()) {
    state.setup_error = scheduled.error();
    state.ready.release();
    return nullptr;
  }
  state.info.scheduling = std::move(scheduled).value();
  state.ready.release();
  state.body(state.info);
  return nullptr;
}

Result<RealtimeThread> RealtimeThread::start(const RealtimeThreadConfig& config, Body body) {
  if (Status valid = validate_name(config.name); !valid.ok()) return valid.error();
  if (Status valid = validate(config.scheduling); !valid.ok()) return valid.error();
  if (config.stack_prefault_bytes + kStackHeadroom > config.stack_size_bytes) {
    return invalid_argument("stack_prefault_bytes (" + std::to_string(config.stack_prefault_bytes) +
                            ") must leave 64 KiB of stack_size_bytes (" +
                            std::to_string(config.stack_size_bytes) + ") free");
  }
  if (!body) return invalid_argument("thread '" + config.name + "' has an empty body");

  auto state = std::make_unique<State>();
  state->name = config.name;
  state->scheduling = config.scheduling;
  state->stack_prefault_bytes = config.stack_prefault_bytes;
  state->body = std::move(body);
  state->info.memory =
      config.lock_memory ? lock_process_memory() : MemoryLockOutcome{false, "not requested"};

  pthread_attr_t attributes;
  const auto initialised = os_call_returning_error(
      "pthread_attr_init", [&] { return ::pthread_attr_init(&attributes); });
  if (!initialised.ok()) return Error{ErrorCode::kIo, initialised.describe()};
  const auto sized = os_call_returning_error("pthread_attr_setstacksize", [&] {
    return ::pthread_attr_setstacksize(&attributes, config.stack_size_bytes);
  });
  if (!sized.ok()) {
    (void)os_call_returning_error("pthread_attr_destroy",
                                  [&] { return ::pthread_attr_destroy(&attributes); });
    return invalid_argument("stack_size_bytes " + std::to_string(config.stack_size_bytes) +
                            " refused: " + sized.describe() + " (below PTHREAD_STACK_MIN?)");
  }
  State* raw_state = state.get();
  const auto created = os_call_returning_error("pthread_create", [&] {
    return ::pthread_create(&raw_state->handle, &attributes, &RealtimeThread::run, raw_state);
  });
  (void)os_call_returning_error("pthread_attr_destroy",
                                [&] { return ::pthread_attr_destroy(&attributes); });
  if (!created.ok()) {
    std::string why = created.describe();
    if (created.error == EAGAIN && current_policy() == SchedPolicy::kDeadline) {
      why += ": the calling thread runs under SCHED_DEADLINE, which may not create threads";
    }
    return Error{ErrorCode::kIo, "thread '" + config.name + "': " + why};
  }
  state->joinable = true;
  state->ready.acquire();
  if (state->setup_error) {
    Error error = *state->setup_error;
    error.message = "thread '" + config.name + "': " + error.message;
    RealtimeThread failed(std::move(state));
    failed.join();
    return error;
  }
  return RealtimeThread(std::move(state));
}

RealtimeThread::RealtimeThread(std::unique_ptr<State> state) noexcept : state_(std::move(state)) {}

RealtimeThread::RealtimeThread(RealtimeThread&& other) noexcept = default;

RealtimeThread& RealtimeThread::operator=(RealtimeThread&& other) noexcept {
  if (this != &other) {
    join();
    state_ = std::move(other.state_);
  }
  return *this;
}

RealtimeThread::~RealtimeThread() { join(); }

bool RealtimeThread::joinable() const noexcept { return state_ != nullptr && state_->joinable; }

void RealtimeThread::join() noexcept {
  if (!joinable()) return;
  const auto joined = os_call_returning_error(
      "pthread_join", [&] { return ::pthread_join(state_->handle, nullptr); });
  GRIP_ASSERT(joined.ok());  // EDEADLK: a thread joining itself
  state_->joinable = false;
}

const RealtimeThreadInfo& RealtimeThread::info() const noexcept {
  GRIP_ASSERT(state_ != nullptr);
  return state_->info;
}

}  // namespace grip::platform
