#pragma once
// A child process for tests that need a second process (a DDS peer, the grip command): spawned
// from an argument list, killed and reaped when it goes out of scope, so that a failed
// assertion never leaves it running.

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

extern char** environ;

namespace grip::testing {

class ChildProcess {
 public:
  // argv[0] is the program's path. Empty when posix_spawn fails.
  static std::optional<ChildProcess> spawn(std::vector<std::string> argv) {
    std::vector<char*> pointers;
    for (std::string& a : argv) pointers.push_back(a.data());
    pointers.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, pointers[0], nullptr, nullptr, pointers.data(), environ) != 0) {
      return std::nullopt;
    }
    return ChildProcess(pid);
  }
  ChildProcess(ChildProcess&& other) noexcept : pid_(std::exchange(other.pid_, 0)) {}
  ChildProcess& operator=(ChildProcess&&) = delete;
  ~ChildProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }

  void kill(int signal) const { ::kill(pid_, signal); }
  // Waits for the exit; the raw waitpid status.
  int wait() {
    int status = 0;
    waitpid(std::exchange(pid_, 0), &status, 0);
    return status;
  }

 private:
  explicit ChildProcess(pid_t pid) : pid_(pid) {}
  pid_t pid_;
};

}  // namespace grip::testing
