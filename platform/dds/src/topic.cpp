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

Result<Endpoint> create_endpoint(const Participant& participant,
                                 const dds_topic_descriptor_t* descriptor, const std::string& name,
                                 const Qos& qos, CreateEndpoint create, const char* call) {
  Result<Entity> topic = create_topic(participant, descriptor, name);
  if (!topic.ok()) return topic.error();
  Result<QosPtr> dds_qos = make_qos(qos);
  if (!dds_qos.ok()) return dds_qos.error();
  Result<dds_entity_t> endpoint =
      check_entity(create(participant.get(), topic->get(), dds_qos->get(), nullptr), call);
  if (!endpoint.ok()) return endpoint.error();
  return Endpoint{std::move(topic.value()), Entity(endpoint.value())};
}

}  // namespace grip::platform::dds
