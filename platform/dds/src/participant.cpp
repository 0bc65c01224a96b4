#include "grip/platform/dds/participant.hpp"

#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "grip/platform/dds/error.hpp"

namespace grip::platform::dds {

// The domain entity created by dds_create_domain, shared by the Participants of one domain id
// in this process and deleted with the last of them.
struct Participant::Domain {
  Entity entity;
};

namespace {

std::mutex& registry_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<DomainId, std::weak_ptr<Participant::Domain>>& registry() {
  static std::map<DomainId, std::weak_ptr<Participant::Domain>> domains;
  return domains;
}

}  // namespace

Result<Participant> Participant::create(DomainId domain_id, const std::string& config) {
  if (domain_id >= DDS_DOMAIN_DEFAULT) {
    return invalid_argument("DDS domain id must be < DDS_DOMAIN_DEFAULT (got " +
                            std::to_string(domain_id) + ")");
  }
  const std::string effective = config.empty() ? std::string(loopback_config()) : config;

  std::shared_ptr<Domain> domain;
  {
    std::lock_guard<std::mutex> lock(registry_mutex());
    domain = registry()[domain_id].lock();
    if (!domain) {
      Result<dds_entity_t> created =
          check_entity(dds_create_domain(domain_id, effective.c_str()), "dds_create_domain");
      if (!created.ok()) return created.error();
      domain = std::make_shared<Domain>(Domain{Entity(created.value())});
      registry()[domain_id] = domain;
    }
  }
  Result<dds_entity_t> participant =
      check_entity(dds_create_participant(domain_id, nullptr, nullptr), "dds_create_participant");
  if (!participant.ok()) return participant.error();
  return Participant(domain_id, std::move(domain), Entity(participant.value()));
}

}  // namespace grip::platform::dds
