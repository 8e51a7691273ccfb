// Contract: seconds on the monotonic clock (CLOCK_MONOTONIC through std::chrono::steady_clock),
// the wall-time base of robots' control loops, pose stamps and bring-up trials. Never sim time.
#pragma once

#include <chrono>

namespace smart::common {

inline double steady_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace smart::common
