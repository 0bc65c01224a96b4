#include "grip/platform/dds/entity.hpp"

#include "grip/platform/dds/error.hpp"

namespace grip::platform::dds {

Status Entity::reset() noexcept {
  const dds_entity_t handle = release();
  if (handle <= 0) return Ok{};
  const dds_return_t rc = dds_delete(handle);
  // Already deleted with its parent (the participant deletes its children): done.
  if (rc == DDS_RETCODE_BAD_PARAMETER || rc == DDS_RETCODE_ALREADY_DELETED) return Ok{};
  return check(rc, "dds_delete");
}

}  // namespace grip::platform::dds
