#include "grip/platform/dds/participant.hpp"

#include <map>
#include <memory>
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

Result<Participant> Participant::create(DomainId domain_id, const std::string& config,
                                        const std::optional<SecurityFiles>& security) {
  if (domain_id >= DDS_DOMAIN_DEFAULT) {
    return invalid_argument("DDS domain id must be < DDS_DOMAIN_DEFAULT (got " +
                            std::to_string(domain_id) + ")");
  }
  if (security) {
    if (Status checked = security->check(); !checked) return checked.error();
  }
  std::string effective = config.empty() ? std::string(loopback_config()) : config;
  if (security && config.empty()) {
    // Cyclone reports refused peers only in its discovery trace (on_refused_by_security).
    const std::size_t end = effective.rfind("</Domain>");
    if (end != std::string::npos) effective.insert(end, refusal_tracing_config());
  }

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
  std::unique_ptr<dds_qos_t, void (*)(dds_qos_t*)> qos(nullptr, dds_delete_qos);
  if (security) {
    qos.reset(dds_create_qos());
    if (Status set = set_security_properties(qos.get(), *security); !set) return set.error();
  }
  Result<dds_entity_t> participant =
      check_entity(dds_create_participant(domain_id, qos.get(), nullptr), "dds_create_participant");
  if (!participant.ok()) {
    if (!security) return participant.error();
    // Cyclone's plugins say why on its log (a certificate out of its validity, a document not
    // signed by the CA, a permissions subject that is not the certificate's).
    return Error{participant.error().code,
                 participant.error().message + ": the DDS security plugins refused the files in '" +
                     security->directory() + "' (Cyclone's log says why)"};
  }
  return Participant(domain_id, std::move(domain), Entity(participant.value()));
}

}  // namespace grip::platform::dds
