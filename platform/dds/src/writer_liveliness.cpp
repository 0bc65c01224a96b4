#include "grip/platform/dds/writer_liveliness.hpp"

#include "grip/platform/dds/error.hpp"

namespace grip::platform::dds {

Result<std::unique_ptr<WriterLiveliness>> WriterLiveliness::attach(dds_entity_t reader) {
  std::unique_ptr<WriterLiveliness> self(new WriterLiveliness(reader));
  dds_listener_t* listener = dds_create_listener(self.get());
  if (listener == nullptr)
    return to_error(make_dds_error(DDS_RETCODE_OUT_OF_RESOURCES, "dds_create_listener"));
  dds_lset_liveliness_changed(listener, &WriterLiveliness::on_liveliness_changed);
  const dds_return_t rc = dds_set_listener(reader, listener);
  dds_delete_listener(listener);  // the reader keeps a copy
  if (rc < 0) return to_error(make_dds_error(rc, "dds_set_listener"));
  return self;
}

WriterLiveliness::~WriterLiveliness() {
  // Waits for a callback in progress (Cyclone serialises listener changes with callbacks).
  static_cast<void>(dds_set_listener(reader_, nullptr));
}

void WriterLiveliness::watch(dds_instance_handle_t writer) noexcept {
  watched_.store(writer, std::memory_order_release);
}

void WriterLiveliness::on_liveliness_changed(dds_entity_t /*reader*/,
                                             dds_liveliness_changed_status_t status, void* self) {
  auto* watcher = static_cast<WriterLiveliness*>(self);
  dds_instance_handle_t writer = status.last_publication_handle;
  if (writer == 0 || writer != watcher->watched_.load(std::memory_order_acquire)) return;
  // alive_count falls when the writer loses liveliness or leaves, rises when it regains it.
  if (status.alive_count_change < 0) watcher->lost_.store(writer, std::memory_order_release);
  if (status.alive_count_change > 0) {
    watcher->lost_.compare_exchange_strong(writer, 0, std::memory_order_acq_rel);
  }
}

}  // namespace grip::platform::dds
