// Map synchronisation never silently diverges: over a lossy channel, every loss is seen as a
// gap, a snapshot heals it, and the receiver's map then equals the sender's cell for cell.

#include "grip/link/map_sync.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "grip/common/random.hpp"

namespace grip::link {
namespace {

OccupancyGrid unknown_map(int w = 300, int h = 300) {
  return OccupancyGrid::create(w, h, 0.1, -1.0, 2.0, Cell::kUnknown).value();
}

// What a subscriber holds equals what the publisher holds.
void expect_equal_maps(const OccupancyGrid& a, const OccupancyGrid& b) {
  ASSERT_EQ(geometry_of(a), geometry_of(b));
  EXPECT_TRUE(std::equal(a.cells().begin(), a.cells().end(), b.cells().begin()));
  EXPECT_EQ(map_checksum(a), map_checksum(b));
}

// A random rectangle of random value, as a sensor sweep or an appearing obstacle would write.
CellBox scribble(OccupancyGrid& map, Random& rng) {
  const int x0 = static_cast<int>(rng.below(280));
  const int y0 = static_cast<int>(rng.below(280));
  const CellBox box{x0, y0, x0 + static_cast<int>(rng.below(20)),
                    y0 + static_cast<int>(rng.below(20))};
  const Cell value = static_cast<Cell>(rng.below(3));
  for (int y = box.y0; y <= box.y1; ++y)
    for (int x = box.x0; x <= box.x1; ++x) map.set(x, y, value);
  return box;
}

TEST(MapSync, ChecksumTellsMapsApart) {
  OccupancyGrid a = unknown_map();
  OccupancyGrid b = unknown_map();
  EXPECT_EQ(map_checksum(a), map_checksum(b));
  b.set(299, 299, Cell::kFree);
  EXPECT_NE(map_checksum(a), map_checksum(b));
}

TEST(MapSync, AChecksumKeptByTheCellsWrittenEqualsTheWholeMapsAfterEveryWrite) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    Random rng(seed);
    OccupancyGrid map = unknown_map();
    std::uint64_t kept = map_checksum(map);
    for (int write = 0; write < 50; ++write) {
      // Out with the cells a write may touch, in with them after: what the planner does per tile.
      const int x0 = static_cast<int>(rng.below(280));
      const int y0 = static_cast<int>(rng.below(280));
      const CellBox box{x0, y0, x0 + static_cast<int>(rng.below(20)),
                        y0 + static_cast<int>(rng.below(20))};
      kept ^= cells_checksum(map, box);
      for (int y = box.y0; y <= box.y1; ++y)
        for (int x = box.x0; x <= box.x1; ++x) map.set(x, y, static_cast<Cell>(rng.below(3)));
      kept ^= cells_checksum(map, box);
      ASSERT_EQ(kept, map_checksum(map)) << "after write " << write;
    }
  }
}

TEST(MapSync, FirstUpdateAsksForASnapshotWhichSyncs) {
  MapSender sender(unknown_map());
  MapReceiver receiver(1U << 20);
  Random rng(3);
  const CellBox box = scribble(sender.map(), rng);
  sender.send_updates(
      box, 1, [&](const grip_msg_MapUpdate& m) { EXPECT_TRUE(receiver.apply(m).verdict.ok()); });
  ASSERT_TRUE(receiver.has_map());
  EXPECT_FALSE(receiver.in_sync());  // it has seen one patch, not the map
  EXPECT_TRUE(receiver.should_request(0, 1000));
  receiver.note_requested(0);
  EXPECT_FALSE(receiver.should_request(999, 1000));
  EXPECT_TRUE(receiver.should_request(1000, 1000));  // asks again while nothing heals

  bool synced = false;
  sender.send_snapshot(2, [&](const grip_msg_MapUpdate& m) {
    EXPECT_LE(m.width_cells * m.height_cells, static_cast<std::uint32_t>(grip_msg_kMaxPatchCells));
    const MapApplied applied = receiver.apply(m);
    synced = synced || applied.synced;
    EXPECT_FALSE(applied.healed);  // a first sync is not a heal
  });
  EXPECT_TRUE(synced);
  EXPECT_TRUE(receiver.in_sync());
  EXPECT_EQ(receiver.gaps(), 0U);
  expect_equal_maps(receiver.map(), sender.map());
  EXPECT_EQ(sender.snapshots_sent(), 1U);
}

