#pragma once
// A one-process `grip explore` keeps its traffic to itself: its planner and simulator share a
// Cyclone domain in this process, configured with the project's loopback-only configuration
// plus a discovery tag of its own (Cyclone's Discovery/Tag), so that participants of any other
// run, even on the same domain and topics, are never discovered and nothing crosses.
//
// A run told where its topics are (--domain, --topic-prefix, or a parameter file whose link
// section names a domain, prefix or DDS configuration) is shared on purpose: other processes on
// that domain hear it, as `grip planner` and `grip sim` do. --private keeps it private anyway.
//
// LinkWatch shows that nothing crossed: readers on every contract topic that ignore this
// process's own writers (Cyclone's ignore-local QoS), whose matched-writer counts are the
// writers of other processes this run could have received a sample from.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/params/params.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/topic.hpp"
#include "params_options.hpp"

namespace grip::tools {

struct ExploreLink {
  bool is_private = true;
  std::string discovery_tag;  // private: "grip-explore-<pid>-<random>"; shared: empty
  // Cyclone XML for every participant of the run (Participant::create); empty: the built-in
  // loopback-only configuration.
  std::string dds_config;
};

// Private unless the options or the parameter file say where the topics are; `force_private`
// (--private) makes it private whatever they say.
ExploreLink choose_explore_link(const ParamsOptions& options, const params::GripParams& p,
                                bool force_private);

// A tag no other run draws: the process id and 64 random bits.
std::string private_discovery_tag();
// The loopback-only configuration (platform::dds::loopback_config()) with Discovery/Tag `tag`.
std::string private_dds_config(std::string_view tag);

class LinkWatch {
 public:
  // Joins `domain` (configured by `dds_config` if this process has not yet) and opens a reader
  // on each contract topic under `topic_prefix`, each ignoring this process's writers.
  // With `security`, as the run's own participants (an unauthenticated watch would match no
  // secured writer).
  static Result<LinkWatch> start(
      platform::dds::DomainId domain, const std::string& dds_config,
      const std::string& topic_prefix,
      const std::optional<platform::dds::SecurityFiles>& security = std::nullopt);

  // Writers of other processes matched since start(), by topic name (a topic none matched is
  // listed with 0).
  struct TopicCount {
    std::string topic;
    std::uint32_t other_writers = 0;
  };
  Result<std::vector<TopicCount>> other_writers() const;

 private:
  explicit LinkWatch(platform::dds::Participant participant)
      : participant_(std::move(participant)) {}

  platform::dds::Participant participant_;  // declared first: deletes its readers last
  struct Watched {
    std::string topic;
    platform::dds::Endpoint reader;
  };
  std::vector<Watched> readers_;
};

// The report's "link" section: domain, prefix, private or shared (and the tag), the writers of
// other processes each topic matched (with their total), and the samples each side rejected.
nlohmann::json link_json(const params::LinkParams& link, const ExploreLink& choice,
                         const std::vector<LinkWatch::TopicCount>& other_writers,
                         const nlohmann::json& rejected);

}  // namespace grip::tools
