#pragma once
// One RAII owner per dds_entity_t: deletes it exactly once, move-only.
//
// Cyclone deletes an entity's children with it (a participant takes its topics, readers and
// writers along). A child's owner may therefore outlive the entity itself; its later
// dds_delete returns BAD_PARAMETER or ALREADY_DELETED, which the destructor treats as done.

#include <dds/dds.h>

#include "grip/common/result.hpp"

namespace grip::platform::dds {

class Entity {
 public:
  Entity() noexcept = default;
  explicit Entity(dds_entity_t handle) noexcept : handle_(handle) {}
  ~Entity() { static_cast<void>(reset()); }  // failures cannot be reported here

  Entity(Entity&& other) noexcept : handle_(other.release()) {}
  Entity& operator=(Entity&& other) noexcept {
    if (this != &other) {
      static_cast<void>(reset());
      handle_ = other.release();
    }
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;

  dds_entity_t get() const noexcept { return handle_; }
  bool valid() const noexcept { return handle_ > 0; }
  explicit operator bool() const noexcept { return valid(); }

  // Gives up ownership without deleting.
  dds_entity_t release() noexcept {
    const dds_entity_t handle = handle_;
    handle_ = 0;
    return handle;
  }

  // Deletes the entity now (if any). An entity already deleted through its parent counts as
  // deleted; any other failure is returned (the handle is dropped either way).
  Status reset() noexcept;

 private:
  dds_entity_t handle_ = 0;
};

}  // namespace grip::platform::dds
