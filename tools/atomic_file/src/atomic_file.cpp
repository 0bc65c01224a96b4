#include "grip/tools/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

namespace grip::tools {

namespace {

Error io_error(const std::string& message) { return Error{ErrorCode::kIo, message}; }

std::string directory_of(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  return parent.empty() ? "." : parent;
}

}  // namespace

Result<AtomicFile> AtomicFile::create(const std::string& path) {
  if (path.empty()) return io_error("cannot write a file without a name");
  // ".<name>.tmp-XXXXXX" in the same directory: rename(2) stays within one file system.
  std::string temporary = directory_of(path);
  temporary.append("/.");
  temporary.append(std::filesystem::path(path).filename().string());
  temporary.append(".tmp-XXXXXX");
  const int fd = mkstemp(temporary.data());
  if (fd < 0) return io_error("cannot write '" + path + "': " + std::strerror(errno));
  // mkstemp makes it 0600; a report is as readable as any file the user creates.
  const mode_t mask = umask(0);
  umask(mask);
  static_cast<void>(fchmod(fd, static_cast<mode_t>(0666) & ~mask));
  std::FILE* file = fdopen(fd, "w");
  if (file == nullptr) {
    const int error = errno;
    close(fd);
    unlink(temporary.c_str());
    return io_error("cannot write '" + path + "': " + std::strerror(error));
  }
  return AtomicFile(path, std::move(temporary), file);
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : path_(std::move(other.path_)),
      temporary_(std::move(other.temporary_)),
      file_(std::exchange(other.file_, nullptr)) {
  other.temporary_.clear();
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  if (file_ != nullptr) {
    std::fclose(file_);
    file_ = nullptr;
  }
  if (!temporary_.empty()) {
    unlink(temporary_.c_str());
    temporary_.clear();
  }
}

Status AtomicFile::commit() {
  if (file_ == nullptr) return io_error("'" + path_ + "' was already written");
  const bool failed =
      std::fflush(file_) != 0 || std::ferror(file_) != 0 || fsync(fileno(file_)) != 0;
  const int error = errno;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || close_failed) {
    discard();
    return io_error("cannot write '" + path_ + "': " + std::strerror(error));
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int rename_error = errno;
    discard();
    return io_error("cannot write '" + path_ + "': " + std::strerror(rename_error));
  }
  temporary_.clear();
  return Ok{};
}

Status write_file_atomically(const std::string& path, std::string_view contents) {
  auto file = AtomicFile::create(path);
  if (!file) return file.error();
  std::fwrite(contents.data(), 1, contents.size(), file->stream());
  return file->commit();
}

Status check_writable(const std::string& path, std::string_view what) {
  const std::string prefix = std::string(what) + ": cannot write '" + path + "': ";
  if (path.empty()) return io_error(std::string(what) + ": an empty path");
  struct stat target {};
  if (stat(path.c_str(), &target) == 0 && S_ISDIR(target.st_mode)) {
    return io_error(prefix + "it is a directory");
  }
  const std::string directory = directory_of(path);
  struct stat dir {};
  if (stat(directory.c_str(), &dir) != 0) {
    return io_error(prefix + "no directory '" + directory + "' (" + std::strerror(errno) + ")");
  }
  if (!S_ISDIR(dir.st_mode)) return io_error(prefix + "'" + directory + "' is not a directory");
  if (access(directory.c_str(), W_OK | X_OK) != 0) {
    return io_error(prefix + "directory '" + directory + "' is not writable (" +
                    std::strerror(errno) + ")");
  }
  return Ok{};
}

}  // namespace grip::tools
