#include "grip/platform/dds/topic.hpp"

#include "grip/platform/dds/error.hpp"

namespace grip::platform::dds {

Result<Entity> create_topic(const Participant& participant,
                            const dds_topic_descriptor_t* descriptor, const std::string& name) {
  if (descriptor == nullptr) return invalid_argument("create_topic: null type descriptor");
  Result<dds_entity_t> topic =
      check_entity(dds_create_topic(participant.get(), descriptor, name.c_str(), nullptr, nullptr),
                   "dds_create_topic");
  if (!topic.ok()) return topic.error();
  return Entity(topic.value());
}

}  // namespace grip::platform::dds
