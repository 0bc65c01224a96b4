#pragma once
// Child processes of the `grip` command (a planner, ddsperf, exploration runs): spawned from an
// argument list, killed and reaped when they go out of scope, so that an error or Ctrl-C in the
// parent never leaves one running.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <vector>

#include "grip/common/result.hpp"

extern char** environ;

namespace grip::tools {

// A child process, killed and reaped when it goes out of scope.
class Child {
 public:
  // args[0] is looked up in PATH; `env_extra` (NAME=value) comes before the inherited
  // environment; stdout goes to `stdout_path` when given (stderr with it when
  // `with_stderr`).
  static Result<Child> spawn(std::vector<std::string> args,
                             const std::vector<std::string>& env_extra,
                             const std::string& stdout_path, bool with_stderr = false) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_strings(env_extra);
    for (char** e = environ; *e != nullptr; ++e) env_strings.emplace_back(*e);
    std::vector<char*> envp;
    for (auto& e : env_strings) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!stdout_path.empty()) {
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(),
                                       O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (with_stderr) posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    }
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return Error{ErrorCode::kIo, "cannot start " + args[0] + ": " + std::strerror(rc)};
    return Child(pid);
  }
  Child(Child&& other) noexcept : pid_(other.pid_) { other.pid_ = 0; }
  Child& operator=(Child&&) = delete;
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  // Waits for the child to exit by itself; its exit status.
  int wait() {
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = 0;
    return exit_status(status);
  }
  // Its exit status if it has exited (then reaped), else -1; without waiting.
  int poll() {
    if (pid_ <= 0) return -1;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) != pid_) return -1;
    pid_ = 0;
    return exit_status(status);
  }
  // Sends it `signal` (SIGTERM: asks it to stop and report; SIGKILL: a crash).
  void send(int signal) const {
    if (pid_ > 0) kill(pid_, signal);
  }
  bool running() const { return pid_ > 0; }

 private:
  explicit Child(pid_t pid) : pid_(pid) {}
  static int exit_status(int status) {
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  pid_t pid_;
};

// The path of the running executable, to start more of it.
inline Result<std::string> self_executable() {
  char self[4096] = {};
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return Error{ErrorCode::kIo, "cannot find the grip executable (/proc/self/exe)"};
  return std::string(self, static_cast<std::size_t>(n));
}

}  // namespace grip::tools
