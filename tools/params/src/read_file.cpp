#include "read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>

#include "grip/platform/os_call.hpp"

namespace grip::params::detail {

namespace {

// Closes the descriptor on every way out.
class OpenFile {
 public:
  explicit OpenFile(int fd) : fd_(fd) {}
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;
  ~OpenFile() {
    (void)platform::os_call("close", [this] { return ::close(fd_); });
  }
  int fd() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Result<std::string> read_parameter_file(const std::string& path) {
  const auto refuse = [&path](const std::string& why) {
    return invalid_argument(path + ": " + why);
  };
  // O_NONBLOCK: opening a FIFO waits for a writer otherwise. It changes nothing for the
  // regular file read below.
  const auto opened = platform::os_call(
      "open", [&] { return ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK); });
  if (!opened.ok()) return refuse("cannot open the parameter file (" + opened.describe() + ")");
  const OpenFile file(opened.value);
  struct stat info {};
  const auto examined = platform::os_call("fstat", [&] { return ::fstat(file.fd(), &info); });
  if (!examined.ok()) return refuse("cannot read the parameter file (" + examined.describe() + ")");
  if (S_ISDIR(info.st_mode)) return refuse("is a directory, not a parameter file");
  if (!S_ISREG(info.st_mode)) {
    return refuse("is not a regular file (a device, FIFO or socket), not a parameter file");
  }
  const auto too_large = [&] {
    return refuse("is larger than " + std::to_string(kMaxParameterFileBytes) +
                  " bytes, not a parameter file");
  };
  if (info.st_size > kMaxParameterFileBytes) return too_large();
  std::string text;
  std::array<char, 4096> chunk{};
  for (;;) {
    const auto got =
        platform::os_call("read", [&] { return ::read(file.fd(), chunk.data(), chunk.size()); });
    if (!got.ok() && got.error == EINTR) continue;
    if (!got.ok()) return refuse("cannot read the parameter file (" + got.describe() + ")");
    if (got.value == 0) return text;
    text.append(chunk.data(), static_cast<std::size_t>(got.value));
    // A file that grows while it is read.
    if (text.size() > static_cast<std::size_t>(kMaxParameterFileBytes)) return too_large();
  }
}

}  // namespace grip::params::detail
