#include "grip/platform/memory.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "grip_command.hpp"

namespace grip::platform {
namespace {

// A field of /proc/self/status, e.g. "CapEff" or "VmLck", as its text.
std::string status_field(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(key + ":", 0) == 0) {
      std::istringstream value(line.substr(key.size() + 1));
      std::string first;
      value >> first;
      return first;
    }
  }
  return {};
}

bool has_effective_capability(int bit) {
  const std::uint64_t mask = std::stoull(status_field("CapEff"), nullptr, 16);
  return (mask >> bit & 1U) != 0;
}

constexpr int kCapIpcLock = 14;

// The sanitizers make mlockall a no-op (see memory.hpp).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitizerBuild = true;
#else
constexpr bool kSanitizerBuild = false;
#endif

TEST(RealtimeMemory, LocksTheProcessWithCapIpcLockOrSaysWhyNot) {
  // WHEN the process memory is locked
  const MemoryLockOutcome outcome = lock_process_memory();

  // THEN with CAP_IPC_LOCK it is (the kernel reports locked pages), otherwise the reason says why
  if (kSanitizerBuild) {
    EXPECT_FALSE(outcome.locked);
    EXPECT_NE(outcome.reason.find("sanitizer"), std::string::npos) << outcome.reason;
  } else if (has_effective_capability(kCapIpcLock)) {
    EXPECT_TRUE(outcome.locked) << outcome.reason;
    EXPECT_EQ(outcome.reason, "");
    EXPECT_GT(std::stoull(status_field("VmLck")), 0U) << "VmLck in /proc/self/status, kB";
    EXPECT_TRUE(lock_process_memory().locked) << "locking twice is harmless";
  } else if (!outcome.locked) {
    EXPECT_EQ(outcome.reason.rfind("mlockall: E", 0), 0U) << outcome.reason;
  }
  munlockall();  // leave the other tests an unlocked process
  EXPECT_EQ(std::stoull(status_field("VmLck")), 0U);
}

