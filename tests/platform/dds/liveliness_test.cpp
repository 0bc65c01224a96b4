// A reader notices when the writer's participant goes away.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
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

}  // namespace
}  // namespace grip::platform::dds
