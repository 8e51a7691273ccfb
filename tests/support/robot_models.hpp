// The robot models agent tests drive: the shipped footbot (config/robots/footbot.yaml).
#pragma once

#include <string>

#include "smart/agent/robot_model.hpp"

namespace smart::test {

inline agent::RobotModel footbot_model() {
  return agent::load_robot_model(std::string(SMART_SOURCE_DIR) + "/config/robots/footbot.yaml");
}

}  // namespace smart::test
