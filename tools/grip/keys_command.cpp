// `grip keys init DIR`: the keys and signed documents DDS Security needs
// (platform/dds/security.hpp) for the planner, the vehicle, an operator and the one-process `grip
// explore`, made with the openssl command (run as a child process, never through a shell):
//   DIR/ca/ca.key, ca.pem    the CA (EC prime256v1); it signs the identities and the documents.
//                             Keep ca.key off the vehicle: it is needed only to sign again.
//   DIR/ROLE/                 one folder per role, the one `--security` takes (security.hpp):
//     ca.pem, identity.pem, identity.key (0600), governance.p7s, permissions.p7s
// The governance: unauthenticated participants not allowed, join access control, discovery,
// liveliness and every grip topic's data and metadata encrypted, read and write access
// controlled. The permissions (each role's certificate subject "CN=grip-ROLE,O=grip"):
//   planner   publishes plans, its status and map requests; subscribes to vehicle states, map
//             updates, goals and the vehicle's description
//   vehicle   the reverse (and it may set goals, as a vehicle's mission side does)
//   operator  publishes goals; subscribes to every grip topic (`grip goal`, `grip echo`)
//   explore   both sides: `grip explore` runs the planner and the simulator in one process, and
//             Cyclone 0.10 gives every participant of a domain in a process the first one's
//             permissions, so that process needs an identity allowed both (never deploy it)
// Documents are S/MIME signed with their content included, as DDS Security requires.

#include <sys/stat.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "child.hpp"
#include "commands.hpp"
#include "dds_config.hpp"
#include "grip/link/topics.hpp"

namespace grip::tools {

namespace {

namespace fs = std::filesystem;

struct KeysOptions {
  std::string dir;
  bool force = false;
  unsigned days = 365;
  int domain = -1;  // -1: every domain
  std::string topic_prefix;
};

// What each role publishes and subscribes to, by the topics' unprefixed names.
struct Role {
  const char* name;
  std::vector<const char*> publish;
  std::vector<const char*> subscribe;
};

std::vector<Role> roles() {
  using namespace link;
  const std::vector<const char*> all{kVehicleStateTopic,      kPlanTopic, kMapUpdateTopic,
                                     kMapRequestTopic,        kGoalTopic, kPlannerStatusTopic,
                                     kVehicleDescriptionTopic};
  return {
      {"planner",
       {kPlanTopic, kPlannerStatusTopic, kMapRequestTopic},
       {kVehicleStateTopic, kMapUpdateTopic, kGoalTopic, kVehicleDescriptionTopic}},
      {"vehicle",
       {kVehicleStateTopic, kMapUpdateTopic, kGoalTopic, kVehicleDescriptionTopic},
       {kPlanTopic, kPlannerStatusTopic, kMapRequestTopic}},
      {"operator", {kGoalTopic}, all},
      {"explore", all, all},
  };
}

// Runs openssl with `args`; its output goes to `log`, quoted in the error when it fails.
Status openssl(std::vector<std::string> args, const fs::path& log) {
  args.insert(args.begin(), "openssl");
  auto child = Child::spawn(args, {}, log.string(), /*with_stderr=*/true);
  if (!child) return child.error();
  if (const int status = child->wait(); status != 0) {
    std::ifstream in(log);
    std::stringstream said;
    said << in.rdbuf();
    return Error{ErrorCode::kIo, "openssl " + args[1] + " failed (status " +
                                     std::to_string(status) + "): " + said.str()};
  }
  return Ok{};
}

Status write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) return Error{ErrorCode::kIo, "cannot write " + path.string()};
  return Ok{};
}

std::string utc(std::chrono::system_clock::time_point t) {
  const std::time_t s = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  return text;
}

// Cyclone's access control refuses a document naming a domain id above 230.
constexpr int kMaxSecuredDomainId = 230;

std::string domains_xml(int domain) {
  return domain < 0 ? "<id_range><min>0</min><max>" + std::to_string(kMaxSecuredDomainId) +
                          "</max></id_range>"
                    : "<id>" + std::to_string(domain) + "</id>";
}

// The topic expressions of `base`: under the given prefix only, or without one the plain name
// and the name under any prefix (two vehicles on one domain, each its prefix).
std::vector<std::string> topic_expressions(const char* base, const std::string& prefix) {
  if (!prefix.empty()) return {prefix + "_" + base};
  return {base, std::string("*_") + base};
}

// One governance rule: every sample of the topics `expression` matches encrypted, and only
// participants with the permission may discover, read or write them.
std::string topic_rule(const std::string& expression) {
  return "        <topic_rule>\n          <topic_expression>" + expression +
         "</topic_expression>\n"
         "          <enable_discovery_protection>true</enable_discovery_protection>\n"
         "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
         "          <enable_read_access_control>true</enable_read_access_control>\n"
         "          <enable_write_access_control>true</enable_write_access_control>\n"
         "          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>\n"
         "          <data_protection_kind>ENCRYPT</data_protection_kind>\n"
         "        </topic_rule>\n";
}

