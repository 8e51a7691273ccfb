// Contract: ActionWindowBuffer owns the steps of one robot's action window and exposes them as
// the idlc-generated smart_msg_ActionWindow (whose sequence borrows the buffer, _release=false),
// so writing a window needs no dds_alloc. copy_steps() copies a received (loaned) window out.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/dds/topics.hpp"

namespace smart::dds {

class ActionWindowBuffer {
 public:
  ActionWindowBuffer(uint32_t robot_id, uint64_t run_id, uint32_t total_actions,
                     std::vector<smart_msg_ActionStep> steps = {});
  std::vector<smart_msg_ActionStep>& steps() { return steps_; }
  // The view is valid until steps() is modified or the buffer is destroyed.
  const smart_msg_ActionWindow& view();

 private:
  std::vector<smart_msg_ActionStep> steps_;
  smart_msg_ActionWindow msg_{};
};

std::vector<smart_msg_ActionStep> copy_steps(const smart_msg_ActionWindow& window);

}  // namespace smart::dds
