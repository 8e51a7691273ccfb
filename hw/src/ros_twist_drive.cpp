#include "smart/hw/ros_twist_drive.hpp"

#include <spdlog/spdlog.h>

#include "smart/agent/kinematics.hpp"

namespace smart::hw {

RosTwistDrive::RosTwistDrive(const dds::Participant& participant, const std::string& ns,
                             double wheel_base_m, agent::WheelFactors trim)
    : wheel_base_m_(wheel_base_m),
      trim_(trim),
      ros_topic_(dds::ros_cmd_vel_topic(ns)),
      topic_(participant, dds::ros_topic(ros_topic_)),
      writer_(participant, topic_, dds::ros_command_qos().to_dds()) {}

RosTwistDrive::~RosTwistDrive() {
  try {
    stop();
  } catch (const std::exception& e) {
    spdlog::warn("{}: could not write the zero twist on shutdown: {}", ros_topic_, e.what());
  }
}

void RosTwistDrive::set_wheel_speeds(agent::WheelSpeeds speeds) {
  speeds.left_mps *= trim_.left;
  speeds.right_mps *= trim_.right;
  const agent::Twist t = agent::to_twist(speeds, wheel_base_m_);
  geometry_msgs_msg_dds__Twist_ m{};
  m.linear.x = t.linear_mps;
  m.angular.z = t.angular_radps;
  writer_.write(m);
  ++commands_;
}

}  // namespace smart::hw
