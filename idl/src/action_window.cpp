#include "smart/dds/action_window.hpp"

#include "smart/dds/sequence.hpp"

namespace smart::dds {

ActionWindowBuffer::ActionWindowBuffer(uint32_t robot_id, uint64_t run_id, uint32_t total_actions,
                                       std::vector<smart_msg_ActionStep> steps)
    : steps_(std::move(steps)) {
  msg_.robot_id = robot_id;
  msg_.run_id = run_id;
  msg_.total_actions = total_actions;
}

const smart_msg_ActionWindow& ActionWindowBuffer::view() {
  borrow(msg_.actions, steps_);
  return msg_;
}

std::vector<smart_msg_ActionStep> copy_steps(const smart_msg_ActionWindow& window) {
  return copy_of<smart_msg_ActionStep>(window.actions);
}

}  // namespace smart::dds
