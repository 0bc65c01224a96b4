// Link-time interposition of the C and C++ allocation functions; see alloc_counter.hpp.
//
// Rules for everything in this file, because it runs inside malloc:
//  - never allocate (no std::string, no iostream, no dlsym): forward to glibc's __libc_* entry
//    points, which are exported for exactly this use;
//  - touch only initial-exec TLS and lock-free atomics, both usable before main() and in
//    threads that are just starting.

#include "grip/platform/alloc_counter.hpp"

#include <malloc.h>  // memalign, valloc, pvalloc

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

// The sanitizers bring their own malloc and must own every block; our definitions would lose
// the symbol lookup to theirs anyway, and any we defined that they do not would hand them blocks
// from glibc. There GRIP_ALLOC_COUNTER_INTERPOSE (alloc_counter.hpp) is 0: no interposers, and
// interposed() reports false.

namespace {

enum class Mode : std::uint8_t { kOff, kArmed, kProbing };

struct ThreadState {
  Mode mode;
  bool probe_hit;
  std::uint64_t allocations;
  std::uint64_t deallocations;
};

// initial-exec: the variable lives in the static TLS block set up with the thread, so reaching
// it is a fixed offset from the thread pointer and never calls __tls_get_addr (which may
// allocate). constinit and a trivial type: no lazy initialisation, no destructor registration.
[[gnu::tls_model("initial-exec")]] constinit thread_local ThreadState t_state{};  // kOff, zeros

constinit std::atomic<std::uint64_t> g_allocations{0};
constinit std::atomic<std::uint64_t> g_deallocations{0};

static_assert(std::atomic<std::uint64_t>::is_always_lock_free);

[[maybe_unused]] inline void count_allocation() noexcept {
  ThreadState& state = t_state;
  if (state.mode == Mode::kOff) {
    return;
  }
  if (state.mode == Mode::kArmed) {
    ++state.allocations;
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  } else {
    state.probe_hit = true;
  }
}

[[maybe_unused]] inline void count_deallocation() noexcept {
  ThreadState& state = t_state;
  if (state.mode == Mode::kArmed) {
    ++state.deallocations;
    g_deallocations.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace

namespace grip::alloc_counter {

bool interposed() noexcept {
  const ThreadState saved = t_state;
  t_state = ThreadState{Mode::kProbing, false, 0, 0};
  // Through volatile pointers: the compiler may neither elide the pair nor bind the call to a
  // definition in this file. &std::malloc resolves, like any call, to the first definition in
  // the lookup order: ours when interposition works.
  void* (*volatile do_malloc)(std::size_t) = &std::malloc;
  void (*volatile do_free)(void*) = &std::free;
  do_free(do_malloc(16));
  const bool hit = t_state.probe_hit;
  t_state = saved;
  return hit;
}

void arm() noexcept { t_state = ThreadState{Mode::kArmed, false, 0, 0}; }

void disarm() noexcept { t_state.mode = Mode::kOff; }

Counts counts() noexcept { return Counts{t_state.allocations, t_state.deallocations}; }

Counts process_counts() noexcept {
  return Counts{g_allocations.load(std::memory_order_relaxed),
                g_deallocations.load(std::memory_order_relaxed)};
}

}  // namespace grip::alloc_counter

#if GRIP_ALLOC_COUNTER_INTERPOSE

// glibc's allocator proper, exported under these names (GLIBC_2.2.5) for interposers.
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t count, std::size_t size) noexcept;
void* __libc_realloc(void* pointer, std::size_t size) noexcept;
void __libc_free(void* pointer) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void* __libc_valloc(std::size_t size) noexcept;
void* __libc_pvalloc(std::size_t size) noexcept;
}

#define GRIP_INTERPOSE __attribute__((visibility("default")))

// ---- C allocation functions (declared by <cstdlib> and <malloc.h>) ----

extern "C" {

GRIP_INTERPOSE void* malloc(std::size_t size) noexcept {
  count_allocation();
  return __libc_malloc(size);
}

GRIP_INTERPOSE void* calloc(std::size_t count, std::size_t size) noexcept {
  count_allocation();
  return __libc_calloc(count, size);
}

GRIP_INTERPOSE void* realloc(void* pointer, std::size_t size) noexcept {
  if (pointer == nullptr) {
    count_allocation();
  } else if (size == 0) {
    count_deallocation();  // glibc frees and returns null
  } else {
    count_allocation();
    count_deallocation();
  }
  return __libc_realloc(pointer, size);
}

GRIP_INTERPOSE void* reallocarray(void* pointer, std::size_t count, std::size_t size) noexcept {
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(count, size, &bytes)) {
    errno = ENOMEM;
    return nullptr;
  }
  return realloc(pointer, bytes);
}

GRIP_INTERPOSE void free(void* pointer) noexcept {
  if (pointer != nullptr) {
    count_deallocation();
  }
  __libc_free(pointer);
}

// glibc's aligned_alloc and memalign are the same function.
GRIP_INTERPOSE void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  count_allocation();
  return __libc_memalign(alignment, size);
}

