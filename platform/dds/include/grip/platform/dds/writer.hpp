#pragma once
// A typed DDS writer for an idlc-generated C type T (descriptor e.g. &grip_msg_Plan_desc).
// Owns its topic handle and its writer handle; both are children of the participant, so the
// Writer may outlive a deleted participant (its handles are then already gone).

#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>

#include "grip/common/result.hpp"
#include "grip/platform/dds/entity.hpp"
#include "grip/platform/dds/error.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/qos.hpp"
#include "grip/platform/dds/topic.hpp"

namespace grip::platform::dds {

template <typename T>
class Writer {
 public:
  static Result<Writer> create(const Participant& participant,
                               const dds_topic_descriptor_t* descriptor, const std::string& topic,
                               const Qos& qos) {
    Result<Endpoint> created = create_endpoint(participant, descriptor, topic, qos,
                                               &dds_create_writer, "dds_create_writer");
    if (!created.ok()) return created.error();
    return Writer(std::move(created->topic), std::move(created->endpoint));
  }

  // Publishes one sample. A reliable writer may block up to the QoS max_blocking_time and then
  // fails with "Timeout"; never call this from the planning thread.
  Status write(const T& sample) { return check(dds_write(writer_.get(), &sample), "dds_write"); }
  // As write(), with the source timestamp given (DDS time, ns since the epoch) rather than now:
  // for a sample measured earlier than it is sent.
  Status write_at(const T& sample, dds_time_t source_timestamp) {
    return check(dds_write_ts(writer_.get(), &sample, source_timestamp), "dds_write_ts");
  }

  Result<dds_publication_matched_status_t> publication_matched() const {
    return read_status(&dds_get_publication_matched_status, writer_.get(),
                       "dds_get_publication_matched_status");
  }

  // Waits until at least `readers` readers are matched (start-up and tests only).
  Status wait_for_readers(std::uint32_t readers, std::chrono::nanoseconds timeout) const {
    return wait_until_count(
        [this]() -> Result<std::uint32_t> {
          Result<dds_publication_matched_status_t> status = publication_matched();
          if (!status.ok()) return status.error();
          return status->current_count;
        },
        readers, timeout, "publication_matched");
  }

  // Waits until every matched reader has acknowledged every sample written (tools only: a
  // process that writes once and exits must not leave before its sample arrived).
  Status wait_for_acks(std::chrono::nanoseconds timeout) const {
    return check(dds_wait_for_acks(writer_.get(), timeout.count()), "dds_wait_for_acks");
  }

  dds_entity_t get() const noexcept { return writer_.get(); }

 private:
  Writer(Entity topic, Entity writer) : topic_(std::move(topic)), writer_(std::move(writer)) {}

  Entity topic_;  // declared first: the writer is deleted before its topic
  Entity writer_;
};

}  // namespace grip::platform::dds
