// Contract: waiting helpers shared by Writer and Reader; polling a status at a short interval is
// only used for rare events (matching), never on the data path.
#pragma once

#include <chrono>
#include <functional>
#include <thread>

namespace smart::dds {

// Polls `done` every 5 ms until it returns true or `timeout` passes; returns the last result.
inline bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace smart::dds
