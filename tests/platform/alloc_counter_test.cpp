#include "grip/platform/alloc_counter.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include "grip/memory/fixed_vector.hpp"
#include "grip/memory/indexed_min_heap.hpp"
#include "grip/memory/object_pool.hpp"

namespace grip {
namespace {

// Sanitizers own malloc, so interposition cannot work there (see alloc_counter.hpp).
constexpr bool kSanitizerBuild = GRIP_ALLOC_COUNTER_INTERPOSE == 0;

TEST(AllocCounter, InterposesMallocExceptUnderSanitizers) {
  if constexpr (kSanitizerBuild) {
    EXPECT_FALSE(alloc_counter::interposed())
        << "a sanitizer build must report that its own malloc wins";
  } else {
    EXPECT_TRUE(alloc_counter::interposed())
        << "grip_alloc_counter is linked but its malloc is not the one the process calls: it "
           "must be a SHARED library linked into the executable, ahead of any other allocator";
  }
}

// The counting tests exist only where counting is possible: a sanitizer build has nothing to
// count with (checked above), and the unsanitized CI build runs them.
#if GRIP_ALLOC_COUNTER_INTERPOSE
// Stores through a volatile pointer so that the compiler cannot elide an allocation whose
// result is otherwise unused (C++14 allows new/delete pairs to be elided).
void* volatile g_sink = nullptr;
void escape(void* p) { g_sink = p; }

class AllocCounterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(alloc_counter::interposed())
        << "the allocation counter is not interposed, so these tests would prove nothing";
  }
  void TearDown() override { alloc_counter::disarm(); }
};

TEST_F(AllocCounterTest, CountsMallocAndFree) {
  alloc_counter::arm();
  void* p = std::malloc(64);
  escape(p);
  const alloc_counter::Counts after_malloc = alloc_counter::counts();
  std::free(p);
  const alloc_counter::Counts after_free = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_EQ(after_malloc.allocations, 1U);
  EXPECT_EQ(after_malloc.deallocations, 0U);
  EXPECT_EQ(after_free.allocations, 1U);
  EXPECT_EQ(after_free.deallocations, 1U);
}

TEST_F(AllocCounterTest, CountsNewAndDelete) {
  alloc_counter::arm();
  int* p = new int(42);
  escape(p);
  const alloc_counter::Counts after_new = alloc_counter::counts();
  delete p;
  int* a = new int[10];
  escape(a);
  delete[] a;
  const alloc_counter::Counts after_all = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_EQ(after_new.allocations, 1U);
  EXPECT_EQ(after_all.allocations, 2U);
  EXPECT_EQ(after_all.deallocations, 2U);
}

TEST_F(AllocCounterTest, CountsAlignedAndNothrowNew) {
  struct alignas(64) Block {
    double values[8];
  };
  alloc_counter::arm();
  Block* b = new Block;
  escape(b);
  delete b;
  int* n = new (std::nothrow) int(1);
  escape(n);
  delete n;
  const alloc_counter::Counts c = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_EQ(c.allocations, 2U);
  EXPECT_EQ(c.deallocations, 2U);
}

TEST_F(AllocCounterTest, CountsAVectorThatAllocates) {
  alloc_counter::arm();
  {
    std::vector<int> v(100);
    escape(v.data());
  }
  const alloc_counter::Counts c = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_GE(c.allocations, 1U);
  EXPECT_GE(c.deallocations, 1U);
}

TEST_F(AllocCounterTest, CountsCallocReallocAndAlignedAllocations) {
  alloc_counter::arm();
  void* c = std::calloc(4, 16);
  escape(c);
  const std::uint64_t after_calloc = alloc_counter::counts().allocations;
  void* r = std::realloc(c, 4096);  // a move: one allocation and one deallocation
  escape(r);
  const alloc_counter::Counts after_realloc = alloc_counter::counts();
  std::free(r);
  void* fresh = std::realloc(nullptr, 32);  // realloc of null allocates
  escape(fresh);
  std::free(fresh);
  void* aligned = std::aligned_alloc(64, 128);
  escape(aligned);
  std::free(aligned);
  void* posix = nullptr;
  const int status = posix_memalign(&posix, 64, 128);
  escape(posix);
  std::free(posix);
  const alloc_counter::Counts total = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_EQ(after_calloc, 1U);
  EXPECT_EQ(after_realloc.allocations, 2U);
  EXPECT_EQ(after_realloc.deallocations, 1U);
  EXPECT_EQ(status, 0);
  EXPECT_EQ(total.allocations, 5U);
  EXPECT_EQ(total.deallocations, 5U);
}

