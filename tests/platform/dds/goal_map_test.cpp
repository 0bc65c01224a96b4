// A Goal and a MapUpdate with a 64x64 patch round-trip between two participants.

#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

#include "goal.h"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "map_update.h"
#include "private_topics.hpp"

namespace grip::platform::dds {
namespace {

using namespace std::chrono_literals;

Qos reliable_qos() {
  Qos qos;
  qos.history_depth = 8;
  qos.max_blocking_time = 100ms;
  return qos;
}

// Takes until one valid sample is in buffer[0] or 5 s pass.
template <typename T, std::size_t N>
std::size_t take_one(Reader<T>& reader, SampleBuffer<T, N>& buffer) {
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (std::chrono::steady_clock::now() < deadline) {
    Result<std::size_t> taken = reader.take(buffer);
    if (!taken.ok()) return 0;
    if (*taken > 0) return *taken;
    std::this_thread::sleep_for(1ms);
  }
  return 0;
}

TEST(DdsGoalMap, GoalRoundTrips) {
  constexpr DomainId kDomain = 52;
  Result<Participant> a = Participant::create(kDomain);
  ASSERT_TRUE(a.ok()) << a.error().message;
  Result<Participant> b = Participant::create(kDomain);
  ASSERT_TRUE(b.ok()) << b.error().message;
  auto reader = Reader<grip_msg_Goal>::create(
      *b, &grip_msg_Goal_desc, ::grip::testing::private_topic("grip_goal"), reliable_qos());
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto writer = Writer<grip_msg_Goal>::create(
      *a, &grip_msg_Goal_desc, ::grip::testing::private_topic("grip_goal"), reliable_qos());
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, 5s).ok());

  grip_msg_Goal goal{};
  goal.sequence_number = 7;
  goal.stamp_ns = 123456789;
  goal.x_m = 12.5;
  goal.y_m = -3.25;
  goal.radius_m = 0.75;
  ASSERT_TRUE(writer->write(goal).ok());

  SampleBuffer<grip_msg_Goal, 4> buffer(&grip_msg_Goal_desc);
  ASSERT_EQ(take_one(*reader, buffer), 1U);
  EXPECT_EQ(buffer[0].sequence_number, 7U);
  EXPECT_EQ(buffer[0].stamp_ns, 123456789U);
  EXPECT_EQ(buffer[0].x_m, 12.5);
  EXPECT_EQ(buffer[0].y_m, -3.25);
  EXPECT_EQ(buffer[0].radius_m, 0.75);
}

TEST(DdsGoalMap, MapUpdateWith64x64PatchRoundTrips) {
  constexpr DomainId kDomain = 53;
  Result<Participant> a = Participant::create(kDomain);
  ASSERT_TRUE(a.ok()) << a.error().message;
  Result<Participant> b = Participant::create(kDomain);
  ASSERT_TRUE(b.ok()) << b.error().message;
  auto reader = Reader<grip_msg_MapUpdate>::create(
      *b, &grip_msg_MapUpdate_desc, ::grip::testing::private_topic("grip_map_update"),
      reliable_qos());
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto writer = Writer<grip_msg_MapUpdate>::create(
      *a, &grip_msg_MapUpdate_desc, ::grip::testing::private_topic("grip_map_update"),
      reliable_qos());
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, 5s).ok());

  constexpr std::uint32_t kSide = 64;
  std::vector<std::uint8_t> cells(kSide * kSide);
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<std::uint8_t>((i * 7) % 3);

  grip_msg_MapUpdate update{};
  update.sequence_number = 42;
  update.stamp_ns = 99;
  update.origin_x_cell = 10;
  update.origin_y_cell = 4;
  update.map_width_cells = 300;
  update.map_height_cells = 200;
  update.map_origin_x_m = -1.5;
  update.width_cells = kSide;
  update.height_cells = kSide;
  update.resolution_m = 0.1;
  update.snapshot_id = 3;
  update.snapshot_part = 1;
  update.snapshot_parts = 2;
  update.cells._buffer = cells.data();
  update.cells._length = static_cast<std::uint32_t>(cells.size());
  update.cells._maximum = static_cast<std::uint32_t>(cells.size());
  update.cells._release = false;
  ASSERT_TRUE(writer->write(update).ok());

  SampleBuffer<grip_msg_MapUpdate, 2> buffer(&grip_msg_MapUpdate_desc);
  ASSERT_EQ(take_one(*reader, buffer), 1U);
  const grip_msg_MapUpdate& got = buffer[0];
  EXPECT_EQ(got.sequence_number, 42U);
  EXPECT_EQ(got.stamp_ns, 99U);
  EXPECT_EQ(got.origin_x_cell, 10U);
  EXPECT_EQ(got.origin_y_cell, 4U);
  EXPECT_EQ(got.map_width_cells, 300U);
  EXPECT_EQ(got.map_height_cells, 200U);
  EXPECT_EQ(got.map_origin_x_m, -1.5);
  EXPECT_EQ(got.width_cells, kSide);
  EXPECT_EQ(got.height_cells, kSide);
  EXPECT_EQ(got.resolution_m, 0.1);
  EXPECT_EQ(got.snapshot_id, 3U);
  EXPECT_EQ(got.snapshot_part, 1U);
  EXPECT_EQ(got.snapshot_parts, 2U);
  ASSERT_EQ(got.cells._length, cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) ASSERT_EQ(got.cells._buffer[i], cells[i]) << i;
}

}  // namespace
}  // namespace grip::platform::dds
