#pragma once
// Counts heap allocations made by the calling thread, to prove that a real-time loop does not
// touch the heap after start-up: arm() before the cycle, counts() after it, expect zero.
//
// How: glibc removed __malloc_hook (2.34), so the library `grip_alloc_counter` interposes at
// link time instead. It is a shared library that defines malloc, calloc, realloc, reallocarray,
// free, aligned_alloc, posix_memalign, memalign, valloc, pvalloc and every global operator
// new / new[] / delete / delete[] (plain, sized, aligned, nothrow). Linking it into an executable
// (target_link_libraries) puts it before libc and libstdc++ in the dynamic linker's symbol
// lookup order, exactly as LD_PRELOAD would (it can also be LD_PRELOADed into any binary), so
// every call from the executable and from every shared library, libc's own internal callers such
// as strdup or fopen included, reaches these definitions. They count and forward to glibc's
// allocator through its exported entry points (__libc_malloc, __libc_free, __libc_memalign, ...),
// not through dlsym, which can itself allocate.
//
// Counting is per thread and only while armed. The per-thread state is a `thread_local` with the
// initial-exec TLS model, so reaching it never calls into the allocator (a lazily allocated TLS
// block would recurse into malloc).
//
// What it does not see: memory obtained with mmap/brk directly, and allocations glibc makes
// through internal, non-interposable paths. Under AddressSanitizer or ThreadSanitizer the
// sanitizer's own malloc must win, so the library is built without its interposers: it still
// links, counts() stays zero and interposed() returns false. Check interposed() before trusting
// a zero.

#include <cstdint>

// 1 when this build interposes the allocator and can count; 0 under a sanitizer, whose own
// malloc must own every block (GCC announces one with __SANITIZE_*__, clang only through
// __has_feature). Tests that count allocations compile only where this is 1.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define GRIP_ALLOC_COUNTER_INTERPOSE 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define GRIP_ALLOC_COUNTER_INTERPOSE 0
#endif
#endif
#ifndef GRIP_ALLOC_COUNTER_INTERPOSE
#define GRIP_ALLOC_COUNTER_INTERPOSE 1
#endif

namespace grip::alloc_counter {

struct Counts {
  std::uint64_t allocations;    // successful or not: every call that asks the heap for memory
  std::uint64_t deallocations;  // every release of a non-null pointer
};

// True iff this library's allocator is the one the process actually calls (probed with a real
// malloc/free). False under ASan/TSan, or when the library is linked but overridden by another
// allocator earlier in the lookup order.
bool interposed() noexcept;

// Resets the calling thread's counts to zero and starts counting its allocations.
void arm() noexcept;

// Stops counting for the calling thread; counts() keeps the values reached.
void disarm() noexcept;

// The calling thread's counts since its last arm(). realloc of a non-null pointer to a non-zero
// size counts as one allocation and one deallocation; realloc(p, 0) as one deallocation.
Counts counts() noexcept;

// Allocations and deallocations made by any thread while that thread was armed, since the
// process started. Never reset: take differences. Costs one relaxed atomic add per counted
// event, and counted events are what an armed thread should never produce.
Counts process_counts() noexcept;

}  // namespace grip::alloc_counter
