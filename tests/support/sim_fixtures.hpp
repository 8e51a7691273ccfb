// Small fixtures shared by the sim/ tests.
#pragma once

#include <string>

#include "smart/agent/robot_model.hpp"

namespace smart::test {

// A 10 kg disc of radius 0.2 m on a 0.3 m wheel base, 1 m/s and 1 m/s² (the fleet and shard
// tests' robot).
inline agent::RobotModel sim_test_model(const std::string& name = "test") {
  agent::RobotModel m;
  m.name = name;
  m.radius_m = 0.2;
  m.mass_kg = 10;
  m.wheel_base_m = 0.3;
  m.max_speed_mps = 1.0;
  m.max_accel_mps2 = 1.0;
  m.max_decel_mps2 = 1.0;
  return m;
}

}  // namespace smart::test
