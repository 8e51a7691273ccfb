// An emulated JetBot opened the way `smart agent --i2c emulated` opens one (hw/robot_io.hpp): at
// (0.5, 0.5) facing +x, its Vicon stream to this process on a free port, with optional wheel
// gains (a weak or backwards wheel). For tests of what runs on a robot's hardware.
#pragma once

#include <vector>

#include "smart/agent/robot_model.hpp"
#include "smart/hw/robot_io.hpp"

namespace smart::test {

// `model`, when given, receives the robot file's model.
inline hw::RobotIo open_emulated_jetbot(const dds::Participant& participant,
                                        std::vector<double> wheel_gains = {},
                                        agent::RobotModel* model = nullptr) {
  hw::RobotIoOptions o;
  o.i2c = "emulated";
  o.emulate_pose = {0.5, 0.5, 0.0};
  o.emulate_wheel_gains = std::move(wheel_gains);
  const auto file = hw::robot_file(o);
  const auto m = agent::load_robot_model(file);
  if (model != nullptr) *model = m;
  return hw::open_robot(o, 0, m, file, participant);
}

}  // namespace smart::test
