#pragma once
// Runs the `grip` command as users run it (or any command line), capturing its exit status and
// output.

#include <sys/wait.h>

#include <cstdio>
#include <string>

#include "test_paths.hpp"

namespace grip::testing {

inline const std::string kGrip = GRIP_BINARY_DIR "/bin/grip";

struct CommandRun {
  int status;          // the exit status, -1 when it did not exit normally
  std::string output;  // stdout and stderr (see run_grip's streams)
};

// Runs a shell command line; what it writes to stdout is captured (redirect stderr into it in
// the line to capture that too).
inline CommandRun run_command(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, "popen failed"};
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// `streams` redirects the command's output: the default captures stdout and stderr; "2>/dev/null"
// stdout alone; "2>&1 >/dev/null" stderr alone.
inline CommandRun run_grip(const std::string& arguments, const std::string& streams = "2>&1") {
  return run_command(kGrip + " " + arguments + " " + streams);
}

}  // namespace grip::testing
