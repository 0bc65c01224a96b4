#pragma once
// A DDS waitset for a service thread: it sleeps until a reader has data or until wake() is
// called from another thread (to stop it, or to hand it work), with a timeout for periodic work.

#include <dds/dds.h>

#include <chrono>
#include <cstdint>

#include "grip/common/result.hpp"
#include "grip/platform/dds/entity.hpp"
#include "grip/platform/dds/participant.hpp"

namespace grip::platform::dds {

class WaitSet {
 public:
  static Result<WaitSet> create(const Participant& participant);

  // Wakes the waitset when `reader` has data available.
  Status attach_data_available(dds_entity_t reader);
  // Wakes the waitset when `writer`'s matched readers change.
  Status attach_publication_matched(dds_entity_t writer);

  // Blocks until something attached triggers, wake() is called, or `timeout` passes. Returns
  // whether anything triggered. A woken waitset stays woken until the next wait() returns.
  Result<bool> wait(std::chrono::nanoseconds timeout);
  // Any thread; never blocks.
  Status wake();

 private:
  WaitSet(Entity waitset, Entity guard)
      : waitset_(static_cast<Entity&&>(waitset)), guard_(static_cast<Entity&&>(guard)) {}
  Status attach(dds_entity_t entity, std::uint32_t status_mask, const char* call);

  Entity waitset_;
  Entity guard_;
};

}  // namespace grip::platform::dds
