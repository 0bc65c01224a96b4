#pragma once
// The panic path for broken invariants (never for operational errors, which are returned).
// Active in every build type: a broken invariant in a planner that drives a vehicle must stop
// the process loudly, not continue on corrupted state.

#include <cstdio>
#include <cstdlib>

namespace grip::detail {
[[noreturn]] inline void panic(const char* expr, const char* file, int line) noexcept {
  std::fprintf(stderr, "grip: invariant violated: %s (%s:%d)\n", expr, file, line);
  std::abort();
}
}  // namespace grip::detail

#define GRIP_ASSERT(expr) \
  ((expr) ? static_cast<void>(0) : ::grip::detail::panic(#expr, __FILE__, __LINE__))