TEST(RealtimeMemory, ThreadUsageCountsAMinorFaultOnAFreshPage) {
  munlockall();  // a lock left by another test (MCL_FUTURE) would fault the page in at mmap
  const long page = sysconf(_SC_PAGESIZE);
  void* mapping = mmap(nullptr, static_cast<std::size_t>(page), PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(mapping, MAP_FAILED);

  // GIVEN the usage before the first touch of a fresh anonymous page
  const ThreadUsage before = thread_usage();
  // WHEN the page is written
  *static_cast<volatile char*>(mapping) = 1;
  const ThreadUsage after = thread_usage();

  // THEN the thread took a minor fault for it, and no major one
  EXPECT_GE(after.minor_faults, before.minor_faults + 1);
  EXPECT_EQ(after.major_faults, before.major_faults);
  munmap(mapping, static_cast<std::size_t>(page));
}

TEST(RealtimeMemory, ThreadUsageCountsTheVoluntarySwitchOfASleep) {
  const ThreadUsage before = thread_usage();
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const ThreadUsage after = thread_usage();
  EXPECT_GE(after.voluntary_switches, before.voluntary_switches + 1);
  EXPECT_GE(after.involuntary_switches, before.involuntary_switches);
}

struct PrefaultFaults {
  ThreadUsage start;
  ThreadUsage after_first;
  ThreadUsage after_second;
};

void* prefault_twice(void* argument) {
  auto& faults = *static_cast<PrefaultFaults*>(argument);
  faults.start = thread_usage();
  prefault_stack(1024 * 1024);
  faults.after_first = thread_usage();
  prefault_stack(1024 * 1024);
  faults.after_second = thread_usage();
  return nullptr;
}

// On a stack mapped for this test (glibc reuses the stacks of joined threads, whose pages may
// already be resident).
TEST(RealtimeMemory, PrefaultStackFaultsInAMebibyteOnceAndNotAgain) {
  munlockall();  // with MCL_FUTURE the fresh stack would be resident from the start
  constexpr std::size_t kStackBytes = 2 * 1024 * 1024;
  void* stack = mmap(nullptr, kStackBytes, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS | MAP_STACK, -1, 0);
  ASSERT_NE(stack, MAP_FAILED);
  pthread_attr_t attributes;
  ASSERT_EQ(pthread_attr_init(&attributes), 0);
  ASSERT_EQ(pthread_attr_setstack(&attributes, stack, kStackBytes), 0);
  PrefaultFaults faults{};
  pthread_t thread{};
  ASSERT_EQ(pthread_create(&thread, &attributes, &prefault_twice, &faults), 0);
  ASSERT_EQ(pthread_join(thread, nullptr), 0);
  pthread_attr_destroy(&attributes);
  munmap(stack, kStackBytes);

  // The first call writes pages nobody had touched (so it was not optimised away); the second
  // finds them resident. 1 MiB is 256 pages of 4 KiB; transparent huge pages could make fewer.
  const std::uint64_t first = faults.after_first.minor_faults - faults.start.minor_faults;
  const std::uint64_t second = faults.after_second.minor_faults - faults.after_first.minor_faults;
  std::cout << "prefault_stack(1 MiB) on a fresh stack: " << first << " minor faults, then "
            << second << "\n";
  EXPECT_GE(first, 1U);
  EXPECT_LE(second, 1U);
}

TEST(RealtimeMemory, PrefaultStackOfZeroBytesDoesNothing) {
  const ThreadUsage before = thread_usage();
  prefault_stack(0);
  EXPECT_EQ(thread_usage().major_faults, before.major_faults);
}

// ---- Huge pages: the probe (tests/platform/probe) run with the environment a user might have.

constexpr const char* kHugePagesProbe = GRIP_BINARY_DIR "/bin/grip_huge_pages_probe";

struct ProbeRun {
  std::vector<std::string> started;  // "pid=... argument=..." of every start
  std::string tunables;
  long long anon_huge_kb = -1;
};

ProbeRun run_huge_pages_probe(const std::string& environment) {
  const testing::CommandRun run =
      testing::run_command("env " + environment + " " + kHugePagesProbe + " an-argument 2>&1");
  EXPECT_EQ(run.status, 0) << run.output;
  ProbeRun probe;
  std::istringstream lines(run.output);
  std::string line;
  while (std::getline(lines, line)) {
    // The rest of the line after `key`, when the line starts with it.
    std::string rest;
    const auto after = [&](const std::string& key) {
      if (line.rfind(key, 0) != 0) return false;
      rest = line.substr(key.size());
      return true;
    };
    if (after("GRIP_PROBE started ")) probe.started.push_back(rest);
    if (after("GRIP_PROBE tunables=")) probe.tunables = rest;
    if (after("GRIP_PROBE anon_huge_kb=")) probe.anon_huge_kb = std::stoll(rest);
  }
  return probe;
}

bool machine_offers_huge_pages() {
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text;
  std::getline(mode, text);
  return !text.empty() && text.find("[never]") == std::string::npos;
}

TEST(HugePages, TheProcessStartsAgainOnceAsItWasWithGlibcAskedForHugePages) {
  // GIVEN no glibc tunables, or others than huge pages
  for (const std::string& before : {std::string{}, std::string{"glibc.malloc.perturb=0"}}) {
    const ProbeRun probe =
        run_huge_pages_probe(before.empty() ? "-u GLIBC_TUNABLES" : "GLIBC_TUNABLES=" + before);
    ASSERT_FALSE(probe.started.empty());
    EXPECT_NE(probe.started[0].find(" argument=an-argument"), std::string::npos);
    if (kSanitizerBuild || !machine_offers_huge_pages()) {
      // THEN under a sanitizer, or on a machine without transparent huge pages, nothing changes
      EXPECT_EQ(probe.started.size(), 1U);
      EXPECT_EQ(probe.tunables, before);
      continue;
    }
    // THEN it started again once, the same process with the same name and arguments, the tunable
    // added to the others, and a large block it writes lies in huge pages
    ASSERT_EQ(probe.started.size(), 2U);
    EXPECT_EQ(probe.started[1], probe.started[0]);
    EXPECT_EQ(probe.tunables,
              before.empty() ? "glibc.malloc.hugetlb=1" : before + ":glibc.malloc.hugetlb=1");
    EXPECT_GT(probe.anon_huge_kb, 0);
  }
}

TEST(HugePages, AUsersOwnChoiceIsKept) {
  // GIVEN a user who turned glibc's huge pages off
  const ProbeRun probe = run_huge_pages_probe("GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  // THEN the process is not started again and the choice stands
  EXPECT_EQ(probe.started.size(), 1U);
  EXPECT_EQ(probe.tunables, "glibc.malloc.hugetlb=0");
}

}  // namespace
}  // namespace grip::platform
