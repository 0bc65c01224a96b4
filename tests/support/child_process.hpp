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
  // argv[0] is the program's path. The child's environment is ours, changed by `environment`:
  // "NAME=value" sets NAME, "NAME" unsets it. Empty when posix_spawn fails.
  static std::optional<ChildProcess> spawn(std::vector<std::string> argv,
                                           const std::vector<std::string>& environment = {}) {
    std::vector<char*> pointers;
    for (std::string& a : argv) pointers.push_back(a.data());
    pointers.push_back(nullptr);
    std::vector<std::string> variables;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string variable = *e;
      const std::string name = variable.substr(0, variable.find('='));
      bool changed = false;
      for (const std::string& c : environment) changed |= c.substr(0, c.find('=')) == name;
      if (!changed) variables.push_back(variable);
    }
    for (const std::string& c : environment) {
      if (c.find('=') != std::string::npos) variables.push_back(c);
    }
    std::vector<char*> envp;
    for (std::string& v : variables) envp.push_back(v.data());
    envp.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, pointers[0], nullptr, nullptr, pointers.data(), envp.data()) != 0) {
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
