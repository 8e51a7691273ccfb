// What the fault suite's rogues forge (tests/faults): shared so every case forges the same.
#pragma once

#include <cstdint>

#include "smart/dds/action_window.hpp"

namespace smart::test {

// A window sending robot 4 of `run` straight across the map (30 m), as a rogue would.
inline dds::ActionWindowBuffer forged_window(uint64_t run) {
  dds::ActionWindowBuffer w(4, run, 1);
  smart_msg_ActionStep step{};
  step.type = smart_msg_ACTION_MOVE;
  step.from = {1.0, 1.0, 2, 2};
  step.to = {30.0, 30.0, 60, 60};
  w.steps().push_back(step);
  return w;
}

}  // namespace smart::test
