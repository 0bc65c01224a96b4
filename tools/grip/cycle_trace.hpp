#pragma once
// `--cycle-trace FILE`: one CSV row per planning cycle, for finding out why a deadline was
// missed (a late wake-up, a long target choice, growth that overran, a slow commit), what the
// cycle achieved, and, exploring, where it headed and why (a target that flips between groups,
// plans that creep or loop). Written from an ordinary thread as records arrive; the planning thread
// only fills the record (rt::CycleRecord).

#include <cstdio>
#include <memory>
#include <string>

#include "grip/common/result.hpp"
#include "grip/rt/periodic_loop.hpp"
#include "grip/tools/atomic_file.hpp"

namespace grip::tools {

class CycleTrace {
 public:
  // Opens the file and writes the header; an error names the file. The rows go to a temporary
  // file beside it, which close() renames into place: the file appears whole or not at all.
  static Result<CycleTrace> open(const std::string& path);
  // Appends a row; a write error is reported once by close().
  void write(const rt::CycleRecord& record);
  // Flushes, closes and renames it into place; an error names the file.
  Status close();

 private:
  explicit CycleTrace(std::unique_ptr<AtomicFile> file) : file_(std::move(file)) {}

  std::unique_ptr<AtomicFile> file_;
  std::int64_t first_release_ns_ = -1;
};

}  // namespace grip::tools
