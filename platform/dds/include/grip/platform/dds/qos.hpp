#pragma once
// The QoS of a reader or writer, set explicitly (nothing is left to Cyclone's defaults for the
// policies that matter on a control link).

#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

#include "grip/common/result.hpp"

namespace grip::platform::dds {

struct Qos {
  // Reliable delivery; a reliable writer blocks in dds_write for at most max_blocking_time
  // when the readers' history is full, then returns DDS_RETCODE_TIMEOUT.
  bool reliable = true;
  std::chrono::nanoseconds max_blocking_time = std::chrono::milliseconds(10);
  // KEEP_LAST history of this depth (>= 1).
  std::int32_t history_depth = 1;
  // Deadline period; empty = infinite. A writer's must be <= its readers' to match.
  std::optional<std::chrono::nanoseconds> deadline;
  // AUTOMATIC liveliness with this lease: a peer that stops (process killed, participant
  // deleted) is noticed within about one lease.
  std::chrono::nanoseconds liveliness_lease = std::chrono::seconds(1);
  // TRANSIENT_LOCAL durability: late-joining readers get the writer's history.
  bool transient_local = false;
};

struct QosDeleter {
  void operator()(dds_qos_t* qos) const noexcept { dds_delete_qos(qos); }
};
using QosPtr = std::unique_ptr<dds_qos_t, QosDeleter>;

// Validates the fields (history_depth >= 1, durations > 0) and builds the dds_qos_t.
Result<QosPtr> make_qos(const Qos& qos);

}  // namespace grip::platform::dds
