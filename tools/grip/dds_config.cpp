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

Result<platform::dds::Participant> join_domain(std::uint32_t domain,
                                               const std::string& dds_config_option) {
  const Result<std::string> config = choose_dds_config(dds_config_option);
  if (!config) return config.error();
  return platform::dds::Participant::create(domain, *config);
}

}  // namespace grip::tools
