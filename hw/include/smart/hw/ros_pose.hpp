// Contract: a PoseSource fed by a ROS 2 topic read over plain Cyclone DDS (DDS topic
// "rt/<topic>", rmw type names, best effort: dds::ros_sensor_qos()):
// - kPoseStamped: geometry_msgs/PoseStamped from a mocap driver (vrpn_mocap, mocap4ros2 relays);
// - kOdometry: nav_msgs/Odometry from a ROS 2 diff-drive base (TurtleBot3, Gazebo), its
//   pose.pose part.
// Samples arrive on a listener thread and only the latest is kept; read() never blocks and
// reports a pose older than max_age_s as invalid (the agent then stops: its stale-pose watchdog).
// Heading from the quaternion (geometry::yaw_of); position and heading are mapped into the
// world frame by `transform` (a `smart calibrate` transform file; identity for metres already in
// the grid's frame).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "smart/agent/interfaces.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/geometry/frame_transform.hpp"

namespace smart::hw {

class RosPoseSource : public agent::PoseSource {
 public:
  enum class Message { kPoseStamped, kOdometry };
  RosPoseSource(const dds::Participant& participant, const std::string& ros_topic,
                geometry::FrameTransform transform, double max_age_s, std::function<double()> now_s,
                Message message = Message::kPoseStamped);
  // Listeners that fire while the readers are being deleted return at once (the Reader's
  // trampoline also catches a take that fails then).
  ~RosPoseSource() override { ready_ = false; }
  agent::PoseSample read() override;
  uint64_t samples() const;

 private:
  void accept(const geometry_msgs_msg_dds__Pose_& pose);
  geometry::FrameTransform transform_;
  double max_age_s_;
  std::function<double()> now_s_;
  mutable std::mutex mutex_;
  std::optional<agent::PoseSample> latest_;
  uint64_t samples_ = 0;
  std::atomic<bool> ready_{false};  // the listener runs only once the reader is in place
  std::optional<dds::Topic<geometry_msgs_msg_dds__PoseStamped_>> pose_topic_;
  std::optional<dds::Topic<nav_msgs_msg_dds__Odometry_>> odom_topic_;
  std::unique_ptr<dds::Reader<geometry_msgs_msg_dds__PoseStamped_>> pose_reader_;
  std::unique_ptr<dds::Reader<nav_msgs_msg_dds__Odometry_>> odom_reader_;
};

}  // namespace smart::hw
