#pragma once
// A DDS domain participant created with an explicit Cyclone configuration.
//
// Cyclone has one instance of a domain per process, configured when it is created. The first
// Participant of a domain id in a process creates the domain (dds_create_domain) with the given
// configuration; later ones in the same process join it and the configuration they pass is not
// applied (Cyclone cannot reconfigure a running domain). The domain is deleted with the last
// Participant that uses it. Participants of one domain in one process talk through Cyclone's
// in-process delivery; participants in different processes go over the configured interface.

#include <dds/dds.h>

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"
#include "grip/platform/dds/entity.hpp"
#include "grip/platform/dds/security.hpp"

namespace grip::platform::dds {

using DomainId = dds_domainid_t;

// The project's loopback-only configuration (platform/dds/config/loopback.xml, embedded at
// build time): lo interface, AllowMulticast false, unicast peer 127.0.0.1.
std::string_view loopback_config();

class Participant {
 public:
  // `config` is Cyclone XML text (starting with '<') or a "file://" URI; empty means
  // loopback_config(). domain must be < DDS_DOMAIN_DEFAULT. With `security`, the participant
  // authenticates with those files, and talks only to participants its governance and
  // permissions allow (security.hpp); a file that cannot be read is refused, named.
  static Result<Participant> create(DomainId domain, const std::string& config = {},
                                    const std::optional<SecurityFiles>& security = std::nullopt);

  dds_entity_t get() const noexcept { return participant_.get(); }
  DomainId domain() const noexcept { return domain_id_; }

  // Deletes the participant (and, through Cyclone, every topic, reader and writer in it).
  Status reset() noexcept { return participant_.reset(); }

  struct Domain;  // implementation detail: shared by the participants of one domain id

 private:
  Participant(DomainId domain_id, std::shared_ptr<Domain> domain, Entity participant)
      : domain_id_(domain_id), domain_(std::move(domain)), participant_(std::move(participant)) {}

  DomainId domain_id_ = 0;
  std::shared_ptr<Domain> domain_;  // declared before participant_: outlives it
  Entity participant_;
};

}  // namespace grip::platform::dds