TEST(MapSync, AGapInsideASnapshotDoesNotHeal) {
  MapSender sender(unknown_map());
  MapReceiver receiver(1U << 20);
  int part = 0;
  sender.send_snapshot(1, [&](const grip_msg_MapUpdate& m) {
    if (part++ != 2) receiver.apply(m);  // part 2 of 4 lost
  });
  EXPECT_EQ(part, 4);
  EXPECT_FALSE(receiver.in_sync());
  EXPECT_EQ(receiver.gaps(), 1U);
  sender.send_snapshot(2, [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  EXPECT_TRUE(receiver.in_sync());
  EXPECT_EQ(receiver.heals(), 1U);
}

TEST(MapSync, LossyChannelIsHealedAndMapsEndEqual) {
  MapSender sender(unknown_map());
  MapReceiver receiver(1U << 20);
  Random rng(11);
  Random loss(12);
  std::uint64_t dropped = 0;
  bool diverged_while_in_sync = false;
  const auto lossy = [&](const grip_msg_MapUpdate& m) {
    if (loss.below(100) < 20) {
      ++dropped;
      return;
    }
    EXPECT_TRUE(receiver.apply(m).verdict.ok());
  };
  for (int step = 0; step < 400; ++step) {
    sender.send_updates(scribble(sender.map(), rng), static_cast<std::uint64_t>(step), lossy);
    if (receiver.should_request(step, 5)) {
      receiver.note_requested(step);
      sender.send_snapshot(static_cast<std::uint64_t>(step), lossy);
    }
    // In sync means equal, once the receiver has seen the sender's last update (a loss of the
    // very last one shows as a gap only when the next arrives).
    if (receiver.in_sync() && receiver.last_sequence() == sender.last_sequence() &&
        map_checksum(receiver.map()) != map_checksum(sender.map())) {
      diverged_while_in_sync = true;
    }
  }
  // The link recovers: no more loss; the receiver's request is answered.
  sender.send_updates(scribble(sender.map(), rng), 401,
                      [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  if (receiver.should_request(1000, 5)) {
    sender.send_snapshot(1000, [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  }
  EXPECT_GT(dropped, 50U);
  EXPECT_GT(receiver.gaps(), 10U);
  EXPECT_GT(receiver.heals(), 5U);
  EXPECT_FALSE(diverged_while_in_sync);
  ASSERT_TRUE(receiver.in_sync());
  expect_equal_maps(receiver.map(), sender.map());
}

TEST(MapSync, ARestartedPublisherIsAGapAndHeals) {
  MapSender first(unknown_map());
  MapReceiver receiver(1U << 20);
  first.send_snapshot(1, [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  Random rng(5);
  for (int i = 0; i < 20; ++i)
    first.send_updates(scribble(first.map(), rng), 2,
                       [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  ASSERT_TRUE(receiver.in_sync());

  MapSender second(unknown_map());  // numbers from 1 again, with a different map
  second.send_updates(scribble(second.map(), rng), 3,
                      [&](const grip_msg_MapUpdate& m) { EXPECT_TRUE(receiver.apply(m).gap); });
  EXPECT_FALSE(receiver.in_sync());
  second.send_snapshot(4, [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  EXPECT_TRUE(receiver.in_sync());
  expect_equal_maps(receiver.map(), second.map());
}

TEST(MapSync, RejectedUpdatesChangeNothing) {
  MapSender sender(unknown_map());
  MapReceiver receiver(1U << 20);
  sender.send_snapshot(1, [&](const grip_msg_MapUpdate& m) { receiver.apply(m); });
  const std::uint64_t before = map_checksum(receiver.map());
  grip_msg_MapUpdate bad{};
  sender.send_updates(CellBox{0, 0, 9, 9}, 2, [&](const grip_msg_MapUpdate& m) { bad = m; });
  std::vector<std::uint8_t> cells(100, 1);
  bad.cells._buffer = cells.data();
  bad.cells._length = 99;  // wrong length
  EXPECT_EQ(receiver.apply(bad).verdict.reason, Rejection::kWrongLength);
  bad.cells._length = 100;
  bad.origin_x_cell = 295;  // off the map
  EXPECT_EQ(receiver.apply(bad).verdict.reason, Rejection::kPatchOutsideMap);
  EXPECT_EQ(map_checksum(receiver.map()), before);
  EXPECT_TRUE(receiver.in_sync());  // a rejected sample is not a gap: its number was not used
}

TEST(MapSync, TooLargeAMapIsRefused) {
  MapSender sender(unknown_map());
  MapReceiver receiver(10'000);  // smaller than 300 x 300
  sender.send_snapshot(1, [&](const grip_msg_MapUpdate& m) {
    EXPECT_EQ(receiver.apply(m).verdict.reason, Rejection::kMapTooLarge);
  });
  EXPECT_FALSE(receiver.has_map());
}

}  // namespace
}  // namespace grip::link