std::string governance_xml(const KeysOptions& o) {
  std::string topics;
  for (const char* base :
       {link::kVehicleStateTopic, link::kPlanTopic, link::kMapUpdateTopic, link::kMapRequestTopic,
        link::kGoalTopic, link::kPlannerStatusTopic, link::kVehicleDescriptionTopic}) {
    for (const std::string& expression : topic_expressions(base, o.topic_prefix)) {
      topics += topic_rule(expression);
    }
  }
  // Any other topic: nobody may use it (read and write access controlled, and no permission
  // grants it).
  topics += topic_rule("*");
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<!-- grip's DDS Security governance, made by grip keys init -->\n"
         "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/"
         "omg_shared_ca_governance.xsd\">\n"
         "  <domain_access_rules>\n    <domain_rule>\n      <domains>" +
         domains_xml(o.domain) +
         "</domains>\n"
         "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
         "      <enable_join_access_control>true</enable_join_access_control>\n"
         "      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>\n"
         "      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>\n"
         "      <rtps_protection_kind>NONE</rtps_protection_kind>\n"
         "      <topic_access_rules>\n" +
         topics +
         "      </topic_access_rules>\n    </domain_rule>\n  </domain_access_rules>\n</dds>\n";
}

std::string subject(const Role& role) { return std::string("CN=grip-") + role.name + ",O=grip"; }

std::string permissions_xml(const KeysOptions& o, const Role& role) {
  const auto now = std::chrono::system_clock::now();
  const auto topic_list = [&](const std::vector<const char*>& bases) {
    std::string xml;
    for (const char* base : bases) {
      for (const std::string& expression : topic_expressions(base, o.topic_prefix)) {
        xml += "              <topic>" + expression + "</topic>\n";
      }
    }
    return xml;
  };
  const auto rule = [&](const char* kind, const std::vector<const char*>& bases) {
    return std::string("          <") + kind + ">\n            <topics>\n" + topic_list(bases) +
           "            </topics>\n            <partitions><partition>*</partition>"
           "</partitions>\n          </" +
           kind + ">\n";
  };
  // A day before now: a clock a little behind the signer's still accepts it.
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<!-- grip's DDS Security permissions of the " +
         std::string(role.name) +
         ", made by grip keys init -->\n"
         "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/"
         "omg_shared_ca_permissions.xsd\">\n"
         "  <permissions>\n    <grant name=\"grip_" +
         role.name + "\">\n      <subject_name>" + subject(role) +
         "</subject_name>\n      <validity>\n        <not_before>" +
         utc(now - std::chrono::hours(24)) + "</not_before>\n        <not_after>" +
         utc(now + std::chrono::hours(24) * o.days) +
         "</not_after>\n      </validity>\n      <allow_rule>\n        <domains>" +
         domains_xml(o.domain) + "</domains>\n" + rule("publish", role.publish) +
         rule("subscribe", role.subscribe) +
         "      </allow_rule>\n      <default>DENY</default>\n    </grant>\n  </permissions>\n"
         "</dds>\n";
}

// S/MIME signed by the CA, the content included (openssl's clear-signed multipart output).
Status sign(const fs::path& ca, const fs::path& in, const fs::path& out, const fs::path& log) {
  return openssl({"smime", "-sign", "-in", in.string(), "-text", "-out", out.string(), "-signer",
                  (ca / "ca.pem").string(), "-inkey", (ca / "ca.key").string()},
                 log);
}

Status make_key(const fs::path& key, const fs::path& log) {
  Status made = openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1",
                         "-out", key.string()},
                        log);
  if (!made) return made;
  fs::permissions(key, fs::perms::owner_read | fs::perms::owner_write);
  return Ok{};
}

const char* const kMadeHere[] = {"ca", "planner", "vehicle", "operator", "explore"};

Status refuse_overwrite(const KeysOptions& o) {
  std::error_code ec;
  if (!fs::exists(o.dir, ec)) return Ok{};
  if (!fs::is_directory(o.dir, ec)) return invalid_argument("'" + o.dir + "' is not a folder");
  if (fs::is_empty(o.dir, ec)) return Ok{};
  if (!o.force) {
    return invalid_argument("'" + o.dir +
                            "' is not empty: grip keys init does not overwrite keys (--force "
                            "replaces what it made there)");
  }
  for (const char* made : kMadeHere) fs::remove_all(fs::path(o.dir) / made, ec);
  return Ok{};
}

