#pragma once
// DDS Security for a participant: the files of one identity (its certificate and key, the CA
// that signed them, the domain's governance and the identity's permissions), handed to
// Cyclone's authentication, access-control and cryptography plugins (libddsc0debian ships them)
// as the participant's QoS properties dds.sec.*.
//
// A security directory holds one identity, laid out as `grip keys init` writes each role's:
//   ca.pem           the CA certificate (identity CA and permissions CA: one CA signs both)
//   identity.pem     this participant's certificate, signed by the CA
//   identity.key     its private key (mode 0600)
//   governance.p7s   the domain's rules, S/MIME signed by the CA with the content included
//   permissions.p7s  what this identity may publish and subscribe, S/MIME signed likewise
// from_directory() also accepts the folder `grip keys init` made, and then takes the role's
// subfolder (`keys/` -> `keys/planner/`).
//
// Cyclone 0.10 applies the security settings of the first participant of a domain in a process
// to every later one of that domain in the process, and does not enforce access control
// between participants of one process: a process is one identity.

#include <dds/dds.h>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip::platform::dds {

struct SecurityFiles {
  std::string ca_certificate;
  std::string identity_certificate;
  std::string private_key;
  std::string governance;
  std::string permissions;

  // The files of `directory` (absolute paths when `directory` is); if it has no identity.pem but
  // a subfolder `role` does, that subfolder's. Nothing is read here: check() does.
  static SecurityFiles from_directory(const std::string& directory, const std::string& role = {});

  // Ok when every file can be read; otherwise kInvalidArgument naming the first that cannot
  // ("DDS security: cannot read the permissions '/etc/grip/security/permissions.p7s': No such
  // file or directory").
  Status check() const;

  // The directory the files are in (that of the identity certificate).
  std::string directory() const;
};

// Sets the dds.sec.* properties of `qos` for `files` (paths made absolute, as file: URIs).
Status set_security_properties(dds_qos_t* qos, const SecurityFiles& files);

// Cyclone says that it refused a remote participant's endpoint ("Non secure remote writer ... is
// not allowed", "... not allowed by security") only in its discovery trace. A secured domain on
// the built-in loopback configuration traces that category (to no file); this passes its refusal
// lines to `on_refused` (from Cyclone's threads: it must be thread-safe), the first 20 and then
// every 100th, with how many there were so far. Process-wide; empty: none.
void on_refused_by_security(
    std::function<void(std::string_view line, std::uint64_t count)> on_refused);

// The tracing that makes those lines, for a secured domain's configuration.
std::string_view refusal_tracing_config();

}  // namespace grip::platform::dds
