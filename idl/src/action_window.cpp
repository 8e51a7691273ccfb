#include "smart/dds/action_window.hpp"

namespace smart::dds {

ActionWindowBuffer::ActionWindowBuffer(uint32_t robot_id, uint64_t run_id, uint32_t total_actions,
                                       std::vector<smart_msg_ActionStep> steps)
    : steps_(std::move(steps)) {
  msg_.robot_id = robot_id;
  msg_.run_id = run_id;
  msg_.total_actions = total_actions;
}

const smart_msg_ActionWindow& ActionWindowBuffer::view() {
  msg_.actions._buffer = steps_.data();
  msg_.actions._length = static_cast<uint32_t>(steps_.size());
  msg_.actions._maximum = static_cast<uint32_t>(steps_.size());
  msg_.actions._release = false;  // the vector owns the memory, not Cyclone
  return msg_;
}

std::vector<smart_msg_ActionStep> copy_steps(const smart_msg_ActionWindow& window) {
  return std::vector<smart_msg_ActionStep>(window.actions._buffer,
                                           window.actions._buffer + window.actions._length);
}

}  // namespace smart::dds
