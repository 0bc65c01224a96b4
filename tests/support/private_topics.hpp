#pragma once
// Topic names of this test process alone: every DDS test builds its topic names with a prefix
// unique to the process (as link/topics.hpp's TopicNames does: "<prefix>_grip_plan"; give
// private_topic_prefix() to TopicNames::create or a participant's topic_prefix), so that two
// test runs at once (two ctest runs, another worktree's, a `grip` run on the same domain) never
// deliver a sample to each other even where their domains coincide.
//
// A child process the test spawns (a probe standing in for the other side) uses its parent's
// prefix: the prefix is put into the environment (GRIP_TEST_TOPIC_PREFIX) when the test
// process starts, and a process whose parent made the prefix takes it from there.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <string_view>

namespace grip::testing {

namespace detail {

inline std::string make_private_topic_prefix() {
  constexpr const char* kVariable = "GRIP_TEST_TOPIC_PREFIX";
  // "t<pid>_<random>": the parent's, when it made the one in our environment.
  if (const char* inherited = std::getenv(kVariable); inherited != nullptr) {
    const std::string value = inherited;
    char parent[32];
    std::snprintf(parent, sizeof parent, "t%ld_", static_cast<long>(getppid()));
    if (value.starts_with(parent)) return value;
  }
  std::random_device entropy;
  char prefix[48];
  std::snprintf(prefix, sizeof prefix, "t%ld_%08x", static_cast<long>(getpid()),
                static_cast<unsigned>(entropy()));
  setenv(kVariable, prefix, 1);
  return prefix;
}

// Made when the test process starts, before any child is spawned.
inline const std::string kPrivateTopicPrefix = make_private_topic_prefix();

}  // namespace detail

// This process's topic prefix (a valid link::check_topic_prefix one).
inline const std::string& private_topic_prefix() { return detail::kPrivateTopicPrefix; }

// The name of the contract topic `base` ("grip_plan", link::kPlanTopic) under that prefix.
inline std::string private_topic(std::string_view base) {
  return private_topic_prefix() + "_" + std::string(base);
}

}  // namespace grip::testing
