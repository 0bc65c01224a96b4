// A reader notices when the writer's participant goes away, and tells which writer went.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/platform/dds/writer_liveliness.hpp"
#include "private_topics.hpp"
#include "vehicle_state.h"

namespace grip::platform::dds {
namespace {

using namespace std::chrono_literals;

TEST(DdsLiveliness, ReaderNoticesWriterParticipantDeleted) {
  constexpr DomainId kDomain = 54;
  Qos qos;
  qos.history_depth = 1;
  qos.liveliness_lease = 500ms;
  qos.deadline = 1s;

  Result<Participant> writer_side = Participant::create(kDomain);
  ASSERT_TRUE(writer_side.ok()) << writer_side.error().message;
  Result<Participant> reader_side = Participant::create(kDomain);
  ASSERT_TRUE(reader_side.ok()) << reader_side.error().message;
  auto reader = Reader<grip_msg_VehicleState>::create(
      *reader_side, &grip_msg_VehicleState_desc,
      ::grip::testing::private_topic("grip_vehicle_state"), qos);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto writer = Writer<grip_msg_VehicleState>::create(
      *writer_side, &grip_msg_VehicleState_desc,
      ::grip::testing::private_topic("grip_vehicle_state"), qos);
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  ASSERT_TRUE(reader->wait_for_writers(1, 5s).ok());

  grip_msg_VehicleState state{};
  state.kind = grip_msg_DD_VELOCITY;
  state.state_dim = 3;
  ASSERT_TRUE(writer->write(state).ok());

  // The writer is alive once it has written (automatic liveliness).
  const auto alive_deadline = std::chrono::steady_clock::now() + 5s;
  std::uint32_t alive = 0;
  while (std::chrono::steady_clock::now() < alive_deadline) {
    auto status = reader->liveliness_changed();
    ASSERT_TRUE(status.ok()) << status.error().message;
    alive = status->alive_count;
    if (alive > 0) break;
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_EQ(alive, 1U);

  // Delete the writer's participant (its writer and topic go with it); the Writer object
  // outlives it and must still destruct cleanly.
  ASSERT_TRUE(writer_side->reset().ok());

  const auto lost_deadline = std::chrono::steady_clock::now() + 5s;
  bool noticed = false;
  while (!noticed && std::chrono::steady_clock::now() < lost_deadline) {
    auto liveliness = reader->liveliness_changed();
    auto matched = reader->subscription_matched();
    ASSERT_TRUE(liveliness.ok() && matched.ok());
    noticed = liveliness->alive_count == 0 && matched->current_count == 0;
    if (!noticed) std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(noticed) << "reader did not notice the writer's loss within 5 s";
}

// Two writers on one topic: only the loss of the watched one makes it lost.
TEST(DdsLiveliness, TheWatchedWriterIsLostOnlyWhenItGoesNotWhenAnotherDoes) {
  constexpr DomainId kDomain = 55;
  Qos qos;
  qos.history_depth = 4;
  qos.liveliness_lease = 500ms;
  const std::string topic = ::grip::testing::private_topic("grip_vehicle_state");
  Result<Participant> reader_side = Participant::create(kDomain);
  ASSERT_TRUE(reader_side.ok()) << reader_side.error().message;
  auto reader =
      Reader<grip_msg_VehicleState>::create(*reader_side, &grip_msg_VehicleState_desc, topic, qos);
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto watcher = WriterLiveliness::attach(reader->get());
  ASSERT_TRUE(watcher.ok()) << watcher.error().message;
  EXPECT_TRUE((*watcher)->alive()) << "nothing watched yet";

  Result<Participant> watched_side = Participant::create(kDomain);
  Result<Participant> other_side = Participant::create(kDomain);
  ASSERT_TRUE(watched_side.ok() && other_side.ok());
  auto watched =
      Writer<grip_msg_VehicleState>::create(*watched_side, &grip_msg_VehicleState_desc, topic, qos);
  auto other =
      Writer<grip_msg_VehicleState>::create(*other_side, &grip_msg_VehicleState_desc, topic, qos);
  ASSERT_TRUE(watched.ok() && other.ok());
  ASSERT_TRUE(reader->wait_for_writers(2, 5s).ok());

  // The watched writer's handle, as a vehicle learns it: from the sample it sent.
  grip_msg_VehicleState state{};
  state.kind = grip_msg_DD_VELOCITY;
  state.state_dim = 3;
  state.sequence_number = 7;
  ASSERT_TRUE(watched->write(state).ok());
  SampleBuffer<grip_msg_VehicleState, 4> buffer(&grip_msg_VehicleState_desc);
  dds_instance_handle_t handle = 0;
  const auto until = std::chrono::steady_clock::now() + 5s;
  while (handle == 0 && std::chrono::steady_clock::now() < until) {
    auto taken = reader->take(buffer);
    ASSERT_TRUE(taken.ok());
    for (std::size_t i = 0; i < *taken; ++i) {
      if (buffer[i].sequence_number == 7) handle = buffer.info(i).publication_handle;
    }
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_NE(handle, 0U) << "the watched writer's sample never arrived";
  (*watcher)->watch(handle);

  const auto gone = [&](Result<Participant>& side) {
    ASSERT_TRUE(side->reset().ok());
    const auto deadline = std::chrono::steady_clock::now() + 5s;
    while (std::chrono::steady_clock::now() < deadline) {
      auto matched = reader->subscription_matched();
      ASSERT_TRUE(matched.ok());
      if (matched->current_count < (&side == &other_side ? 2U : 1U)) return;
      std::this_thread::sleep_for(5ms);
    }
    FAIL() << "the reader never noticed a writer leave";
  };
  gone(other_side);
  std::this_thread::sleep_for(100ms);  // any listener call about it has run
  EXPECT_TRUE((*watcher)->alive()) << "another writer's loss marked the watched one lost";
  gone(watched_side);
  const auto lost_deadline = std::chrono::steady_clock::now() + 5s;
  while ((*watcher)->alive() && std::chrono::steady_clock::now() < lost_deadline) {
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_FALSE((*watcher)->alive()) << "the watched writer left and is still alive";
}

}  // namespace
}  // namespace grip::platform::dds
