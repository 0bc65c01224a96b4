#include "dds_config.hpp"

#include <unistd.h>

#include <cstdlib>

#include "grip/link/topics.hpp"

namespace grip::tools {

Result<std::string> choose_dds_config(const std::string& dds_config_option) {
  if (!dds_config_option.empty()) {
    if (access(dds_config_option.c_str(), R_OK) != 0) {
      return invalid_argument("cannot read the Cyclone DDS configuration '" + dds_config_option +
                              "'");
    }
    return "file://" + dds_config_option;
  }
  if (const char* uri = std::getenv("CYCLONEDDS_URI"); uri != nullptr && *uri != '\0') {
    return std::string(uri);
  }
  return std::string();
}

void add_dds_config_option(CLI::App& command, std::string& dds_config_option) {
  command.add_option("--dds-config", dds_config_option,
                     "Cyclone DDS XML configuration file (default: $CYCLONEDDS_URI, else the "
                     "built-in loopback-only one)");
}

void add_link_options(CLI::App& command, std::uint32_t& domain, std::string& dds_config_option) {
  command.add_option("--domain", domain, "DDS domain id")
      ->check(CLI::Range(0U, kMaxDomainId))
      ->capture_default_str();
  add_dds_config_option(command, dds_config_option);
}

CLI::Validator topic_prefix_validator() {
  return CLI::Validator(
      [](const std::string& value) {
        const Status checked = link::check_topic_prefix(value);
        return checked.ok() ? std::string() : checked.error().message;
      },
      "PREFIX");
}

Result<std::optional<platform::dds::SecurityFiles>> security_files(const std::string& directory,
                                                                   const char* role) {
  if (directory.empty()) return std::optional<platform::dds::SecurityFiles>();
  platform::dds::SecurityFiles files =
      platform::dds::SecurityFiles::from_directory(directory, role);
  if (Status checked = files.check(); !checked) return checked.error();
  return std::optional<platform::dds::SecurityFiles>(std::move(files));
}

void log_refused_peers(std::function<void(const std::string&)> warn) {
  platform::dds::on_refused_by_security(
      [warn = std::move(warn)](std::string_view line, std::uint64_t count) {
        warn("DDS Security refused a peer (" + std::to_string(count) +
             " refusals so far; the first 20 and every 100th are logged): " + std::string(line));
      });
}

std::string unauthenticated_link_warning() {
  return "THE LINK IS UNAUTHENTICATED AND UNENCRYPTED: any participant on this DDS domain can "
         "read the plans and send this side plans, states, maps and goals. Give --security DIR "
         "(or link.security_dir; grip keys init DIR makes the keys)";
}

Result<platform::dds::Participant> join_domain(std::uint32_t domain,
                                               const std::string& dds_config_option,
                                               const std::string& security_dir) {
  const Result<std::string> config = choose_dds_config(dds_config_option);
  if (!config) return config.error();
  auto security = security_files(security_dir, "operator");
  if (!security) return security.error();
  return platform::dds::Participant::create(domain, *config, *security);
}

}  // namespace grip::tools
