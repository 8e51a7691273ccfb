// Contract: what a lifecycle call (configure, activate, deactivate) of an agent or a drive
// backend returns, as ros2_control's hardware components do (hardware_interface::CallbackReturn,
// SUCCESS / FAILURE / ERROR; control.ros.org, "Hardware Components", Lifecycle): kSuccess, the
// component is in the next state; kFailure, it stays where it was and the call may be retried
// (e.g. activate before configure); kError, it is unusable (a device that does not answer) and
// the caller shuts down. A call that does not succeed says what happened and how to fix it.
// Lifecycle calls return this instead of throwing, so every caller has an explicit failure path.
#pragma once

#include <string>
#include <utility>

namespace smart::agent {

enum class CallbackReturn { kSuccess, kFailure, kError };

struct [[nodiscard]] LifecycleResult {
  CallbackReturn code = CallbackReturn::kSuccess;
  std::string message;  // empty on success

  bool ok() const { return code == CallbackReturn::kSuccess; }
  static LifecycleResult success() { return {}; }
  static LifecycleResult failure(std::string why) {
    return {CallbackReturn::kFailure, std::move(why)};
  }
  static LifecycleResult error(std::string why) { return {CallbackReturn::kError, std::move(why)}; }
};

}  // namespace smart::agent
