// Participant creation with the loopback configuration, error paths and entity ownership.

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "goal.h"
#include "grip/platform/dds/entity.hpp"
#include "grip/platform/dds/error.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "private_topics.hpp"

namespace grip::platform::dds {
namespace {

TEST(DdsParticipant, EmbeddedConfigIsLoopbackOnly) {
  const std::string_view config = loopback_config();
  EXPECT_NE(config.find("<AllowMulticast>false</AllowMulticast>"), std::string_view::npos);
  EXPECT_NE(config.find("<NetworkInterface name=\"lo\"/>"), std::string_view::npos);
  EXPECT_NE(config.find("<Peer address=\"127.0.0.1\"/>"), std::string_view::npos);
  // Nothing in it names an address outside the loopback range.
  EXPECT_EQ(config.find("address=\""), config.find("address=\"127."));
}

TEST(DdsParticipant, CreateAndDestroyWithDefaultConfig) {
  for (int round = 0; round < 3; ++round) {
    Result<Participant> participant = Participant::create(55);
    ASSERT_TRUE(participant.ok()) << participant.error().message;
    EXPECT_GT(participant->get(), 0);
    EXPECT_EQ(participant->domain(), 55U);
    dds_domainid_t domain = 0;
    ASSERT_TRUE(check(dds_get_domainid(participant->get(), &domain), "dds_get_domainid").ok());
    EXPECT_EQ(domain, 55U);
  }
}

TEST(DdsParticipant, ExplicitXmlConfigIsAccepted) {
  Result<Participant> participant = Participant::create(56, std::string(loopback_config()));
  ASSERT_TRUE(participant.ok()) << participant.error().message;
}

TEST(DdsParticipant, MalformedConfigIsAnError) {
  Result<Participant> participant =
      Participant::create(57, "<CycloneDDS><Domain><General><NoSuchElement/></General></Domain>");
  EXPECT_FALSE(participant.ok());
}

TEST(DdsParticipant, DefaultDomainIdIsRejected) {
  Result<Participant> participant = Participant::create(DDS_DOMAIN_DEFAULT);
  ASSERT_FALSE(participant.ok());
  EXPECT_EQ(participant.error().code, ErrorCode::kInvalidArgument);
}

TEST(DdsErrors, EmptyTopicNameIsAnErrorNamingTheReturnCode) {
  Result<Participant> participant = Participant::create(58);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  auto reader = Reader<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc, "", Qos{});
  ASSERT_FALSE(reader.ok());
  EXPECT_NE(reader.error().message.find("dds_create_topic"), std::string::npos)
      << reader.error().message;
  EXPECT_NE(reader.error().message.find(dds_strretcode(DDS_RETCODE_BAD_PARAMETER)),
            std::string::npos)
      << reader.error().message;
  EXPECT_EQ(reader.error().code, ErrorCode::kInvalidArgument);
}

TEST(DdsErrors, InvalidQosIsRejectedBeforeDds) {
  Result<Participant> participant = Participant::create(58);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  Qos qos;
  qos.history_depth = 0;
  auto writer = Writer<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc,
                                              ::grip::testing::private_topic("grip_goal"), qos);
  ASSERT_FALSE(writer.ok());
  EXPECT_NE(writer.error().message.find("history_depth"), std::string::npos);
}

TEST(DdsErrors, CheckMapsCodesAndKeepsTheText) {
  EXPECT_TRUE(check(DDS_RETCODE_OK, "x").ok());
  EXPECT_TRUE(check(5, "x").ok());
  Status status = check(DDS_RETCODE_TIMEOUT, "dds_write");
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().code, ErrorCode::kIo);
  EXPECT_NE(status.error().message.find("dds_write"), std::string::npos);
  EXPECT_NE(status.error().message.find(dds_strretcode(DDS_RETCODE_TIMEOUT)), std::string::npos);
  EXPECT_EQ(check(DDS_RETCODE_OUT_OF_RESOURCES, "x").error().code, ErrorCode::kCapacity);
  DdsError raw = make_dds_error(DDS_RETCODE_BAD_PARAMETER, "dds_take");
  EXPECT_EQ(raw.code, DDS_RETCODE_BAD_PARAMETER);
}

TEST(DdsEntity, DoubleDeleteIsHarmless) {
  Result<Participant> participant = Participant::create(59);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  Entity topic(dds_create_topic(participant->get(), &grip_msg_Goal_desc,
                                ::grip::testing::private_topic("grip_goal").c_str(), nullptr,
                                nullptr));
  ASSERT_TRUE(topic.valid());
  const dds_entity_t handle = topic.get();
  EXPECT_TRUE(topic.reset().ok());
  EXPECT_FALSE(topic.valid());
  EXPECT_TRUE(topic.reset().ok());  // nothing left to delete
  // Someone else deleting the same handle again: Cyclone reports it, the Entity would not.
  EXPECT_LT(dds_delete(handle), 0);
  Entity stale(handle);
  EXPECT_TRUE(stale.reset().ok());
}

TEST(DdsEntity, ChildrenOutlivingTheirParticipantDestructCleanly) {
  Result<Participant> participant = Participant::create(60);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  auto reader = Reader<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc,
                                              ::grip::testing::private_topic("grip_goal"), Qos{});
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  auto writer = Writer<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc,
                                              ::grip::testing::private_topic("grip_goal"), Qos{});
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  ASSERT_TRUE(participant->reset().ok());  // deletes topic, reader and writer with it
  // The reader's handle is gone: calls report an error instead of crashing.
  EXPECT_FALSE(reader->subscription_matched().ok());
  grip_msg_Goal goal{};
  EXPECT_FALSE(writer->write(goal).ok());
  // Reader and writer destructors run at scope exit: dds_delete on dead handles is fine.
}

TEST(DdsEntity, MoveTransfersOwnership) {
  Result<Participant> participant = Participant::create(61);
  ASSERT_TRUE(participant.ok()) << participant.error().message;
  Entity a(dds_create_topic(participant->get(), &grip_msg_Goal_desc,
                            ::grip::testing::private_topic("grip_goal").c_str(), nullptr, nullptr));
  const dds_entity_t handle = a.get();
  Entity b(std::move(a));
  EXPECT_FALSE(a.valid());  // NOLINT(bugprone-use-after-move)
  EXPECT_EQ(b.get(), handle);
  Entity c;
  c = std::move(b);
  EXPECT_EQ(c.get(), handle);
  EXPECT_TRUE(c.reset().ok());
}

}  // namespace
}  // namespace grip::platform::dds
