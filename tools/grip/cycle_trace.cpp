#include "cycle_trace.hpp"

#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

namespace grip::tools {

namespace {

double us(std::int64_t ns) { return static_cast<double>(ns) * 1e-3; }

}  // namespace

Result<CycleTrace> CycleTrace::open(const std::string& path) {
  // Written to a temporary file beside `path`, renamed into place by close().
  auto opened = AtomicFile::create(path);
  if (!opened) return Error{ErrorCode::kIo, "--cycle-trace: " + opened.error().message};
  auto file = std::make_unique<AtomicFile>(std::move(opened).value());
  // Times in microseconds; release_ms from the first traced cycle's release.
  std::fputs(
      "cycle,release_ms,wake_us,prepare_us,retain_us,grow_us,commit_us,commit_reserve_us,"
      "compute_us,lateness_us,missed,skipped,restarted,committed,kept_previous,"
      "plan_available,pool_exhausted,edges_added,edges_retained,tree_edges,plan_duration_s,"
      "retain_status,restart_cause\n",
      file->stream());
  return CycleTrace(std::move(file));
}

void CycleTrace::write(const rt::CycleRecord& r) {
  if (!file_) return;
  if (first_release_ns_ < 0) first_release_ns_ = r.release_ns;
  const rt::CycleOutcome& o = r.outcome;
  const std::string_view retain_status = retain_status_name(o.retain_status);
  const std::string_view restart_cause = rt::restart_cause_name(o.restart_cause);
  std::fprintf(
      file_->stream(),
      "%llu,%.3f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%d,%d,%d,%d,%d,%d,%d,%llu,%u,%u,%.3f,%"
      ".*s,%.*s\n",
      static_cast<unsigned long long>(r.cycle),
      static_cast<double>(r.release_ns - first_release_ns_) * 1e-6, us(r.wake_latency_ns),
      us(o.prepare_ns), us(o.retain_ns), us(o.grow_ns), us(o.commit_ns), us(o.commit_reserve_ns),
      us(r.compute_ns), us(r.lateness_ns), r.missed ? 1 : 0, r.skipped ? 1 : 0,
      o.restarted() ? 1 : 0, o.committed ? 1 : 0, o.kept_previous ? 1 : 0, o.plan_available ? 1 : 0,
      o.pool_exhausted ? 1 : 0, static_cast<unsigned long long>(o.edges_added), o.edges_retained,
      o.tree_edges, o.plan_duration_s, static_cast<int>(retain_status.size()), retain_status.data(),
      static_cast<int>(restart_cause.size()), restart_cause.data());
}

Status CycleTrace::close() {
  if (!file_) return Ok{};
  const std::unique_ptr<AtomicFile> file = std::move(file_);
  if (Status s = file->commit(); !s) {
    return Error{ErrorCode::kIo, "--cycle-trace: " + s.error().message};
  }
  return Ok{};
}

}  // namespace grip::tools