Status init_keys(const KeysOptions& o) {
  if (Status ok = refuse_overwrite(o); !ok) return ok;
  if (Status ok = link::check_topic_prefix(o.topic_prefix); !ok) return ok;
  const fs::path dir(o.dir);
  const fs::path ca = dir / "ca";
  std::error_code ec;
  fs::create_directories(ca, ec);
  if (ec) return Error{ErrorCode::kIo, "cannot make " + ca.string() + ": " + ec.message()};
  fs::permissions(ca, fs::perms::owner_all, ec);
  const fs::path log = ca / "openssl.log";
  const std::string days = std::to_string(o.days);
  if (Status s = make_key(ca / "ca.key", log); !s) return s;
  if (Status s = openssl({"req", "-new", "-x509", "-key", (ca / "ca.key").string(), "-out",
                          (ca / "ca.pem").string(), "-days", days, "-subj", "/O=grip/CN=grip CA"},
                         log);
      !s) {
    return s;
  }
  const fs::path governance = ca / "governance.xml";
  if (Status s = write_text(governance, governance_xml(o)); !s) return s;
  if (Status s = sign(ca, governance, ca / "governance.p7s", log); !s) return s;
  std::cout << "grip keys init: in " << dir.string() << "\n  ca/ca.key, ca/ca.pem: the CA (keep "
            << "ca.key off the vehicles)\n  ca/governance.xml, signed as each role's "
            << "governance.p7s\n";
  unsigned serial = 1;
  for (const Role& role : roles()) {
    const fs::path folder = dir / role.name;
    fs::create_directories(folder, ec);
    if (ec) return Error{ErrorCode::kIo, "cannot make " + folder.string() + ": " + ec.message()};
    if (Status s = make_key(folder / "identity.key", log); !s) return s;
    const fs::path csr = ca / (std::string(role.name) + ".csr");
    if (Status s = openssl({"req", "-new", "-key", (folder / "identity.key").string(), "-out",
                            csr.string(), "-subj", std::string("/O=grip/CN=grip-") + role.name},
                           log);
        !s) {
      return s;
    }
    if (Status s =
            openssl({"x509", "-req", "-in", csr.string(), "-CA", (ca / "ca.pem").string(), "-CAkey",
                     (ca / "ca.key").string(), "-set_serial", std::to_string(++serial), "-days",
                     days, "-out", (folder / "identity.pem").string()},
                    log);
        !s) {
      return s;
    }
    fs::remove(csr, ec);
    const fs::path permissions = ca / (std::string(role.name) + "-permissions.xml");
    if (Status s = write_text(permissions, permissions_xml(o, role)); !s) return s;
    if (Status s = sign(ca, permissions, folder / "permissions.p7s", log); !s) return s;
    fs::copy_file(ca / "ca.pem", folder / "ca.pem", fs::copy_options::overwrite_existing, ec);
    if (!ec) {
      fs::copy_file(ca / "governance.p7s", folder / "governance.p7s",
                    fs::copy_options::overwrite_existing, ec);
    }
    if (ec)
      return Error{ErrorCode::kIo, "cannot copy into " + folder.string() + ": " + ec.message()};
    std::cout << "  " << role.name << "/: identity.pem (" << subject(role)
              << "), identity.key (0600), permissions.p7s, ca.pem, governance.p7s\n";
  }
  fs::remove(log, ec);
  std::cout << "valid for " << o.days << " days, "
            << (o.domain < 0 ? std::string("every domain") : "domain " + std::to_string(o.domain))
            << ", topics "
            << (o.topic_prefix.empty() ? std::string("of any prefix") : o.topic_prefix + "_*")
            << ". Give each command its role's folder: grip planner --security " << o.dir
            << "/planner (or " << o.dir << ": each command takes its own role)\n";
  return Ok{};
}

}  // namespace

void register_keys_command(CLI::App& app) {
  CLI::App* keys = app.add_subcommand("keys", "DDS Security keys and signed documents");
  keys->require_subcommand(1);
  auto o = std::make_shared<KeysOptions>();
  CLI::App* init = keys->add_subcommand(
      "init",
      "Make a CA, an identity for the planner, the vehicle, an operator and grip explore, the "
      "governance and each one's permissions, signed (openssl)");
  init->add_option("DIR", o->dir, "Folder to write them to (made if missing)")->required();
  init->add_flag("--force", o->force, "Replace the keys an earlier grip keys init made in DIR");
  init->add_option("--days", o->days, "Validity of the certificates and permissions, in days")
      ->check(CLI::Range(1U, 36500U))
      ->capture_default_str();
  init->add_option("--domain", o->domain,
                   "The one DDS domain allowed, up to 230 (default: every domain up to 230)")
      ->check(CLI::Range(0, kMaxSecuredDomainId));
  add_topic_prefix_option(*init, o->topic_prefix, "none: topics of any prefix");
  init->callback([o]() {
    if (Status s = init_keys(*o); !s) {
      std::cerr << "grip keys init: " << s.error().message << "\n";
      throw CLI::RuntimeError(2);
    }
  });
}

}  // namespace grip::tools
