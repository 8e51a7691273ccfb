// Contract: Entity owns one Cyclone DDS entity handle and deletes it (and so its children) when
// destroyed. Move-only; a moved-from Entity holds no handle.
#pragma once

#include <dds/dds.h>

#include <utility>

namespace smart::dds {

class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  Entity(Entity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}
  Entity& operator=(Entity&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, 0);
    }
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  ~Entity() { reset(); }

  dds_entity_t handle() const { return handle_; }
  explicit operator bool() const { return handle_ > 0; }

  void reset() {
    // The handle may already be gone when a parent was deleted first; that error is harmless.
    if (handle_ > 0) (void)dds_delete(handle_);
    handle_ = 0;
  }

 private:
  dds_entity_t handle_ = 0;
};

}  // namespace smart::dds
