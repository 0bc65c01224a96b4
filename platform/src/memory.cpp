#include "grip/platform/memory.hpp"

#include <alloca.h>
#include <linux/capability.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <string>

#include "grip/common/assert.hpp"
#include "grip/platform/os_call.hpp"
#include "grip/platform/proc_files.hpp"
#include "privileges.hpp"

namespace grip::platform {

MemoryLockOutcome lock_process_memory() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // The sanitizers intercept mlockall and return 0 without locking (their shadow memory is far
  // too large to lock): say so rather than report a lock that does not exist.
  return MemoryLockOutcome{false,
                           "mlockall: not available under a sanitizer (intercepted as a "
                           "no-op)"};
#endif
  const auto locked = os_call("mlockall", [] { return ::mlockall(MCL_CURRENT | MCL_FUTURE); });
  if (locked.ok()) return MemoryLockOutcome{true, {}};
  const bool cap_ipc_lock = detail::has_effective_capability(CAP_IPC_LOCK);
  const std::string limit = detail::rlimit_text(detail::soft_rlimit(RLIMIT_MEMLOCK));
  std::string why;
  switch (locked.error) {
    case ENOMEM:
      why = cap_ipc_lock ? "CAP_IPC_LOCK is present, so the memory itself ran out (a memory "
                           "cgroup limit or the machine's RAM)"
                         : "RLIMIT_MEMLOCK is " + limit +
                               " bytes, less than the process maps, and no CAP_IPC_LOCK";
      break;
    case EPERM:
      why = "no CAP_IPC_LOCK and RLIMIT_MEMLOCK is " + limit + " bytes";
      break;
    case EAGAIN:
      why = "some or all of the memory could not be locked";
      break;
    default:
      return MemoryLockOutcome{false, "mlockall: " + describe_errno(locked.error)};
  }
  return MemoryLockOutcome{false,
                           "mlockall: " + std::string(errno_name(locked.error)) + " (" + why + ")"};
}

void prefer_huge_pages(char** argv) noexcept {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  (void)argv;
#else
  try {
    constexpr const char* kTunables = "GLIBC_TUNABLES";
    constexpr const char* kHugePages = "glibc.malloc.hugetlb";
    const char* set = std::getenv(kTunables);
    const std::string before = set != nullptr ? set : "";
    if (before.find(kHugePages) != std::string::npos) return;
    const auto mode = detail::read_small_file("/sys/kernel/mm/transparent_hugepage/enabled");
    if (!mode || mode.value().find("[never]") != std::string::npos) return;
    const std::string after = (before.empty() ? "" : before + ":") + kHugePages + "=1";
    if (::setenv(kTunables, after.c_str(), 1) != 0) return;
    // By its path, so that the process keeps its name (ps, top, pgrep and systemd show the
    // file's name, which /proc/self/exe would make "exe"); by /proc/self/exe when the file has
    // gone since (replaced by an upgrade).
    char self[PATH_MAX];
    const ssize_t length = ::readlink("/proc/self/exe", self, sizeof self - 1);
    if (length > 0) {
      self[length] = '\0';
      ::execv(self, argv);
    }
    ::execv("/proc/self/exe", argv);
    // Still here: go on as started, with the environment as it was.
    if (set != nullptr) {
      ::setenv(kTunables, before.c_str(), 1);
    } else {
      ::unsetenv(kTunables);
    }
  } catch (...) {
    // Out of memory at start-up: go on without huge pages.
  }
#endif
}

// Out of line, so that the alloca'd block is released when it returns. The writes go through a
// volatile pointer: the compiler may not drop them although nothing reads the block.
__attribute__((noinline)) void prefault_stack(std::size_t bytes) noexcept {
  if (bytes == 0) return;
  constexpr std::size_t kStride = 4096;  // no larger than any page size
  auto* block = static_cast<volatile unsigned char*>(alloca(bytes));
  // From the top (nearest the current frame) down, the order in which a stack grows.
  for (std::size_t offset = bytes; offset > 0;) {
    offset = offset > kStride ? offset - kStride : 0;
    block[offset] = 0;
  }
  block[bytes - 1] = 0;
}

ThreadUsage thread_usage() noexcept {
  rusage usage{};
  const auto got = os_call("getrusage", [&] { return ::getrusage(RUSAGE_THREAD, &usage); });
  GRIP_ASSERT(got.ok());  // fails only for a bad pointer or `who`
  return ThreadUsage{
      static_cast<std::uint64_t>(usage.ru_minflt),
      static_cast<std::uint64_t>(usage.ru_majflt),
      static_cast<std::uint64_t>(usage.ru_nvcsw),
      static_cast<std::uint64_t>(usage.ru_nivcsw),
  };
}

}  // namespace grip::platform
