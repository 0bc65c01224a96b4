#include "grip/platform/dds/security.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <utility>

namespace grip::platform::dds {

namespace {

namespace fs = std::filesystem;

std::string in(const fs::path& directory, const char* name) { return (directory / name).string(); }

std::string file_uri(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  return "file:" + (ec ? path : absolute.lexically_normal().string());
}

}  // namespace

SecurityFiles SecurityFiles::from_directory(const std::string& directory, const std::string& role) {
  fs::path dir(directory);
  std::error_code ec;
  if (!role.empty() && !fs::exists(dir / "identity.pem", ec) &&
      fs::exists(dir / role / "identity.pem", ec)) {
    dir /= role;
  }
  SecurityFiles files;
  files.ca_certificate = in(dir, "ca.pem");
  files.identity_certificate = in(dir, "identity.pem");
  files.private_key = in(dir, "identity.key");
  files.governance = in(dir, "governance.p7s");
  files.permissions = in(dir, "permissions.p7s");
  return files;
}

Status SecurityFiles::check() const {
  const std::pair<const char*, const std::string*> files[] = {
      {"CA certificate", &ca_certificate},
      {"identity certificate", &identity_certificate},
      {"private key", &private_key},
      {"governance", &governance},
      {"permissions", &permissions}};
  for (const auto& [what, path] : files) {
    if (path->empty()) return invalid_argument(std::string("DDS security: no ") + what + " given");
    // Opened, not only access()ed: a folder or an unreadable file is refused here, not by
    // Cyclone's plugins with a less telling message.
    std::ifstream file(*path);
    std::error_code ec;
    if (!file || fs::is_directory(*path, ec)) {
      const int err = errno;
      return invalid_argument(std::string("DDS security: cannot read the ") + what + " '" + *path +
                              "'" + (err != 0 ? std::string(": ") + std::strerror(err) : ""));
    }
  }
  return Ok{};
}

std::string SecurityFiles::directory() const {
  return fs::path(identity_certificate).parent_path().string();
}

Status set_security_properties(dds_qos_t* qos, const SecurityFiles& files) {
  if (Status checked = files.check(); !checked) return checked;
  // The plugins by their short names: Debian's libddsc finds them in its own folder.
  const std::pair<const char*, std::string> properties[] = {
      {"dds.sec.auth.library.path", "dds_security_auth"},
      {"dds.sec.auth.library.init", "init_authentication"},
      {"dds.sec.auth.library.finalize", "finalize_authentication"},
      {"dds.sec.crypto.library.path", "dds_security_crypto"},
      {"dds.sec.crypto.library.init", "init_crypto"},
      {"dds.sec.crypto.library.finalize", "finalize_crypto"},
      {"dds.sec.access.library.path", "dds_security_ac"},
      {"dds.sec.access.library.init", "init_access_control"},
      {"dds.sec.access.library.finalize", "finalize_access_control"},
      {"dds.sec.auth.identity_ca", file_uri(files.ca_certificate)},
      {"dds.sec.auth.identity_certificate", file_uri(files.identity_certificate)},
      {"dds.sec.auth.private_key", file_uri(files.private_key)},
      {"dds.sec.access.permissions_ca", file_uri(files.ca_certificate)},
      {"dds.sec.access.governance", file_uri(files.governance)},
      {"dds.sec.access.permissions", file_uri(files.permissions)},
  };
  for (const auto& [name, value] : properties) dds_qset_prop(qos, name, value.c_str());
  return Ok{};
}

namespace {

std::mutex& refusal_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::function<void(std::string_view, std::uint64_t)>& refusal_callback() {
  static std::function<void(std::string_view, std::uint64_t)> callback;
  return callback;
}
std::atomic<std::uint64_t> g_refusals{0};

extern "C" void trace_sink(void*, const dds_log_data_t* data) {
  const std::string_view line(data->message, data->size);
  if (line.find("not allowed") == std::string_view::npos) return;
  const std::uint64_t n = g_refusals.fetch_add(1) + 1;
  if (n > 20 && n % 100 != 0) return;
  std::lock_guard<std::mutex> lock(refusal_mutex());
  if (refusal_callback()) refusal_callback()(line, n);
}

}  // namespace

void on_refused_by_security(
    std::function<void(std::string_view line, std::uint64_t count)> on_refused) {
  std::lock_guard<std::mutex> lock(refusal_mutex());
  refusal_callback() = std::move(on_refused);
  dds_set_trace_sink(refusal_callback() ? &trace_sink : nullptr, nullptr);
}

std::string_view refusal_tracing_config() {
  return "<Tracing><Category>discovery</Category><OutputFile>/dev/null</OutputFile></Tracing>";
}

}  // namespace grip::platform::dds
