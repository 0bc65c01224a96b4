#include "grip/platform/dds/error.hpp"

#include <string>

namespace grip::platform::dds {

DdsError make_dds_error(dds_return_t rc, const char* call) {
  return DdsError{rc,
                  std::string(call) + ": " + dds_strretcode(rc) + " (" + std::to_string(rc) + ")"};
}

Error to_error(const DdsError& error) {
  ErrorCode code = ErrorCode::kIo;
  if (error.code == DDS_RETCODE_BAD_PARAMETER) code = ErrorCode::kInvalidArgument;
  if (error.code == DDS_RETCODE_OUT_OF_RESOURCES) code = ErrorCode::kCapacity;
  return Error{code, error.message};
}

Status check(dds_return_t rc, const char* call) {
  if (rc < 0) return to_error(make_dds_error(rc, call));
  return Ok{};
}

Result<dds_entity_t> check_entity(dds_entity_t entity, const char* call) {
  if (entity < 0) return to_error(make_dds_error(entity, call));
  return entity;
}

}  // namespace grip::platform::dds
