#include "smart/record/ros_messages.hpp"

#include "smart/dds/sequence.hpp"
#include "smart/dds/topics.hpp"

namespace smart::record {

namespace {
// Header frame ids and names point at these (the C message types hold char*, never written
// through).
std::string g_map_frame(dds::kRosMapFrame);
char g_empty[] = "";
char g_robots_ns[] = "robots";
char g_goals_ns[] = "goals";
char g_waits_ns[] = "waits";

// visualization_msgs/Marker's type and action constants (ros2/common_interfaces Marker.msg).
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

std_msgs_msg_dds__ColorRGBA_ colour(monitor::Activity a) {
  switch (a) {
    case monitor::Activity::kMoving:
      return {0.2f, 0.8f, 0.2f, 1.0f};
    case monitor::Activity::kWaiting:
      return {1.0f, 0.6f, 0.0f, 1.0f};
    case monitor::Activity::kDone:
      break;
  }
  return {0.6f, 0.6f, 0.6f, 1.0f};
}
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

MarkerMessages::MarkerMessages(std::vector<std::vector<grid::WorldPoint>> paths, double cell_m,
                               double robot_radius_m)
    : paths_(std::move(paths)), cell_m_(cell_m), radius_m_(robot_radius_m) {}

visualization_msgs_msg_dds__MarkerArray_ MarkerMessages::message(
    const monitor::PlanSnapshot& snapshot,
    const std::vector<std::optional<grid::WorldPoint>>& poses, double t_s) {
  const auto stamp = dds::ros_stamp(t_s);
  const auto robots = static_cast<uint32_t>(paths_.size());
  auto where = [&](uint32_t r) {
    if (r < poses.size() && poses[r]) return *poses[r];
    return paths_[r].empty() ? grid::WorldPoint{} : paths_[r].front();
  };
  markers_.clear();
  arrows_.assign(snapshot.waits.size(), {});
  auto clear = marker(g_waits_ns, 0, kArrow, stamp);
  clear.action = kDeleteAll;
  markers_.push_back(clear);
  for (uint32_t r = 0; r < robots; ++r) {
    auto m = marker(g_robots_ns, static_cast<int32_t>(r), kCylinder, stamp);
    const auto p = where(r);
    m.pose.position = {p.x_m, p.y_m, 0.05};
    m.scale = {2 * radius_m_, 2 * radius_m_, 0.1};
    m.color =
        colour(r < snapshot.activity.size() ? snapshot.activity[r] : monitor::Activity::kDone);
    markers_.push_back(m);
    if (paths_[r].empty()) continue;
    auto g = marker(g_goals_ns, static_cast<int32_t>(r), kCube, stamp);
    g.pose.position = {paths_[r].back().x_m, paths_[r].back().y_m, 0.01};
    g.scale = {0.3 * cell_m_, 0.3 * cell_m_, 0.02};
    g.color = {0.2f, 0.4f, 1.0f, 0.6f};
    markers_.push_back(g);
  }
  for (std::size_t k = 0; k < snapshot.waits.size(); ++k) {
    const auto& w = snapshot.waits[k];
    const auto a = where(w.robot), b = where(w.for_robot);
    arrows_[k] = {{{a.x_m, a.y_m, 0.15}, {b.x_m, b.y_m, 0.15}}};
    auto m = marker(g_waits_ns, static_cast<int32_t>(k), kArrow, stamp);
    dds::borrow(m.points, arrows_[k]);
    m.scale = {0.05 * cell_m_, 0.12 * cell_m_, 0.15 * cell_m_};  // shaft, head width, head length
    m.color = {1.0f, 0.3f, 0.0f, 1.0f};
    markers_.push_back(m);
  }
  visualization_msgs_msg_dds__MarkerArray_ array{};
  dds::borrow(array.markers, markers_);
  return array;
}

}  // namespace smart::record
