#pragma once
// Whether one remote writer, matched by a reader, is still alive (DDS liveliness): a writer
// whose peer stopped, was killed or was cut off for its liveliness lease, or that left, is
// lost; one that comes back is alive again. Cyclone reports liveliness per reader; this keeps
// the verdict for the one writer the owner cares about (the planner a vehicle follows), so
// that a peer that is merely slow is told from one that is gone.
//
// Installs a liveliness listener on the reader and removes it when destroyed. The listener
// runs on Cyclone's thread and shares two handles with the owner under a mutex (not for the
// real-time path). Cyclone orders its callbacks after the listener is set and before it is
// removed, in code ThreadSanitizer cannot see; the mutex is one for all watchers, in static
// storage, so that taking it also shows TSan that order (a member mutex would itself be memory
// written by the constructor, unordered for TSan with the callback's first look at it).
// Not movable: the listener points at it.

#include <dds/dds.h>

#include <memory>

#include "grip/common/result.hpp"

namespace grip::platform::dds {

class WriterLiveliness {
 public:
  // `reader` must outlive the returned object.
  static Result<std::unique_ptr<WriterLiveliness>> attach(dds_entity_t reader);
  ~WriterLiveliness();
  WriterLiveliness(const WriterLiveliness&) = delete;
  WriterLiveliness& operator=(const WriterLiveliness&) = delete;

  // The writer to watch (a sample's publication_handle); it counts as alive from now on.
  void watch(dds_instance_handle_t writer);
  // Whether the watched writer is alive; true while none is watched.
  bool alive() const;

 private:
  explicit WriterLiveliness(dds_entity_t reader) noexcept : reader_(reader) {}
  static void on_liveliness_changed(dds_entity_t reader, dds_liveliness_changed_status_t status,
                                    void* self);

  dds_entity_t reader_;
  dds_instance_handle_t watched_ = 0;
  bool lost_ = false;
};

}  // namespace grip::platform::dds
