#pragma once
// A typed DDS reader for an idlc-generated C type T, and the sample storage it takes into.
//
// Samples are taken into caller-owned, reused storage (SampleBuffer): Cyclone deserialises
// into the existing samples and reuses their sequence buffers when large enough, so after the
// first few takes a steady stream of samples no longer allocates.

#include <dds/dds.h>

#include <array>
#include <chrono>
#include <cstddef>
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

// N samples of T with their sample infos. Owns the samples' contents (sequence buffers) and
// frees them with dds_sample_free(DDS_FREE_CONTENTS). Not copyable or movable: Cyclone writes
// into it through pointers.
template <typename T, std::size_t N>
class SampleBuffer {
 public:
  static_assert(N > 0 && N <= 4096, "SampleBuffer capacity out of range");

  explicit SampleBuffer(const dds_topic_descriptor_t* descriptor) noexcept
      : descriptor_(descriptor) {
    for (std::size_t i = 0; i < N; ++i) pointers_[i] = &samples_[i];
  }
  ~SampleBuffer() {
    for (T& sample : samples_) dds_sample_free(&sample, descriptor_, DDS_FREE_CONTENTS);
  }
  SampleBuffer(const SampleBuffer&) = delete;
  SampleBuffer& operator=(const SampleBuffer&) = delete;

  static constexpr std::size_t capacity() noexcept { return N; }
  // After Reader::take returned n: samples [0, n) are the valid data samples, in the order
  // received, and info(i) their sample infos.
  const T& operator[](std::size_t i) const noexcept { return samples_[i]; }
  const dds_sample_info_t& info(std::size_t i) const noexcept { return infos_[i]; }

 private:
  template <typename>
  friend class Reader;

  const dds_topic_descriptor_t* descriptor_;
  std::array<T, N> samples_{};
  std::array<void*, N> pointers_{};
  std::array<dds_sample_info_t, N> infos_{};
};

template <typename T>
class Reader {
 public:
  static Result<Reader> create(const Participant& participant,
                               const dds_topic_descriptor_t* descriptor, const std::string& topic,
                               const Qos& qos) {
    Result<Endpoint> created = create_endpoint(participant, descriptor, topic, qos,
                                               &dds_create_reader, "dds_create_reader");
    if (!created.ok()) return created.error();
    return Reader(descriptor, std::move(created->topic), std::move(created->endpoint));
  }

  // Takes up to N samples without blocking. Returns how many valid data samples are now at the
  // front of `buffer`; samples without data (disposed / unregistered instances) are dropped.
  template <std::size_t N>
  Result<std::size_t> take(SampleBuffer<T, N>& buffer) {
    const dds_return_t rc = dds_take(reader_.get(), buffer.pointers_.data(), buffer.infos_.data(),
                                     N, static_cast<std::uint32_t>(N));
    if (rc < 0) return to_error(make_dds_error(rc, "dds_take"));
    const auto taken = static_cast<std::size_t>(rc);
    std::size_t valid = 0;
    for (std::size_t i = 0; i < taken; ++i) {
      if (!buffer.infos_[i].valid_data) continue;
      if (i != valid) {
        std::swap(buffer.samples_[i], buffer.samples_[valid]);  // moves buffer ownership too
        std::swap(buffer.infos_[i], buffer.infos_[valid]);
      }
      ++valid;
    }
    return valid;
  }

  Result<dds_subscription_matched_status_t> subscription_matched() const {
    return read_status(&dds_get_subscription_matched_status, reader_.get(),
                       "dds_get_subscription_matched_status");
  }

  Result<dds_liveliness_changed_status_t> liveliness_changed() const {
    return read_status(&dds_get_liveliness_changed_status, reader_.get(),
                       "dds_get_liveliness_changed_status");
  }

  Result<dds_requested_deadline_missed_status_t> requested_deadline_missed() const {
    return read_status(&dds_get_requested_deadline_missed_status, reader_.get(),
                       "dds_get_requested_deadline_missed_status");
  }

  // Waits until at least `writers` writers are matched (start-up and tests only).
  Status wait_for_writers(std::uint32_t writers, std::chrono::nanoseconds timeout) const {
    return wait_until_count(
        [this]() -> Result<std::uint32_t> {
          Result<dds_subscription_matched_status_t> status = subscription_matched();
          if (!status.ok()) return status.error();
          return status->current_count;
        },
        writers, timeout, "subscription_matched");
  }

  const dds_topic_descriptor_t* descriptor() const noexcept { return descriptor_; }
  dds_entity_t get() const noexcept { return reader_.get(); }

 private:
  Reader(const dds_topic_descriptor_t* descriptor, Entity topic, Entity reader)
      : descriptor_(descriptor), topic_(std::move(topic)), reader_(std::move(reader)) {}

  const dds_topic_descriptor_t* descriptor_;
  Entity topic_;  // declared first: the reader is deleted before its topic
  Entity reader_;
};

}  // namespace grip::platform::dds
