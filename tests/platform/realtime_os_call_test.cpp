#include "grip/platform/os_call.hpp"

#include <dirent.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>

namespace grip::platform {
namespace {

TEST(RealtimeOsCall, CapturesErrnoOfAFailedCall) {
  const auto closed = os_call("close", [] { return ::close(-1); });
  EXPECT_FALSE(closed.ok());
  EXPECT_EQ(closed.value, -1);
  EXPECT_EQ(closed.error, EBADF);
  EXPECT_EQ(closed.error_name(), "EBADF");
  EXPECT_EQ(closed.describe(), "close: EBADF (Bad file descriptor)");
}

TEST(RealtimeOsCall, ASucceedingCallIsOkWithItsValue) {
  const auto pid = os_call("getpid", [] { return ::getpid(); });
  EXPECT_TRUE(pid.ok());
  EXPECT_EQ(pid.value, ::getpid());
  EXPECT_EQ(pid.error, 0);
}

TEST(RealtimeOsCall, MinusOneWithoutErrnoIsAValueNotAFailure) {
  // getpriority legitimately returns -1 for nice -1; os_call clears errno first.
  const auto priority = os_call("getpriority", [] {
    errno = 0;
    return -1;  // stands in for a call whose -1 is a value and leaves errno alone
  });
  EXPECT_TRUE(priority.ok());
}

TEST(RealtimeOsCall, PthreadStyleCallsReturnTheirErrorNumber) {
  const auto joined = os_call_returning_error(
      "pthread_join", [] { return ::pthread_join(::pthread_self(), nullptr); });
  EXPECT_FALSE(joined.ok());
  EXPECT_EQ(joined.error, EDEADLK);
  EXPECT_EQ(joined.describe(), "pthread_join: EDEADLK (Resource deadlock avoided)");
}

TEST(RealtimeOsCall, PointerCallsDistinguishFailureFromTheEnd) {
  const auto missing = os_call_pointer("opendir", [] { return ::opendir("/nonexistent/grip"); });
  EXPECT_FALSE(missing.ok());
  EXPECT_EQ(missing.error, ENOENT);

  const auto opened = os_call_pointer("opendir", [] { return ::opendir("/proc/self/task"); });
  ASSERT_TRUE(opened.ok());
  int entries = 0;
  while (true) {
    const auto entry = os_call_pointer("readdir", [&] { return ::readdir(opened.value); });
    ASSERT_TRUE(entry.ok()) << entry.describe();
    if (entry.value == nullptr) break;  // the end: ok, null
    ++entries;
  }
  EXPECT_GE(entries, 3);  // ".", ".." and this thread
  closedir(opened.value);
}

TEST(RealtimeOsCall, UnknownErrorNumbersHaveAName) {
  EXPECT_EQ(errno_name(4242), "unknown errno");
  EXPECT_EQ(errno_description(4242), "unknown error");
  EXPECT_EQ(describe_errno(EPERM), "EPERM (Operation not permitted)");
}

}  // namespace
}  // namespace grip::platform
