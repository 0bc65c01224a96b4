#pragma once
// Files the `grip` command writes for people and scripts to read (JSON reports, PNG figures,
// cycle-trace CSVs) appear whole or not at all: they are written to a temporary file in the
// same directory and renamed into place (rename(2) is atomic within a file system), so that a
// run that crashes or is killed never leaves half a JSON where the last good one was.
//
// And a path that cannot be written is refused before a run starts (check_writable), not
// discovered after an hour of exploration.

#include <cstdio>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip::tools {

class AtomicFile {
 public:
  // Opens a temporary file ".<name>.tmp-XXXXXX" beside `path`; an error (kIo) names `path` and
  // why.
  static Result<AtomicFile> create(const std::string& path);

  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&&) = delete;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  // Without commit(): the temporary file is removed and `path` left as it was.
  ~AtomicFile();

  // Where to write until commit(); null after it.
  std::FILE* stream() const noexcept { return file_; }
  const std::string& path() const noexcept { return path_; }

  // Flushes, syncs and closes the temporary file and renames it to `path`. Any write error
  // since create() fails it (kIo naming `path`) and removes the temporary file.
  Status commit();

 private:
  AtomicFile(std::string path, std::string temporary, std::FILE* file)
      : path_(std::move(path)), temporary_(std::move(temporary)), file_(file) {}
  void discard() noexcept;

  std::string path_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
};

// `contents` to `path` through an AtomicFile.
Status write_file_atomically(const std::string& path, std::string_view contents);

// Whether `path` could be written: its directory exists and is writable, and `path` is not a
// directory. kIo naming `what` (the option, "--report") and the path otherwise.
Status check_writable(const std::string& path, std::string_view what);

}  // namespace grip::tools
