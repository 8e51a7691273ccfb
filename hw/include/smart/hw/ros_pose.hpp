// Contract: a PoseSource fed by a ROS 2 geometry_msgs/PoseStamped topic (vrpn_mocap,
// mocap4ros2 relays, any ROS 2 mocap driver) read over plain Cyclone DDS: DDS topic
// "rt/<topic>", type geometry_msgs::msg::dds_::PoseStamped_, best effort (a reliable reader
// would not match vrpn_mocap's sensor-data QoS). Samples arrive on a listener thread and only
// the latest is kept; read() never blocks. Yaw comes from the quaternion (atan2), position is
// mapped into the world frame by the same transform as Vicon (scale 1 for metres).
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "smart/agent/interfaces.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/hw/vicon.hpp"

namespace smart::hw {

class RosPoseSource : public agent::PoseSource {
 public:
  RosPoseSource(const dds::Participant& participant, const std::string& ros_topic,
                ViconTransform transform, double max_age_s, std::function<double()> now_s);
  agent::PoseSample read() override;
  uint64_t samples() const;

 private:
  void on_data();
  ViconTransform transform_;
  double max_age_s_;
  std::function<double()> now_s_;
  mutable std::mutex mutex_;
  std::optional<agent::PoseSample> latest_;
  uint64_t samples_ = 0;
  dds::Topic<geometry_msgs_msg_dds__PoseStamped_> topic_;
  std::unique_ptr<dds::Reader<geometry_msgs_msg_dds__PoseStamped_>> reader_;
};

}  // namespace smart::hw
