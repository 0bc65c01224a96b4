#pragma once
// What machine a run ran on, for its report: a figure means little without the kernel and the
// CPUs behind it. Start-up and report time only: it allocates.

#include <string>

namespace grip::platform {

struct MachineDescription {
  std::string hostname;
  std::string kernel;        // "Linux 6.1.0-18-amd64" (uname: system and release)
  std::string kernel_build;  // uname's version: "#1 SMP PREEMPT_DYNAMIC Debian ..."
  std::string architecture;  // "x86_64"
  std::string cpu_model;     // /proc/cpuinfo's first "model name"; "" where there is none
  int online_cpus = 0;
};

MachineDescription describe_machine();

}  // namespace grip::platform
