// Contract: a DriveBackend for any ROS 2 diff-drive base (TurtleBot3, Gazebo's diff drive
// plugin, a ros2_control diff_drive_controller) over plain Cyclone DDS: the agent's wheel ground
// speeds become one geometry_msgs/Twist on rt/<ns>/cmd_vel (agent::to_twist: linear.x =
// (left + right) / 2, angular.z = (right - left) / wheel_base, after the robot's trim), reliable
// (dds::ros_command_qos(), what nav2 and teleop write with). stop(), deactivate() and the
// destructor write a zero twist, so the base halts at once rather than at its own cmd_vel
// timeout. The base's own limits still apply; the robot YAML should not exceed them.
#pragma once

#include <atomic>
#include <string>

#include "smart/agent/interfaces.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/writer.hpp"

namespace smart::hw {

class RosTwistDrive : public agent::DriveBackend {
 public:
  // ns: the robot's ROS 2 namespace ("/robot_3"; dds::ros_namespace()).
  // trim: factors on each wheel's speed before the twist (RobotModel::trim).
  RosTwistDrive(const dds::Participant& participant, const std::string& ns, double wheel_base_m,
                agent::WheelFactors trim = {});
  ~RosTwistDrive() override;
  RosTwistDrive(const RosTwistDrive&) = delete;
  RosTwistDrive& operator=(const RosTwistDrive&) = delete;
  void set_wheel_speeds(agent::WheelSpeeds speeds) override;
  uint64_t commands() const { return commands_; }
  const std::string& topic() const { return ros_topic_; }

 private:
  double wheel_base_m_;
  agent::WheelFactors trim_;
  std::string ros_topic_;
  dds::Topic<geometry_msgs_msg_dds__Twist_> topic_;
  dds::Writer<geometry_msgs_msg_dds__Twist_> writer_;
  std::atomic<uint64_t> commands_{0};
};

}  // namespace smart::hw