GRIP_INTERPOSE void* memalign(std::size_t alignment, std::size_t size) noexcept {
  count_allocation();
  return __libc_memalign(alignment, size);
}

GRIP_INTERPOSE int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  count_allocation();
  // A power of two and a multiple of sizeof(void*); errno is left untouched, as POSIX asks.
  if (alignment < sizeof(void*) || (alignment & (alignment - 1)) != 0) {
    return EINVAL;
  }
  const int saved_errno = errno;
  void* pointer = __libc_memalign(alignment, size);
  errno = saved_errno;
  if (pointer == nullptr) {
    return ENOMEM;
  }
  *out = pointer;
  return 0;
}

GRIP_INTERPOSE void* valloc(std::size_t size) noexcept {
  count_allocation();
  return __libc_valloc(size);
}

GRIP_INTERPOSE void* pvalloc(std::size_t size) noexcept {
  count_allocation();
  return __libc_pvalloc(size);
}

}  // extern "C"

// ---- C++ global operator new / delete (every replaceable form) ----

namespace {

// The throwing forms: retry through the new_handler, then throw, as [new.delete.single] says.
// One call counts once, however many retries it takes.
void* allocate_or_throw(std::size_t size, std::size_t alignment) {
  count_allocation();
  if (size == 0) {
    size = 1;
  }
  for (;;) {
    void* pointer = alignment == 0 ? __libc_malloc(size) : __libc_memalign(alignment, size);
    if (pointer != nullptr) {
      return pointer;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) {
      throw std::bad_alloc();
    }
    handler();
  }
}

void* allocate_or_null(std::size_t size, std::size_t alignment) noexcept {
  try {
    return allocate_or_throw(size, alignment);
  } catch (...) {
    return nullptr;
  }
}

void deallocate(void* pointer) noexcept {
  if (pointer != nullptr) {
    count_deallocation();
  }
  __libc_free(pointer);
}

std::size_t to_size(std::align_val_t alignment) noexcept {
  return static_cast<std::size_t>(alignment);
}

}  // namespace

GRIP_INTERPOSE void* operator new(std::size_t size) { return allocate_or_throw(size, 0); }
GRIP_INTERPOSE void* operator new[](std::size_t size) { return allocate_or_throw(size, 0); }
GRIP_INTERPOSE void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return allocate_or_null(size, 0);
}
GRIP_INTERPOSE void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return allocate_or_null(size, 0);
}
GRIP_INTERPOSE void* operator new(std::size_t size, std::align_val_t alignment) {
  return allocate_or_throw(size, to_size(alignment));
}
GRIP_INTERPOSE void* operator new[](std::size_t size, std::align_val_t alignment) {
  return allocate_or_throw(size, to_size(alignment));
}
GRIP_INTERPOSE void* operator new(std::size_t size, std::align_val_t alignment,
                                  const std::nothrow_t&) noexcept {
  return allocate_or_null(size, to_size(alignment));
}
GRIP_INTERPOSE void* operator new[](std::size_t size, std::align_val_t alignment,
                                    const std::nothrow_t&) noexcept {
  return allocate_or_null(size, to_size(alignment));
}

GRIP_INTERPOSE void operator delete(void* pointer) noexcept { deallocate(pointer); }
GRIP_INTERPOSE void operator delete[](void* pointer) noexcept { deallocate(pointer); }
GRIP_INTERPOSE void operator delete(void* pointer, const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete[](void* pointer, const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete(void* pointer, std::size_t) noexcept { deallocate(pointer); }
GRIP_INTERPOSE void operator delete[](void* pointer, std::size_t) noexcept { deallocate(pointer); }
GRIP_INTERPOSE void operator delete(void* pointer, std::align_val_t) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete[](void* pointer, std::align_val_t) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete(void* pointer, std::size_t, std::align_val_t) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete[](void* pointer, std::size_t, std::align_val_t) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete(void* pointer, std::align_val_t,
                                    const std::nothrow_t&) noexcept {
  deallocate(pointer);
}
GRIP_INTERPOSE void operator delete[](void* pointer, std::align_val_t,
                                      const std::nothrow_t&) noexcept {
  deallocate(pointer);
}

#endif  // GRIP_ALLOC_COUNTER_INTERPOSE
