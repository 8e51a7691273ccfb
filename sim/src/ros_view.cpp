#include "smart/sim/ros_view.hpp"

#include <cmath>
#include <stdexcept>

#include "smart/dds/sequence.hpp"

namespace smart::sim {

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

namespace {
// Header frame ids point at this (the C message types hold char*, never written through).
std::string g_map_frame(dds::kRosMapFrame);
}  // namespace

RosView::RosView(const dds::Participant& participant, const dds::QosProfile& qos,
                 std::size_t robots, const std::vector<uint32_t>& pose_robots)
    : poses_topic_(participant, dds::ros_topic(std::string(dds::kRosPosesTopic))),
      poses_(participant, poses_topic_, qos.state.to_dds()),
      tf_topic_(participant, dds::ros_topic(std::string(dds::kRosTfTopic))),
      tf_(participant, tf_topic_, qos.state.to_dds()),
      map_topic_(participant, dds::ros_topic(std::string(dds::kRosMapTopic))),
      map_(participant, map_topic_, dds::ros_latched_qos().to_dds()),
      pose_robots_(pose_robots) {
  for (const uint32_t r : pose_robots_) {
    if (r >= robots) {
      throw std::invalid_argument("ROS pose topic asked for robot " + std::to_string(r) +
                                  " but the fleet has " + std::to_string(robots) +
                                  " robots (ids 0.." + std::to_string(robots - 1) + ")");
    }
    pose_topics_.emplace_back(participant, dds::ros_topic(dds::ros_robot_pose_topic(r)));
    pose_writers_.emplace_back(participant, pose_topics_.back(), qos.state.to_dds());
  }
  for (uint32_t i = 0; i < robots; ++i) frames_.push_back(dds::ros_robot_frame(i));
  pose_buffer_.resize(robots);
  tf_buffer_.resize(robots);
}

void RosView::publish(const World& world) {
  const auto stamp = ros_stamp(world.time_s());
  for (uint32_t i = 0; i < pose_buffer_.size(); ++i) {
    const auto p = world.pose(i).pose;
    const auto q = yaw_quaternion(p.yaw_rad);
    pose_buffer_[i] = {{p.x_m, p.y_m, 0.0}, q};
    auto& t = tf_buffer_[i];
    t.header.stamp = stamp;
    t.header.frame_id = g_map_frame.data();
    t.child_frame_id = frames_[i].data();
    t.transform = {{p.x_m, p.y_m, 0.0}, q};
  }
  geometry_msgs_msg_dds__PoseArray_ poses{};
  poses.header = {stamp, g_map_frame.data()};
  dds::borrow(poses.poses, pose_buffer_);
  poses_.write(poses);

  tf2_msgs_msg_dds__TFMessage_ tf{};
  dds::borrow(tf.transforms, tf_buffer_);
  tf_.write(tf);

  for (std::size_t k = 0; k < pose_robots_.size(); ++k) {
    geometry_msgs_msg_dds__PoseStamped_ m{};
    m.header = {stamp, g_map_frame.data()};
    m.pose = pose_buffer_[pose_robots_[k]];
    pose_writers_[k].write(m);
  }
}

void RosView::publish_map(const grid::Grid& grid, double cell_m) {
  auto cells = occupancy_cells(grid);
  nav_msgs_msg_dds__OccupancyGrid_ m{};
  m.header = {ros_stamp(0.0), g_map_frame.data()};
  m.info.resolution = static_cast<float>(cell_m);
  m.info.width = static_cast<uint32_t>(grid.width());
  m.info.height = static_cast<uint32_t>(grid.height());
  // Cell centres are at multiples of cell_m (grid/grid.hpp), so the grid starts half a cell
  // before the first centre.
  m.info.origin = {{-cell_m / 2, -cell_m / 2, 0.0}, yaw_quaternion(0.0)};
  dds::borrow(m.data, cells);
  map_.write(m);
}

}  // namespace smart::sim
