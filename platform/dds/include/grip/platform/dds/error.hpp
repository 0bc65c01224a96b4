#pragma once
// The one place where Cyclone DDS return codes become grip errors. In the C API a negative
// return is an error (a dds_return_t, or a negative dds_entity_t); dds_strretcode names it.
// The message is built only when a call fails, never on a successful path.

#include <dds/dds.h>

#include <string>

#include "grip/common/result.hpp"

namespace grip::platform::dds {

// A failed DDS call: the raw return code and "<call>: <dds_strretcode text> (<code>)".
struct DdsError {
  dds_return_t code;
  std::string message;
};

DdsError make_dds_error(dds_return_t rc, const char* call);

// Maps a DDS error to a grip::Error (bad parameter -> kInvalidArgument, out of resources ->
// kCapacity, anything else -> kIo); the message keeps the dds_strretcode text and the code.
Error to_error(const DdsError& error);

// rc >= 0 is success. `call` names the DDS function, e.g. "dds_create_topic".
Status check(dds_return_t rc, const char* call);

// Reads one communication status of an entity (dds_get_*_status), checked like every call.
template <typename StatusT>
Result<StatusT> read_status(dds_return_t (*get)(dds_entity_t, StatusT*), dds_entity_t entity,
                            const char* call) {
  StatusT status{};
  Status rc = check(get(entity, &status), call);
  if (!rc.ok()) return rc.error();
  return status;
}

// For calls that return an entity handle (negative = error code).
Result<dds_entity_t> check_entity(dds_entity_t entity, const char* call);

}  // namespace grip::platform::dds
