#include "private_link.hpp"

#include <unistd.h>

#include <cstdio>
#include <memory>
#include <random>
#include <utility>

#include "goal.h"
#include "grip/link/topics.hpp"
#include "grip/platform/dds/error.hpp"
#include "grip/platform/dds/qos.hpp"
#include "map_update.h"
#include "plan.h"
#include "planner_status.h"
#include "vehicle_description.h"
#include "vehicle_state.h"

namespace grip::tools {

namespace pdds = platform::dds;

ExploreLink choose_explore_link(const ParamsOptions& options, const params::GripParams& p,
                                bool force_private) {
  // The file's link section counts only for where the topics are; its lease does not share.
  const params::LinkParams defaults;
  const bool placed = options.domain.has_value() || options.topic_prefix.has_value() ||
                      p.link.domain != defaults.domain ||
                      p.link.topic_prefix != defaults.topic_prefix ||
                      p.link.dds_config != defaults.dds_config;
  ExploreLink link;
  link.is_private = force_private || !placed;
  if (link.is_private) {
    link.discovery_tag = private_discovery_tag();
    link.dds_config = private_dds_config(link.discovery_tag);
  }
  return link;
}

std::string private_discovery_tag() {
  std::random_device entropy;
  const std::uint64_t bits = (std::uint64_t{entropy()} << 32U) ^ entropy();
  char random_hex[17];
  std::snprintf(random_hex, sizeof random_hex, "%016llx", static_cast<unsigned long long>(bits));
  return "grip-explore-" + std::to_string(getpid()) + "-" + random_hex;
}

std::string private_dds_config(std::string_view tag) {
  std::string config(pdds::loopback_config());
  // The loopback configuration has one Discovery element; the tag goes first inside it.
  const std::string_view open = "<Discovery>";
  const std::size_t at = config.find(open);
  if (at == std::string::npos) return config;  // cannot happen: loopback.xml is ours
  config.insert(at + open.size(), "\n      <Tag>" + std::string(tag) + "</Tag>");
  return config;
}

namespace {

struct ContractTopic {
  const char* base;
  const dds_topic_descriptor_t* descriptor;
};

const ContractTopic kContractTopics[] = {
    {link::kVehicleStateTopic, &grip_msg_VehicleState_desc},
    {link::kPlanTopic, &grip_msg_Plan_desc},
    {link::kMapUpdateTopic, &grip_msg_MapUpdate_desc},
    {link::kMapRequestTopic, &grip_msg_MapRequest_desc},
    {link::kGoalTopic, &grip_msg_Goal_desc},
    {link::kPlannerStatusTopic, &grip_msg_PlannerStatus_desc},
    {link::kVehicleDescriptionTopic, &grip_msg_VehicleDescription_desc},
};

// Best effort, volatile, keep-last 1, no deadline or lease: the least a reader can ask, so it
// matches every writer of the topic that a reader of the run could match. Writers of this
// process are ignored: what matches is another process's.
dds_entity_t create_watch_reader(dds_entity_t participant, dds_entity_t topic,
                                 const dds_qos_t* /*unused*/, const dds_listener_t* listener) {
  std::unique_ptr<dds_qos_t, pdds::QosDeleter> qos(dds_create_qos());
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_BEST_EFFORT, 0);
  dds_qset_durability(qos.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_ignorelocal(qos.get(), DDS_IGNORELOCAL_PROCESS);
  return dds_create_reader(participant, topic, qos.get(), listener);
}

}  // namespace

Result<LinkWatch> LinkWatch::start(pdds::DomainId domain, const std::string& dds_config,
                                   const std::string& topic_prefix,
                                   const std::optional<pdds::SecurityFiles>& security) {
  auto names = link::TopicNames::create(topic_prefix);
  if (!names) return names.error();
  auto participant = pdds::Participant::create(domain, dds_config, security);
  if (!participant) return participant.error();
  LinkWatch watch(std::move(participant).value());
  for (const ContractTopic& topic : kContractTopics) {
    const std::string name = names->of(topic.base);
    auto reader = pdds::create_endpoint(watch.participant_, topic.descriptor, name, pdds::Qos{},
                                        &create_watch_reader, "dds_create_reader");
    if (!reader) return reader.error();
    watch.readers_.push_back(Watched{name, std::move(reader).value()});
  }
  return watch;
}

Result<std::vector<LinkWatch::TopicCount>> LinkWatch::other_writers() const {
  std::vector<TopicCount> counts;
  for (const Watched& watched : readers_) {
    auto matched =
        pdds::read_status(&dds_get_subscription_matched_status, watched.reader.endpoint.get(),
                          "dds_get_subscription_matched_status");
    if (!matched) return matched.error();
    counts.push_back(TopicCount{watched.topic, matched->total_count});
  }
  return counts;
}

nlohmann::json link_json(const params::LinkParams& link, const ExploreLink& choice,
                         const std::vector<LinkWatch::TopicCount>& other_writers,
                         const nlohmann::json& rejected) {
  nlohmann::json j;
  j["domain"] = link.domain;
  j["topic_prefix"] = link.topic_prefix;
  j["private"] = choice.is_private;
  if (choice.is_private) j["discovery_tag"] = choice.discovery_tag;
  nlohmann::json by_topic = nlohmann::json::object();
  std::uint64_t total = 0;
  for (const LinkWatch::TopicCount& count : other_writers) {
    by_topic[count.topic] = count.other_writers;
    total += count.other_writers;
  }
  // Writers of other processes that matched this run's topics: 0 means no sample of another
  // run could have reached the planner or the vehicle.
  j["other_writers"] = total;
  j["other_writers_by_topic"] = by_topic;
  j["rejected"] = rejected;
  return j;
}

}  // namespace grip::tools
