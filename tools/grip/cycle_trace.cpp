#include "cycle_trace.hpp"

#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

namespace grip::tools {

namespace {

double us(std::int64_t ns) { return static_cast<double>(ns) * 1e-3; }

// A metre figure ("inf": rho's wavefront does not reach), or an empty field where there is
// none (not exploring, no target yet, no end chosen).
void put_m(std::FILE* out, bool known, double m) {
  if (known) {
    std::fprintf(out, ",%.2f", m);
  } else {
    std::fputs(",", out);
  }
}

// The exploration columns (rt::ExplorationRecord): the target's centre, rho from the root to
// it, and how the plan's end was chosen: "sight" (some tree state sees the target: d is the
// visibility sum), "rho" (none does: d is rho at the end), "none" (no end: the plan leads to
// the root), empty when the cycle did not explore (or was skipped).
void put_exploration(std::FILE* out, const rt::ExplorationRecord& e) {
  put_m(out, e.exploring && e.has_target, e.target_x_m);
  put_m(out, e.exploring && e.has_target, e.target_y_m);
  put_m(out, e.exploring && e.chosen, e.root_rho_m);
  const char* choice = !e.exploring ? "" : !e.chosen ? "none" : e.sees_target ? "sight" : "rho";
  std::fprintf(out, ",%s", choice);
  put_m(out, e.exploring && e.chosen, e.d_m);
  put_m(out, e.exploring && e.chosen, e.length_m);
}

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
      "retain_status,restart_cause,"
      "start_x_m,start_y_m,start_theta,"
      "target_x_m,target_y_m,root_rho_m,choice,choice_d_m,choice_length_m\n",
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
      ".*s,%.*s",
      static_cast<unsigned long long>(r.cycle),
      static_cast<double>(r.release_ns - first_release_ns_) * 1e-6, us(r.wake_latency_ns),
      us(o.prepare_ns), us(o.retain_ns), us(o.grow_ns), us(o.commit_ns), us(o.commit_reserve_ns),
      us(r.compute_ns), us(r.lateness_ns), r.missed ? 1 : 0, r.skipped ? 1 : 0,
      o.restarted() ? 1 : 0, o.committed ? 1 : 0, o.kept_previous ? 1 : 0, o.plan_available ? 1 : 0,
      o.pool_exhausted ? 1 : 0, static_cast<unsigned long long>(o.edges_added), o.edges_retained,
      o.tree_edges, o.plan_duration_s, static_cast<int>(retain_status.size()), retain_status.data(),
      static_cast<int>(restart_cause.size()), restart_cause.data());
  if (r.skipped) {  // no body ran: no start, and no exploration either
    std::fputs(",,,", file_->stream());
  } else {
    std::fprintf(file_->stream(), ",%.2f,%.2f,%.3f", o.start_x_m, o.start_y_m, o.start_theta);
  }
  put_exploration(file_->stream(), o.exploration);
  std::fputc('\n', file_->stream());
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
