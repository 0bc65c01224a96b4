#pragma once
// Which Cyclone configuration a command that talks to a vehicle or a planner on a real network
// uses (`grip planner`, `grip echo`, `grip goal`): the file given with --dds-config (for
// `grip planner`, else its parameter file's link.dds_config), else the CYCLONEDDS_URI of the
// environment, as Cyclone users expect, else the project's loopback-only configuration.
// `grip explore` and the benchmarks always stay on loopback, and `grip sim` unless given
// --dds-config (`grip bench faults` runs it in a network namespace of its own).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "grip/common/result.hpp"
#include "grip/params/params.hpp"
#include "grip/platform/dds/participant.hpp"

namespace grip::tools {

// For Participant::create: a file:// URI, the environment's value, or empty (the built-in
// loopback configuration). Refuses a configuration file that cannot be read, naming it.
Result<std::string> choose_dds_config(const std::string& dds_config_option);

using params::kMaxDomainId;

// The --dds-config option of a command on a real link.
void add_dds_config_option(CLI::App& command, std::string& dds_config_option);
// The --domain and --dds-config options of a command on a real link.
void add_link_options(CLI::App& command, std::uint32_t& domain, std::string& dds_config_option);

// The check of a --topic-prefix value as the command line is parsed (link::check_topic_prefix).
CLI::Validator topic_prefix_validator();

// --topic-prefix: the prefix of every grip topic name (link/topics.hpp), so that two vehicles
// can share a domain. Into a std::string, or a std::optional<std::string> that stays unset
// without the option; `default_text` says what holds then.
template <typename T>
void add_topic_prefix_option(CLI::App& command, T& topic_prefix, const std::string& default_text) {
  command
      .add_option("--topic-prefix", topic_prefix,
                  "Prefix of every grip topic name (\"a\": a_grip_plan, ...), so that two vehicles "
                  "can share a domain (default: " +
                      default_text + ")")
      ->check(topic_prefix_validator());
}

// --security DIR: DDS Security with the keys of DIR (platform/dds/security.hpp, made by
// `grip keys init`). Into a std::string or a std::optional<std::string>.
template <typename T>
void add_security_option(CLI::App& command, T& security_dir, const std::string& default_text) {
  command.add_option("--security", security_dir,
                     "DDS Security: authenticate, encrypt and keep to the permissions of the "
                     "keys in DIR (grip keys init DIR makes them; DIR or its folder of this "
                     "command's role; default: " +
                         default_text + ")");
}

// The security files of `directory` for a command of `role` ("planner", "vehicle", "operator",
// "explore": the subfolder taken when `directory` is the one `grip keys init` made), checked;
// none for an empty `directory`. A missing or unreadable file is refused, named.
Result<std::optional<platform::dds::SecurityFiles>> security_files(const std::string& directory,
                                                                   const char* role);

// Cyclone's refusals of peers (platform::dds::on_refused_by_security) as warnings through `warn`
// (thread-safe), for a command whose link is secured.
void log_refused_peers(std::function<void(const std::string&)> warn);

// The start-up warning of a command whose link runs without DDS Security.
std::string unauthenticated_link_warning();

// A participant of an operator tool (`grip echo`, `grip goal`) on `domain`, with the
// configuration chosen above and the operator's keys of `security_dir` (empty: none); a bad
// option is an ErrorCode::kInvalidArgument.
Result<platform::dds::Participant> join_domain(std::uint32_t domain,
                                               const std::string& dds_config_option,
                                               const std::string& security_dir = {});

}  // namespace grip::tools
