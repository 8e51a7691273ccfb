// Contract: the ROS 2 view's messages (idl/smart.idl "The ROS 2 view" and "The plan as rviz2 sees
// it"), built once here for both the live run (sim host's RosView, monitor's RosPlanView publish
// them) and its recording (recorder.hpp writes them to MCAP), so a recording holds what the live
// topics carry. Frame "map"; robot i's frame "robot_<i>"; stamps are sim time (dds::ros_stamp).
// The messages point into this object's buffers (idlc's C types hold pointers): valid until the
// next call that changes them. Pure: no DDS call.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ros2.h"
#include "smart/grid/grid.hpp"
#include "smart/monitor/plan_view.hpp"

namespace smart::record {

// OccupancyGrid cells of a MovingAI grid: row-major from the bottom row (world y grows upwards),
// 100 = blocked, 0 = free. The grid's origin is the outer corner of cell (0, height-1).
std::vector<int8_t> occupancy_cells(const grid::Grid& grid);

// The fleet's poses as PoseArray (robot i at index i), TFMessage ("map" -> "robot_<i>") and
// PoseStamped of one robot.
class FleetMessages {
 public:
  explicit FleetMessages(std::size_t robots);
  std::size_t robots() const { return poses_.size(); }
  void set_pose(uint32_t robot, double x_m, double y_m, double yaw_rad);
  geometry_msgs_msg_dds__PoseArray_ pose_array(double t_s);
  tf2_msgs_msg_dds__TFMessage_ tf(double t_s);
  geometry_msgs_msg_dds__PoseStamped_ pose(uint32_t robot, double t_s);

 private:
  std::vector<std::string> frames_;
  std::vector<geometry_msgs_msg_dds__Pose_> poses_;
  std::vector<geometry_msgs_msg_dds__TransformStamped_> tf_;
};

// The map as OccupancyGrid, stamped 0 (it never changes).
class MapMessage {
 public:
  MapMessage(const grid::Grid& grid, double cell_m);
  nav_msgs_msg_dds__OccupancyGrid_ message();

 private:
  std::vector<int8_t> cells_;
  uint32_t width_, height_;
  double cell_m_;
};

// A robot's planned path (world points, plan_view.hpp planned_path) as nav_msgs/Path, stamped 0.
class PathMessage {
 public:
  explicit PathMessage(const std::vector<grid::WorldPoint>& points);
  nav_msgs_msg_dds__Path_ message();

 private:
  std::vector<geometry_msgs_msg_dds__PoseStamped_> poses_;
};

// The plan view's MarkerArray (rviz2's config/rviz/smart.rviz): a DELETEALL of the old wait
// arrows, then per robot a cylinder at its pose coloured by activity (green moving, orange
// waiting, grey done) in namespace "robots" and a cube at its goal in "goals", and an arrow per
// current Type-2 wait from the waiting robot to the robot it waits for in "waits".
class MarkerMessages {
 public:
  // paths: each robot's planned path (its start when no pose is known yet, its goal).
  MarkerMessages(std::vector<std::vector<grid::WorldPoint>> paths, double cell_m,
                 double robot_radius_m);
  // poses: each robot's last pose, if any.
  visualization_msgs_msg_dds__MarkerArray_ message(
      const monitor::PlanSnapshot& snapshot,
      const std::vector<std::optional<grid::WorldPoint>>& poses, double t_s);
  const std::vector<std::vector<grid::WorldPoint>>& paths() const { return paths_; }

 private:
  std::vector<std::vector<grid::WorldPoint>> paths_;
  double cell_m_, radius_m_;
  std::vector<visualization_msgs_msg_dds__Marker_> markers_;
  std::vector<std::array<geometry_msgs_msg_dds__Point_, 2>> arrows_;
};

}  // namespace smart::record
