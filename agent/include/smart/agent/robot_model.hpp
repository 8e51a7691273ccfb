// Contract: a robot's physical model and kinodynamic limits plus its controller gains, read
// from YAML (config/robots/<name>.yaml) strictly: unknown keys, missing keys and out-of-range
// values throw config::ConfigError naming file:line:column and the accepted range.
#pragma once

#include <string>

#include "smart/agent/types.hpp"
#include "smart/agent/uncertainty.hpp"

namespace smart::agent {

struct ControllerGains {
  double heading_kp = 4.0;      // 1/s: yaw error -> turn rate
  double heading_kd = 0.0;      // s: yaw rate damping
  double cross_track_kp = 1.5;  // 1/m: lateral error -> heading correction (atan)
  double distance_kp = 2.0;     // 1/s: final approach speed per metre left
  double position_tolerance_m = 0.01;
  double heading_tolerance_rad = 0.0087;  // 0.5°
  // Smallest wheel speed that moves the robot (motor dead band, PWM resolution); a rotation
  // that is not done turns at least this fast. 0 for ideal motors.
  double min_wheel_speed_mps = 0.0;
  bool operator==(const ControllerGains&) const = default;
};

struct RobotModel {
  std::string name;
  double radius_m = 0.085;
  double mass_kg = 1.6;
  double wheel_base_m = 0.14;
  double wheel_radius_m = 0.029;
  double max_speed_mps = 1.0;  // forward speed limit
  double max_accel_mps2 = 0.4;
  double max_decel_mps2 = 0.4;
  double max_turn_rate_radps = 0.5236;  // 30°/s
  double max_angular_accel_radps2 = 2.0;
  ControllerGains gains;
  Uncertainty uncertainty;  // optional `uncertainty:` section (uncertainty.hpp); none by default
  // Optional `trim: {left, right}` (0.5..1): factors on each wheel's commanded speed for a base
  // with a mismatched wheel, proposed by `smart calibrate trim`; applied by drives that take a
  // twist (ROS 2). A JetBot trims at its board instead (hardware: left/right alpha).
  WheelFactors trim;
  bool operator==(const RobotModel&) const = default;
};

RobotModel parse_robot_model(const std::string& yaml_text, const std::string& source);
RobotModel load_robot_model(const std::string& path);

}  // namespace smart::agent
