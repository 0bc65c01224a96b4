#include "grip/rt/triple_buffer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <type_traits>

#include "grip/memory/fixed_vector.hpp"
#include "grip/platform/alloc_counter.hpp"
#include "grip/rt/latency_histogram.hpp"

namespace grip::rt {
namespace {

// A snapshot whose fields must always agree: a torn read shows up as unequal fields.
struct Snapshot {
  std::array<std::uint64_t, 64> fields{};

  static Snapshot filled(std::uint64_t value) {
    Snapshot s;
    s.fields.fill(value);
    return s;
  }
  [[nodiscard]] bool consistent() const {
    return std::ranges::all_of(fields, [this](std::uint64_t f) { return f == fields[0]; });
  }
};

using Buffer = TripleBuffer<Snapshot>;

static_assert(!std::is_copy_constructible_v<Buffer> && !std::is_move_constructible_v<Buffer>);
static_assert(std::is_nothrow_default_constructible_v<Buffer>);

class TripleBufferTest : public ::testing::Test {
 protected:
  Buffer buffer_;
};

TEST_F(TripleBufferTest, ReaderSeesNothingBeforeTheFirstPublish) {
  // GIVEN a buffer nobody has published to
  // WHEN the reader looks
  Snapshot out = Snapshot::filled(7);
  const bool updated = buffer_.update();
  const bool read = buffer_.read(out);

  // THEN there is nothing new, the copy target is untouched and the read buffer is T{}
  EXPECT_FALSE(updated);
  EXPECT_FALSE(read);
  EXPECT_EQ(out.fields[0], 7U);
  EXPECT_EQ(buffer_.read_sequence(), 0U);
  EXPECT_EQ(buffer_.read_buffer().fields[0], 0U);
  EXPECT_EQ(buffer_.skipped(), 0U);
  EXPECT_EQ(buffer_.published(), 0U);
}

TEST_F(TripleBufferTest, FreshSaysWhetherUpdateWouldTakeASnapshotWithoutTakingIt) {
  EXPECT_FALSE(buffer_.fresh());
  buffer_.write(Snapshot::filled(1));
  // Looking does not take: still fresh, and update() then takes it.
  EXPECT_TRUE(buffer_.fresh());
  EXPECT_TRUE(buffer_.fresh());
  ASSERT_TRUE(buffer_.update());
  EXPECT_EQ(buffer_.read_buffer().fields[0], 1U);
  EXPECT_FALSE(buffer_.fresh());
  EXPECT_FALSE(buffer_.update());
}

TEST_F(TripleBufferTest, ReaderTakesTheLatestOfSeveralPublishes) {
  // GIVEN three snapshots published before the reader looks
  buffer_.write(Snapshot::filled(1));
  buffer_.write(Snapshot::filled(2));
  buffer_.write(Snapshot::filled(3));
  EXPECT_EQ(buffer_.published(), 3U);

  // WHEN the reader updates
  ASSERT_TRUE(buffer_.update());

  // THEN it holds the last one, knows its sequence number and that two were skipped
  EXPECT_EQ(buffer_.read_buffer().fields[0], 3U);
  EXPECT_TRUE(buffer_.read_buffer().consistent());
  EXPECT_EQ(buffer_.read_sequence(), 3U);
  EXPECT_EQ(buffer_.skipped(), 2U);

  // AND a second update finds nothing new and keeps the same snapshot
  EXPECT_FALSE(buffer_.update());
  EXPECT_EQ(buffer_.read_buffer().fields[0], 3U);
  EXPECT_EQ(buffer_.read_sequence(), 3U);
}

TEST_F(TripleBufferTest, ReadCopiesOnlyWhenSomethingNewArrived) {
  Snapshot out;
  buffer_.write(Snapshot::filled(5));
  ASSERT_TRUE(buffer_.read(out));
  EXPECT_EQ(out.fields[63], 5U);

  // GIVEN nothing published since
  out = Snapshot::filled(0);
  // WHEN reading again THEN false, and the copy target is untouched
  EXPECT_FALSE(buffer_.read(out));
  EXPECT_EQ(out.fields[63], 0U);

  buffer_.write(Snapshot::filled(6));
  ASSERT_TRUE(buffer_.read(out));
  EXPECT_EQ(out.fields[63], 6U);
  EXPECT_EQ(buffer_.read_sequence(), 2U);
  EXPECT_EQ(buffer_.skipped(), 0U);
}

TEST_F(TripleBufferTest, ZeroCopyWriteAndReadHandOverTheSameSnapshot) {
  // GIVEN a snapshot filled in place
  Snapshot& slot = buffer_.write_buffer();
  slot.fields.fill(11);

  // WHEN it is published and the reader updates
  buffer_.publish();
  ASSERT_TRUE(buffer_.update());

  // THEN the reader sees it in place, and the writer now fills a different slot
  EXPECT_EQ(&buffer_.read_buffer(), &slot);
  EXPECT_EQ(buffer_.read_buffer().fields[17], 11U);
  EXPECT_NE(&buffer_.write_buffer(), &buffer_.read_buffer());
}

TEST_F(TripleBufferTest, WriterAndReaderNeverShareASlot) {
  // GIVEN any interleaving of publishes and updates (a fixed pseudo-random one)
  std::uint32_t lcg = 12345;
  for (std::uint64_t step = 0; step < 10'000; ++step) {
    lcg = lcg * 1664525U + 1013904223U;
    if (((lcg >> 16) & 1U) != 0) {
      buffer_.write(Snapshot::filled(step));
    } else {
      buffer_.update();
    }
    // THEN the writer's slot is never the reader's, and the reader's snapshot stays whole
    ASSERT_NE(&buffer_.write_buffer(), &buffer_.read_buffer()) << "step " << step;
    ASSERT_TRUE(buffer_.read_buffer().consistent());
  }
  // AND the reader accounts for every publication up to the one it holds
  EXPECT_LE(buffer_.skipped(), buffer_.read_sequence());
}

// The plan hand-off: a move-only, fixed-capacity T works through the zero-copy calls.
struct Step {
  double x_m = 0.0;
  double y_m = 0.0;
};

TEST(TripleBufferOfAPlan, CarriesAFixedVectorWithoutCopying) {
  auto buffer = std::make_unique<TripleBuffer<FixedVector<Step, 300>>>();

  // GIVEN a plan of 300 steps built in the write buffer
  FixedVector<Step, 300>& plan = buffer->write_buffer();
  plan.clear();
  for (std::size_t i = 0; i < 300; ++i) {
    ASSERT_TRUE(plan.push_back(Step{static_cast<double>(i), 1.0}));
  }

  // WHEN it is published and taken
  buffer->publish();
  ASSERT_TRUE(buffer->update());

  // THEN the reader sees every step
  const FixedVector<Step, 300>& taken = buffer->read_buffer();
  ASSERT_EQ(taken.size(), 300U);
  EXPECT_DOUBLE_EQ(taken[299].x_m, 299.0);
  EXPECT_EQ(buffer->read_sequence(), 1U);
}

TEST(TripleBufferOfStatistics, HandsOverALatencyHistogramCopy) {
  // GIVEN a histogram recorded on one side and written by copy
  auto buffer = std::make_unique<TripleBuffer<LatencyHistogram>>();
  LatencyHistogram recorded;
  recorded.record(1000);
  recorded.record(3000);
  buffer->write(recorded);

  // WHEN the reader copies it out
  auto out = std::make_unique<LatencyHistogram>();
  ASSERT_TRUE(buffer->read(*out));

  // THEN it is the same histogram
  EXPECT_EQ(out->count(), 2U);
  EXPECT_EQ(out->min(), 1000);
  EXPECT_EQ(out->max(), 3000);
}

TEST(TripleBufferConcurrency, ReaderNeverSeesATornSnapshotOrGoesBackwards) {
  // GIVEN a writer thread publishing snapshots whose fields all equal their sequence number
  constexpr std::uint64_t kPublications = 200'000;
  auto buffer = std::make_unique<Buffer>();
  std::thread writer([&buffer] {
    for (std::uint64_t seq = 1; seq <= kPublications; ++seq) {
      Snapshot& s = buffer->write_buffer();
      s.fields.fill(seq);
      buffer->publish();
    }
  });

  // WHEN a reader keeps taking the newest snapshot until it has the last one
  std::uint64_t torn = 0;
  std::uint64_t wrong_sequence = 0;
  std::uint64_t backwards = 0;
  std::uint64_t takes = 0;
  std::uint64_t last = 0;
  while (last < kPublications) {
    if (!buffer->update()) {
      std::this_thread::yield();
      continue;
    }
    ++takes;
    const Snapshot& s = buffer->read_buffer();
    if (!s.consistent()) {
      ++torn;
    }
    if (s.fields[0] != buffer->read_sequence()) {
      ++wrong_sequence;
    }
    if (buffer->read_sequence() <= last) {
      ++backwards;
    }
    last = buffer->read_sequence();
  }
  writer.join();

  // THEN every snapshot was whole, labelled with its own sequence, and strictly newer
  EXPECT_EQ(torn, 0U);
  EXPECT_EQ(wrong_sequence, 0U);
  EXPECT_EQ(backwards, 0U);
  EXPECT_EQ(last, kPublications);
  EXPECT_EQ(buffer->skipped() + takes, kPublications);
  EXPECT_FALSE(buffer->update());
}

// Counting allocations needs the real allocator; sanitizers replace it.
#if GRIP_ALLOC_COUNTER_INTERPOSE
TEST_F(TripleBufferTest, WritingAndReadingNeverTouchTheHeap) {
  ASSERT_TRUE(alloc_counter::interposed())
      << "the allocation counter is not interposed, so this test would prove nothing";

  // GIVEN an armed allocation counter
  Snapshot out;
  alloc_counter::arm();

  // WHEN snapshots are written, published, updated and read in every form
  for (std::uint64_t i = 1; i <= 1000; ++i) {
    buffer_.write(Snapshot::filled(i));
    buffer_.write_buffer().fields.fill(i);
    buffer_.publish();
    buffer_.update();
    buffer_.read(out);
  }
  alloc_counter::disarm();

  // THEN nothing was allocated or freed
  EXPECT_EQ(alloc_counter::counts().allocations, 0U);
  EXPECT_EQ(alloc_counter::counts().deallocations, 0U);
  EXPECT_EQ(buffer_.read_sequence(), 2000U);
}
#endif

}  // namespace
}  // namespace grip::rt
