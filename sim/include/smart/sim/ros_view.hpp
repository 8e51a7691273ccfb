// Contract: the fleet as ROS 2 tools see it (docs/architecture.md, "ROS 2 view"; topic names and
// frames in smart/dds/topics.hpp). publish() writes, from the World's current poses and sim
// time: rt/smart/poses (geometry_msgs/PoseArray, robot i at index i), rt/tf
// (tf2_msgs/TFMessage, "map" -> "robot_<i>" for every robot) and, for the robots chosen at
// construction, rt/robot_<i>/pose (geometry_msgs/PoseStamped). Stamps are sim time. The writers
// use the profile's state QoS (best effort, keep last), like rmw's sensor-data profile.
// publish_map() writes the grid once as rt/map (nav_msgs/OccupancyGrid), reliable and transient
// local so that a viewer started later still gets it (map_server's QoS). The messages are built
// by record/ros_messages.hpp, which recordings share. Every topic is under `ros_namespace`
// ("" or e.g. "/run_a", dds::ros_view_topic), so two runs on one domain can be told apart.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ros2.h"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/writer.hpp"
#include "smart/grid/grid.hpp"
#include "smart/record/ros_messages.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim {

// ROS time and heading quaternions: shared with the monitor's plan view (smart/dds/topics.hpp).
using dds::ros_stamp;
using dds::yaw_quaternion;
using record::occupancy_cells;

class RosView {
 public:
  // Throws std::invalid_argument for a chosen robot id >= robots or an invalid namespace.
  RosView(const dds::Participant& participant, const dds::QosProfile& qos, std::size_t robots,
          const std::vector<uint32_t>& pose_robots, const std::string& ros_namespace = "");
  void publish(const World& world);
  void publish_map(const grid::Grid& grid, double cell_m);

 private:
  dds::Topic<geometry_msgs_msg_dds__PoseArray_> poses_topic_;
  dds::Writer<geometry_msgs_msg_dds__PoseArray_> poses_;
  dds::Topic<tf2_msgs_msg_dds__TFMessage_> tf_topic_;
  dds::Writer<tf2_msgs_msg_dds__TFMessage_> tf_;
  dds::Topic<nav_msgs_msg_dds__OccupancyGrid_> map_topic_;
  dds::Writer<nav_msgs_msg_dds__OccupancyGrid_> map_;
  std::vector<uint32_t> pose_robots_;
  std::vector<dds::Topic<geometry_msgs_msg_dds__PoseStamped_>> pose_topics_;
  std::vector<dds::Writer<geometry_msgs_msg_dds__PoseStamped_>> pose_writers_;
  std::string ns_;
  record::FleetMessages fleet_;
};

}  // namespace smart::sim