TEST_F(AllocCounterTest, FreeingNullIsNotCounted) {
  g_sink = nullptr;
  alloc_counter::arm();
  std::free(nullptr);
  delete static_cast<int*>(g_sink);
  const alloc_counter::Counts c = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_EQ(c.deallocations, 0U);
}

TEST_F(AllocCounterTest, CountsNothingWhileDisarmed) {
  alloc_counter::arm();
  alloc_counter::disarm();
  void* p = std::malloc(64);
  escape(p);
  std::free(p);
  auto owned = std::make_unique<int>(3);
  escape(owned.get());
  owned.reset();

  const alloc_counter::Counts c = alloc_counter::counts();
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
}

TEST_F(AllocCounterTest, ArmResetsTheCounts) {
  alloc_counter::arm();
  escape(new int(1));
  delete static_cast<int*>(g_sink);
  alloc_counter::arm();
  const alloc_counter::Counts c = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
}

TEST_F(AllocCounterTest, PureArithmeticCountsZero) {
  volatile double seed = 0.5;
  alloc_counter::arm();
  double x = seed;
  for (int i = 0; i < 100000; ++i) {
    x = 3.9 * x * (1.0 - x);  // the logistic map: arithmetic only
  }
  const alloc_counter::Counts c = alloc_counter::counts();
  alloc_counter::disarm();

  EXPECT_GE(x, 0.0);
  EXPECT_LE(x, 1.0);
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
}

TEST_F(AllocCounterTest, AnotherThreadsAllocationsDoNotLeakIntoThisThread) {
  // GIVEN a worker thread, created before arming (creating a thread allocates)
  std::atomic<int> phase{0};  // 0: wait, 1: go, 2: done
  std::atomic<std::uint64_t> worker_allocations{0};
  std::thread worker([&] {
    while (phase.load() != 1) {
      std::this_thread::yield();
    }
    alloc_counter::arm();
    for (int i = 0; i < 50; ++i) {
      void* p = std::malloc(128);
      escape(p);
      std::free(p);
    }
    worker_allocations = alloc_counter::counts().allocations;
    alloc_counter::disarm();
    phase.store(2);
  });
  const std::uint64_t process_before = alloc_counter::process_counts().allocations;

  // WHEN this thread is armed while the worker allocates
  alloc_counter::arm();
  phase.store(1);
  while (phase.load() != 2) {
    std::this_thread::yield();
  }
  const alloc_counter::Counts mine = alloc_counter::counts();
  alloc_counter::disarm();
  worker.join();

  // THEN the worker counted its own allocations, this thread counted none, and the
  // process-wide total saw the worker's
  EXPECT_EQ(worker_allocations.load(), 50U);
  EXPECT_EQ(mine.allocations, 0U);
  EXPECT_EQ(mine.deallocations, 0U);
  EXPECT_GE(alloc_counter::process_counts().allocations - process_before, 50U);
}

// The promise of grip/memory, checked with the counter: all memory is taken at construction.
TEST_F(AllocCounterTest, FixedMemoryContainersDoNotAllocateAfterConstruction) {
  // GIVEN containers constructed (and allocated) before arming
  struct Record {
    std::uint32_t next;
    double cost_s;
  };
  FixedVector<int, 32> fixed;
  BoundedVector<Record> bounded(32);
  ObjectPool<Record> pool(32);
  IndexedMinHeap heap(32);

  // WHEN they are filled past capacity, emptied and reused while armed
  alloc_counter::arm();
  for (int round = 0; round < 3; ++round) {
    for (std::uint32_t i = 0; i < 40; ++i) {
      static_cast<void>(fixed.push_back(static_cast<int>(i)));
      static_cast<void>(bounded.emplace_back(Record{i, 1.0}));
      const auto h = pool.acquire();
      if (h != ObjectPool<Record>::kInvalid) {
        static_cast<void>(heap.push(h, static_cast<double>(i % 7)));
      }
    }
    while (!heap.empty()) {
      pool.release(heap.pop());
    }
    fixed.clear();
    bounded.truncate(0);
    pool.clear();
  }
  const alloc_counter::Counts c = alloc_counter::counts();
  alloc_counter::disarm();

  // THEN none of it touched the heap
  EXPECT_EQ(c.allocations, 0U);
  EXPECT_EQ(c.deallocations, 0U);
  EXPECT_EQ(pool.high_water_mark(), 32U);
}

#endif  // unsanitized builds

}  // namespace
}  // namespace grip
