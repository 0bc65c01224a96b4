#include "grip/platform/dds/waitset.hpp"

#include <utility>

#include "grip/platform/dds/error.hpp"

namespace grip::platform::dds {

Result<WaitSet> WaitSet::create(const Participant& participant) {
  Result<dds_entity_t> waitset =
      check_entity(dds_create_waitset(participant.get()), "dds_create_waitset");
  if (!waitset.ok()) return waitset.error();
  Entity owned_waitset(*waitset);
  Result<dds_entity_t> guard =
      check_entity(dds_create_guardcondition(participant.get()), "dds_create_guardcondition");
  if (!guard.ok()) return guard.error();
  Entity owned_guard(*guard);
  if (Status s = check(dds_waitset_attach(*waitset, *guard, *guard), "dds_waitset_attach"); !s) {
    return s.error();
  }
  return WaitSet(std::move(owned_waitset), std::move(owned_guard));
}

Status WaitSet::attach(dds_entity_t entity, std::uint32_t status_mask, const char* call) {
  if (Status s = check(dds_set_status_mask(entity, status_mask), call); !s) return s;
  return check(dds_waitset_attach(waitset_.get(), entity, entity), "dds_waitset_attach");
}

Status WaitSet::attach_data_available(dds_entity_t reader) {
  return attach(reader, DDS_DATA_AVAILABLE_STATUS, "dds_set_status_mask(DATA_AVAILABLE)");
}

Status WaitSet::attach_publication_matched(dds_entity_t writer) {
  return attach(writer, DDS_PUBLICATION_MATCHED_STATUS, "dds_set_status_mask(PUBLICATION_MATCHED)");
}

Result<bool> WaitSet::wait(std::chrono::nanoseconds timeout) {
  const dds_return_t rc = dds_waitset_wait(waitset_.get(), nullptr, 0, timeout.count());
  if (rc < 0) return to_error(make_dds_error(rc, "dds_waitset_wait"));
  // The guard stays triggered until reset; reset it so the next wait can sleep again.
  if (Status s = check(dds_set_guardcondition(guard_.get(), false), "dds_set_guardcondition"); !s) {
    return s.error();
  }
  return rc > 0;
}

Status WaitSet::wake() {
  return check(dds_set_guardcondition(guard_.get(), true), "dds_set_guardcondition");
}

}  // namespace grip::platform::dds
