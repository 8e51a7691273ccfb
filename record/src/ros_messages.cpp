#include "smart/record/ros_messages.hpp"

#include "smart/dds/sequence.hpp"
#include "smart/dds/topics.hpp"

namespace smart::record {

namespace {
// Header frame ids point at this (the C message types hold char*, never written through).
std::string g_map_frame(dds::kRosMapFrame);
}  // namespace

std::vector<int8_t> occupancy_cells(const grid::Grid& grid) {
  std::vector<int8_t> cells;
  cells.reserve(static_cast<std::size_t>(grid.width()) * grid.height());
  for (int32_t row = grid.height() - 1; row >= 0; --row) {
    for (int32_t col = 0; col < grid.width(); ++col) {
      cells.push_back(grid.blocked({col, row}) ? int8_t{100} : int8_t{0});
    }
  }
  return cells;
}

FleetMessages::FleetMessages(std::size_t robots) : poses_(robots), tf_(robots) {
  frames_.reserve(robots);
  for (uint32_t i = 0; i < robots; ++i) frames_.push_back(dds::ros_robot_frame(i));
  for (uint32_t i = 0; i < robots; ++i) {
    tf_[i].header.frame_id = g_map_frame.data();
    tf_[i].child_frame_id = frames_[i].data();
    set_pose(i, 0.0, 0.0, 0.0);
  }
}

void FleetMessages::set_pose(uint32_t robot, double x_m, double y_m, double yaw_rad) {
  const auto q = dds::yaw_quaternion(yaw_rad);
  poses_[robot] = {{x_m, y_m, 0.0}, q};
  tf_[robot].transform = {{x_m, y_m, 0.0}, q};
}

geometry_msgs_msg_dds__PoseArray_ FleetMessages::pose_array(double t_s) {
  geometry_msgs_msg_dds__PoseArray_ m{};
  m.header = {dds::ros_stamp(t_s), g_map_frame.data()};
  dds::borrow(m.poses, poses_);
  return m;
}

tf2_msgs_msg_dds__TFMessage_ FleetMessages::tf(double t_s) {
  const auto stamp = dds::ros_stamp(t_s);
  for (auto& t : tf_) t.header.stamp = stamp;
  tf2_msgs_msg_dds__TFMessage_ m{};
  dds::borrow(m.transforms, tf_);
  return m;
}

geometry_msgs_msg_dds__PoseStamped_ FleetMessages::pose(uint32_t robot, double t_s) {
  geometry_msgs_msg_dds__PoseStamped_ m{};
  m.header = {dds::ros_stamp(t_s), g_map_frame.data()};
  m.pose = poses_[robot];
  return m;
}

MapMessage::MapMessage(const grid::Grid& grid, double cell_m)
    : cells_(occupancy_cells(grid)),
      width_(static_cast<uint32_t>(grid.width())),
      height_(static_cast<uint32_t>(grid.height())),
      cell_m_(cell_m) {}

nav_msgs_msg_dds__OccupancyGrid_ MapMessage::message() {
  nav_msgs_msg_dds__OccupancyGrid_ m{};
  m.header = {dds::ros_stamp(0.0), g_map_frame.data()};
  m.info.resolution = static_cast<float>(cell_m_);
  m.info.width = width_;
  m.info.height = height_;
  // Cell centres are at multiples of cell_m (grid/grid.hpp), so the grid starts half a cell
  // before the first centre.
  m.info.origin = {{-cell_m_ / 2, -cell_m_ / 2, 0.0}, dds::yaw_quaternion(0.0)};
  dds::borrow(m.data, cells_);
  return m;
}

PathMessage::PathMessage(const std::vector<grid::WorldPoint>& points) {
  const auto stamp = dds::ros_stamp(0.0);
  for (const auto& p : points) {
    geometry_msgs_msg_dds__PoseStamped_ s{};
    s.header = {stamp, g_map_frame.data()};
    s.pose = {{p.x_m, p.y_m, 0.0}, dds::yaw_quaternion(0.0)};
    poses_.push_back(s);
  }
}

nav_msgs_msg_dds__Path_ PathMessage::message() {
  nav_msgs_msg_dds__Path_ m{};
  m.header = {dds::ros_stamp(0.0), g_map_frame.data()};
  dds::borrow(m.poses, poses_);
  return m;
}

}  // namespace smart::record
