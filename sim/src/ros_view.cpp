#include "smart/sim/ros_view.hpp"

#include <stdexcept>

namespace smart::sim {

namespace {
std::string checked(const std::string& ros_namespace) {
  dds::check_ros_namespace(ros_namespace);
  return ros_namespace;
}
}  // namespace

RosView::RosView(const dds::Participant& participant, const dds::QosProfile& qos,
                 std::size_t robots, const std::vector<uint32_t>& pose_robots,
                 const std::string& ros_namespace)
    : poses_topic_(participant, dds::ros_topic(dds::ros_view_topic(
                                    checked(ros_namespace), std::string(dds::kRosPosesTopic)))),
      poses_(participant, poses_topic_, qos.state.to_dds()),
      tf_topic_(participant,
                dds::ros_topic(dds::ros_view_topic(ros_namespace, std::string(dds::kRosTfTopic)))),
      tf_(participant, tf_topic_, qos.state.to_dds()),
      map_topic_(participant, dds::ros_topic(dds::ros_view_topic(ros_namespace,
                                                                 std::string(dds::kRosMapTopic)))),
      map_(participant, map_topic_, dds::ros_latched_qos().to_dds()),
      pose_robots_(pose_robots),
      ns_(ros_namespace),
      fleet_(robots) {
  for (const uint32_t r : pose_robots_) {
    if (r >= robots) {
      throw std::invalid_argument("ROS pose topic asked for robot " + std::to_string(r) +
                                  " but the fleet has " + std::to_string(robots) +
                                  " robots (ids 0.." + std::to_string(robots - 1) + ")");
    }
    pose_topics_.emplace_back(
        participant, dds::ros_topic(dds::ros_view_topic(ns_, dds::ros_robot_pose_topic(r))));
    pose_writers_.emplace_back(participant, pose_topics_.back(), qos.state.to_dds());
  }
}

void RosView::publish(const World& world) {
  const double t_s = world.time_s();
  for (uint32_t i = 0; i < fleet_.robots(); ++i) {
    const auto p = world.pose(i).pose;
    fleet_.set_pose(i, p.x_m, p.y_m, p.yaw_rad);
  }
  poses_.write(fleet_.pose_array(t_s));
  tf_.write(fleet_.tf(t_s));
  for (std::size_t k = 0; k < pose_robots_.size(); ++k) {
    pose_writers_[k].write(fleet_.pose(pose_robots_[k], t_s));
  }
}

void RosView::publish_map(const grid::Grid& grid, double cell_m) {
  record::MapMessage m(grid, cell_m);
  map_.write(m.message());
}

}  // namespace smart::sim
