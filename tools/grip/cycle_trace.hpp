#pragma once
// `--cycle-trace FILE`: one CSV row per planning cycle, for finding out why a deadline was
// missed (a late wake-up, a long target choice, growth that overran, a slow commit) and what the
// cycle achieved. Written from an ordinary thread as records arrive; the planning thread only
// fills the record (rt::CycleRecord).

#include <cstdio>
#include <memory>
#include <string>

#include "grip/common/result.hpp"
#include "grip/rt/periodic_loop.hpp"

namespace grip::tools {

class CycleTrace {
 public:
  // Creates (truncates) the file and writes the header; an error names the file.
  static Result<CycleTrace> open(const std::string& path);
  // Appends a row; a write error is reported once by close().
  void write(const rt::CycleRecord& record);
  // Flushes and closes; an error names the file.
  Status close();

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
  };
  CycleTrace(std::string path, std::FILE* file) : path_(std::move(path)), file_(file) {}

  std::string path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::int64_t first_release_ns_ = -1;
};

}  // namespace grip::tools
