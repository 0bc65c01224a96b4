// Topic names: unchanged without a prefix, "<prefix>_<name>" with one, and a prefix that is not
// a plain identifier of at most 64 characters is refused naming it.

#include "grip/link/topics.hpp"

#include <gtest/gtest.h>

#include <string>

namespace grip::link {
namespace {

// Every name of `names` is `start` followed by the contract's own name.
void expect_names_start_with(const TopicNames& names, const std::string& start) {
  EXPECT_EQ(names.vehicle_state, start + "grip_vehicle_state");
  EXPECT_EQ(names.plan, start + "grip_plan");
  EXPECT_EQ(names.map_update, start + "grip_map_update");
  EXPECT_EQ(names.map_request, start + "grip_map_request");
  EXPECT_EQ(names.goal, start + "grip_goal");
  EXPECT_EQ(names.planner_status, start + "grip_planner_status");
  EXPECT_EQ(names.vehicle_description, start + "grip_vehicle_description");
  EXPECT_EQ(names.of(kPlanTopic), start + "grip_plan");
}

TEST(TopicNames, WithoutAPrefixTheNamesAreTheContractsOwn) {
  expect_names_start_with(TopicNames::create("").value(), "");
}

TEST(TopicNames, APrefixIsPutBeforeEveryName) {
  expect_names_start_with(TopicNames::create("rover_2").value(), "rover_2_");
}

TEST(TopicNames, APrefixOf64CharactersIsTheLongestAccepted) {
  EXPECT_TRUE(TopicNames::create(std::string(64, 'a')).ok());
  const Status longer = check_topic_prefix(std::string(65, 'a'));
  ASSERT_FALSE(longer.ok());
  EXPECT_EQ(longer.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(longer.error().message.find("longer than 64 characters"), std::string::npos);
}

TEST(TopicNames, APrefixThatIsNotAnIdentifierIsRefusedNamingIt) {
  for (const char* bad : {"1a", "_a", "a-b", "a b", "a/b", "a.b", "\xc3\xa9t\xc3\xa9"}) {
    const Result<TopicNames> names = TopicNames::create(bad);
    ASSERT_FALSE(names.ok()) << bad;
    EXPECT_EQ(names.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(names.error().message.find(std::string("\"") + bad + "\""), std::string::npos)
        << names.error().message;
  }
  EXPECT_NE(check_topic_prefix("1a").error().message.find("must start with a letter"),
            std::string::npos);
  EXPECT_NE(check_topic_prefix("a-b").error().message.find("letters, digits and '_'"),
            std::string::npos);
  EXPECT_TRUE(check_topic_prefix("A9_z").ok());
}

}  // namespace
}  // namespace grip::link
