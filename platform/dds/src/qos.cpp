#include "grip/platform/dds/qos.hpp"

#include <string>

namespace grip::platform::dds {
namespace {

dds_duration_t to_duration(std::chrono::nanoseconds d) {
  return static_cast<dds_duration_t>(d.count());
}

}  // namespace

Result<QosPtr> make_qos(const Qos& qos) {
  if (qos.history_depth < 1) {
    return invalid_argument("Qos.history_depth must be >= 1 (got " +
                            std::to_string(qos.history_depth) + ")");
  }
  if (qos.max_blocking_time.count() < 0) {
    return invalid_argument("Qos.max_blocking_time must be >= 0");
  }
  if (qos.deadline && qos.deadline->count() <= 0) {
    return invalid_argument("Qos.deadline must be > 0");
  }
  if (qos.liveliness_lease.count() <= 0) {
    return invalid_argument("Qos.liveliness_lease must be > 0");
  }
  QosPtr result(dds_create_qos());
  if (!result) return Error{ErrorCode::kCapacity, "dds_create_qos failed"};
  dds_qos_t* q = result.get();
  dds_qset_reliability(q, qos.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       to_duration(qos.max_blocking_time));
  dds_qset_history(q, DDS_HISTORY_KEEP_LAST, qos.history_depth);
  dds_qset_durability(
      q, qos.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  dds_qset_deadline(q, qos.deadline ? to_duration(*qos.deadline) : DDS_INFINITY);
  dds_qset_liveliness(q, DDS_LIVELINESS_AUTOMATIC, to_duration(qos.liveliness_lease));
  return result;
}

}  // namespace grip::platform::dds
