#include "grip/platform/dds/writer_liveliness.hpp"

#include <mutex>

#include "grip/platform/dds/error.hpp"

namespace grip::platform::dds {
namespace {
constinit std::mutex watchers;  // see the header
}  // namespace

Result<std::unique_ptr<WriterLiveliness>> WriterLiveliness::attach(dds_entity_t reader) {
  std::unique_ptr<WriterLiveliness> self(new WriterLiveliness(reader));
  { const std::lock_guard<std::mutex> published(watchers); }  // before any callback
  dds_listener_t* listener = dds_create_listener(self.get());
  if (listener == nullptr) {
    return to_error(make_dds_error(DDS_RETCODE_OUT_OF_RESOURCES, "dds_create_listener"));
  }
  dds_lset_liveliness_changed(listener, &WriterLiveliness::on_liveliness_changed);
  const dds_return_t rc = dds_set_listener(reader, listener);
  dds_delete_listener(listener);  // the reader keeps a copy
  if (rc < 0) return to_error(make_dds_error(rc, "dds_set_listener"));
  return self;
}

WriterLiveliness::~WriterLiveliness() {
  // Cyclone waits for a callback in progress; taking the mutex after it orders that callback
  // before the memory is freed.
  static_cast<void>(dds_set_listener(reader_, nullptr));
  const std::lock_guard<std::mutex> last(watchers);
}

void WriterLiveliness::watch(dds_instance_handle_t writer) {
  const std::lock_guard<std::mutex> lock(watchers);
  watched_ = writer;
  lost_ = false;
}

bool WriterLiveliness::alive() const {
  const std::lock_guard<std::mutex> lock(watchers);
  return !lost_;
}

void WriterLiveliness::on_liveliness_changed(dds_entity_t /*reader*/,
                                             dds_liveliness_changed_status_t status, void* self) {
  auto* watcher = static_cast<WriterLiveliness*>(self);
  const std::lock_guard<std::mutex> lock(watchers);
  if (watcher->watched_ == 0 || status.last_publication_handle != watcher->watched_) return;
  // alive_count falls when the writer loses liveliness or leaves, rises when it regains it.
  if (status.alive_count_change < 0) watcher->lost_ = true;
  if (status.alive_count_change > 0) watcher->lost_ = false;
}

}  // namespace grip::platform::dds
