#include "smart/monitor/ros_plan_view.hpp"

namespace smart::monitor {

namespace {
std::vector<std::vector<grid::WorldPoint>> planned_paths(const Instance& in, double cell_m) {
  std::vector<std::vector<grid::WorldPoint>> paths;
  for (uint32_t r = 0; r < in.actions.robots(); ++r) {
    paths.push_back(planned_path(in.actions, in.grid, r, cell_m));
  }
  return paths;
}
}  // namespace

RosPlanView::RosPlanView(const dds::Participant& participant, const Instance& instance,
                         double cell_m, double robot_radius_m, const std::string& ros_namespace)
    : markers_(planned_paths(instance, cell_m), cell_m, robot_radius_m),
      markers_topic_(participant, dds::ros_topic(dds::ros_view_topic(
                                      ros_namespace, std::string(dds::kRosMarkersTopic)))),
      markers_writer_(participant, markers_topic_, dds::ros_latched_qos().to_dds()) {
  const auto latched = dds::ros_latched_qos().to_dds();
  const auto robots = static_cast<uint32_t>(markers_.paths().size());
  path_topics_.reserve(robots);
  for (uint32_t r = 0; r < robots; ++r) {
    path_topics_.emplace_back(participant, dds::ros_topic(dds::ros_view_topic(
                                               ros_namespace, dds::ros_robot_plan_topic(r))));
    path_writers_.emplace_back(participant, path_topics_.back(), latched);
  }
}

void RosPlanView::publish_paths() {
  for (std::size_t r = 0; r < markers_.paths().size(); ++r) {
    record::PathMessage m(markers_.paths()[r]);
    path_writers_[r].write(m.message());
  }
}

void RosPlanView::publish(const PlanSnapshot& snapshot,
                          const std::vector<std::optional<common::Pose2D>>& poses, double stamp_s) {
  std::vector<std::optional<grid::WorldPoint>> points(poses.size());
  for (std::size_t r = 0; r < poses.size(); ++r) {
    if (poses[r]) points[r] = grid::WorldPoint{poses[r]->x_m, poses[r]->y_m};
  }
  markers_writer_.write(markers_.message(snapshot, points, stamp_s));
  ++arrays_;
}

}  // namespace smart::monitor
