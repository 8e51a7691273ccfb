#include "smart/monitor/ros_plan_view.hpp"

#include <array>

#include "smart/dds/sequence.hpp"

namespace smart::monitor {

namespace {

// The C message types hold char*; these are never written through.
char g_empty[] = "";
std::string g_map_frame(dds::kRosMapFrame);
char g_robots_ns[] = "robots";
char g_goals_ns[] = "goals";
char g_waits_ns[] = "waits";

constexpr int32_t kArrow = 0, kCube = 1, kCylinder = 3, kAdd = 0, kDeleteAll = 3;

visualization_msgs_msg_dds__Marker_ marker(char* ns, int32_t id, int32_t type,
                                           builtin_interfaces_msg_dds__Time_ stamp) {
  visualization_msgs_msg_dds__Marker_ m{};
  m.header = {stamp, g_map_frame.data()};
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = kAdd;
  m.pose.orientation = dds::yaw_quaternion(0.0);
  m.texture_resource = g_empty;
  m.texture.header.frame_id = g_empty;
  m.texture.format = g_empty;
  m.text = g_empty;
  m.mesh_resource = g_empty;
  m.mesh_file.filename = g_empty;
  return m;
}

std_msgs_msg_dds__ColorRGBA_ colour(Activity a) {
  switch (a) {
    case Activity::kMoving:
      return {0.2f, 0.8f, 0.2f, 1.0f};
    case Activity::kWaiting:
      return {1.0f, 0.6f, 0.0f, 1.0f};
    case Activity::kDone:
      break;
  }
  return {0.6f, 0.6f, 0.6f, 1.0f};
}

}  // namespace

RosPlanView::RosPlanView(const dds::Participant& participant, const Instance& instance,
                         double cell_m, double robot_radius_m, const std::string& ros_namespace)
    : in_(instance),
      cell_m_(cell_m),
      radius_m_(robot_radius_m),
      markers_topic_(participant, dds::ros_topic(dds::ros_view_topic(
                                      ros_namespace, std::string(dds::kRosMarkersTopic)))),
      markers_(participant, markers_topic_, dds::ros_latched_qos().to_dds()) {
  const auto robots = static_cast<uint32_t>(in_.actions.robots());
  const auto latched = dds::ros_latched_qos().to_dds();
  path_topics_.reserve(robots);
  for (uint32_t r = 0; r < robots; ++r) {
    paths_.push_back(planned_path(in_.actions, in_.grid, r, cell_m_));
    path_topics_.emplace_back(participant, dds::ros_topic(dds::ros_view_topic(
                                               ros_namespace, dds::ros_robot_plan_topic(r))));
    path_writers_.emplace_back(participant, path_topics_.back(), latched);
  }
}

void RosPlanView::publish_paths() {
  for (std::size_t r = 0; r < paths_.size(); ++r) {
    record::PathMessage m(paths_[r]);
    path_writers_[r].write(m.message());
  }
}

void RosPlanView::publish(const PlanSnapshot& snapshot,
                          const std::vector<std::optional<common::Pose2D>>& poses, double stamp_s) {
  const auto stamp = dds::ros_stamp(stamp_s);
  const auto robots = static_cast<uint32_t>(paths_.size());
  auto where = [&](uint32_t r) {
    return poses[r] ? grid::WorldPoint{poses[r]->x_m, poses[r]->y_m} : paths_[r].front();
  };
  std::vector<visualization_msgs_msg_dds__Marker_> ms;
  std::vector<std::array<geometry_msgs_msg_dds__Point_, 2>> arrows(snapshot.waits.size());
  ms.reserve(2 * std::size_t{robots} + snapshot.waits.size() + 1);
  auto clear = marker(g_waits_ns, 0, kArrow, stamp);
  clear.action = kDeleteAll;
  ms.push_back(clear);
  for (uint32_t r = 0; r < robots; ++r) {
    auto m = marker(g_robots_ns, static_cast<int32_t>(r), kCylinder, stamp);
    const auto p = where(r);
    m.pose.position = {p.x_m, p.y_m, 0.05};
    m.scale = {2 * radius_m_, 2 * radius_m_, 0.1};
    m.color = colour(snapshot.activity[r]);
    ms.push_back(m);
    auto g = marker(g_goals_ns, static_cast<int32_t>(r), kCube, stamp);
    g.pose.position = {paths_[r].back().x_m, paths_[r].back().y_m, 0.01};
    g.scale = {0.3 * cell_m_, 0.3 * cell_m_, 0.02};
    g.color = {0.2f, 0.4f, 1.0f, 0.6f};
    ms.push_back(g);
  }
  for (std::size_t k = 0; k < snapshot.waits.size(); ++k) {
    const auto& w = snapshot.waits[k];
    const auto a = where(w.robot), b = where(w.for_robot);
    arrows[k] = {{{a.x_m, a.y_m, 0.15}, {b.x_m, b.y_m, 0.15}}};
    auto m = marker(g_waits_ns, static_cast<int32_t>(k), kArrow, stamp);
    dds::borrow(m.points, arrows[k]);
    m.scale = {0.05 * cell_m_, 0.12 * cell_m_, 0.15 * cell_m_};  // shaft, head width, head length
    m.color = {1.0f, 0.3f, 0.0f, 1.0f};
    ms.push_back(m);
  }
  visualization_msgs_msg_dds__MarkerArray_ array{};
  dds::borrow(array.markers, ms);
  markers_.write(array);
  ++arrays_;
}

}  // namespace smart::monitor
