#pragma once
// The planner participant's threads, in one table: what each is called (top -H, ps -L, gdb), the
// policy it asks for and its priority. Service threads start at creation, before the planning
// thread, which under SCHED_DEADLINE could not create them. None is pinned to a CPU: the kernel
// refuses SCHED_DEADLINE to a thread whose affinity is a subset of the CPUs it balances over.

#include "grip/platform/scheduling.hpp"

namespace grip::rt::dds {

struct ParticipantThread {
  const char* name;  // at most 15 characters
  platform::PolicyRequest policy;
  int fifo_priority;  // for kFifo; 0 otherwise
};

// Waits on the readers, validates every sample, keeps the map in sync and hands over tiles,
// states and goals (receive_side.hpp).
inline constexpr ParticipantThread kReceiveThread{"grip-receive", platform::PolicyRequest::kOther,
                                                  0};
// One replanning cycle per period (rt::PeriodicLoop); its policy is the configuration's
// (PlannerParticipantConfig::policy: SCHED_DEADLINE, else FIFO, else OTHER). Never calls DDS.
inline constexpr ParticipantThread kPlanningThread{"grip-planner", platform::PolicyRequest::kAuto,
                                                   0};
// Writes plans and status (publish_side.hpp). A plan is worth most when fresh: a low FIFO
// priority where the machine grants one, so that it is not queued behind ordinary work;
// refused (no CAP_SYS_NICE), it stays SCHED_OTHER and the report says so.
inline constexpr ParticipantThread kPublishThread{"grip-publish", platform::PolicyRequest::kFifo,
                                                  10};
// Chooses frontier targets while exploring in real time (rt::ExplorationDriver): wavefronts
// over the known space, milliseconds, beside the planning thread.
inline constexpr ParticipantThread kTargetThread{"grip-target", platform::PolicyRequest::kOther, 0};

}  // namespace grip::rt::dds
