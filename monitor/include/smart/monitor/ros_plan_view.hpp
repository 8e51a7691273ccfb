// Contract: the monitor's ROS 2 plan view for rviz2 (idl/smart.idl, "The plan as rviz2 sees
// it"), a thin edge over plan_view.hpp: publish_paths() writes every robot's planned path once
// (nav_msgs/Path, transient local); publish() writes one MarkerArray with the robots at their
// last reported poses coloured by activity (green moving, orange waiting, grey done), their goals,
// and an arrow per current Type-2 wait, after a DELETEALL of the old arrows. Frame "map", as the
// sim host's ROS view and OccupancyGrid. config/rviz/smart.rviz shows all of it. Paths are built
// by record/ros_messages.hpp (shared with recordings); every topic is under `ros_namespace`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "smart/common/pose.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/writer.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/monitor/plan_view.hpp"
#include "smart/record/ros_messages.hpp"

namespace smart::monitor {

class RosPlanView {
 public:
  RosPlanView(const dds::Participant& participant, const Instance& instance, double cell_m,
              double robot_radius_m, const std::string& ros_namespace = "");
  void publish_paths();
  // poses: each robot's last reported pose (nullopt: none yet; drawn at its start).
  void publish(const PlanSnapshot& snapshot,
               const std::vector<std::optional<common::Pose2D>>& poses, double stamp_s);
  uint64_t marker_arrays() const { return arrays_; }

 private:
  record::MarkerMessages markers_;  // the plan's paths, and the markers built from them
  std::vector<dds::Topic<nav_msgs_msg_dds__Path_>> path_topics_;
  std::vector<dds::Writer<nav_msgs_msg_dds__Path_>> path_writers_;
  dds::Topic<visualization_msgs_msg_dds__MarkerArray_> markers_topic_;
  dds::Writer<visualization_msgs_msg_dds__MarkerArray_> markers_writer_;
  uint64_t arrays_ = 0;
};

}  // namespace smart::monitor
