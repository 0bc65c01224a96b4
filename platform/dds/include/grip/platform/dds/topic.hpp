#pragma once
// A topic handle plus the typed sample helpers shared by Writer and Reader.

#include <dds/dds.h>

#include <chrono>
#include <string>

#include "grip/common/result.hpp"
#include "grip/platform/dds/entity.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/qos.hpp"

namespace grip::platform::dds {

// Creates (or, if it exists in this participant, opens another handle to) the topic `name` of
// the idlc-generated type `descriptor` (e.g. &grip_msg_Plan_desc).
Result<Entity> create_topic(const Participant& participant,
                            const dds_topic_descriptor_t* descriptor, const std::string& name);

// A reader or writer with the topic handle it was created on.
struct Endpoint {
  Entity topic;
  Entity endpoint;
};
using CreateEndpoint = dds_entity_t (*)(dds_entity_t, dds_entity_t, const dds_qos_t*,
                                        const dds_listener_t*);

// Creates the topic and, on it, a reader or writer (`create` is dds_create_reader or
// dds_create_writer, `call` its name for errors) with the given QoS.
Result<Endpoint> create_endpoint(const Participant& participant,
                                 const dds_topic_descriptor_t* descriptor, const std::string& name,
                                 const Qos& qos, CreateEndpoint create, const char* call);

// Polls `get_count` every few milliseconds until it reports >= `count` or `timeout` passes.
// Used by the wait_for_* helpers; start-up and test code only.
template <typename GetCount>
Status wait_until_count(GetCount get_count, std::uint32_t count, std::chrono::nanoseconds timeout,
                        const char* what);

}  // namespace grip::platform::dds

#include "grip/platform/dds/detail/wait.hpp"
