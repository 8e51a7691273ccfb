#include "smart/record/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "smart/dds/topics.hpp"
#include "smart/record/cdr.hpp"
#include "smart/record/schemas.hpp"

namespace smart::record {

namespace {

uint64_t ns_of(double t_s) { return t_s <= 0 ? 0 : static_cast<uint64_t>(std::llround(t_s * 1e9)); }

// rosbag2's offered_qos_profiles metadata (rosbag2_storage/qos.hpp: history 1 keep last,
// reliability 1 reliable / 2 best effort, durability 1 transient local / 2 volatile; durations at
// rmw's "infinite").
std::string qos_yaml(bool latched) {
  constexpr const char* kInfinite = "\n    sec: 2147483647\n    nsec: 4294967295";
  return std::string("- history: 1\n  depth: 1\n  reliability: ") + (latched ? "1" : "2") +
         "\n  durability: " + (latched ? "1" : "2") + "\n  deadline:" + kInfinite +
         "\n  lifespan:" + kInfinite +
         "\n  liveliness: 1\n  liveliness_lease_duration:" + kInfinite +
         "\n  avoid_ros_namespace_conventions: false\n";
}

// Heap order, earliest on top: by time, then progress before events, progress by robot and
// action, events as given, so that the file does not depend on the order progress was told in
// (a live recording hears it as it arrives, an export in actions.csv's order).
bool later(const auto& a, const auto& b) {
  if (a.t_s != b.t_s) return a.t_s > b.t_s;
  const bool a_event = a.event >= 0, b_event = b.event >= 0;
  if (a_event != b_event) return a_event;
  if (a_event) return a.order > b.order;
  return a.robot != b.robot ? a.robot > b.robot : a.finished_seq > b.finished_seq;
}

}  // namespace

RunRecorder::RunRecorder(ByteSink& sink, RecorderOptions options, std::size_t robots,
                         uint64_t run_id)
    : options_(std::move(options)),
      writer_(sink, options_.mcap),
      run_id_(run_id),
      fleet_(robots),
      starts_(robots),
      points_(robots) {
  dds::check_ros_namespace(options_.ros_namespace);
  for (const uint32_t r : options_.pose_robots) check_robot(r, "a chosen pose robot");
  poses_ch_ = ros_channel(ros_type_name<geometry_msgs_msg_dds__PoseArray_>(),
                          std::string(dds::kRosPosesTopic), false);
  tf_ch_ = ros_channel(ros_type_name<tf2_msgs_msg_dds__TFMessage_>(), std::string(dds::kRosTfTopic),
                       false);
  for (const uint32_t r : options_.pose_robots) {
    pose_chs_.push_back(ros_channel(ros_type_name<geometry_msgs_msg_dds__PoseStamped_>(),
                                    dds::ros_robot_pose_topic(r), false));
  }
  state_ch_ = smart_channel("smart::msg::RobotState", smart_msg_TOPIC_STATE);
  progress_ch_ = smart_channel("smart::msg::Progress", smart_msg_TOPIC_PROGRESS);
  events_ch_ = smart_channel("smart::msg::RunEvent", std::string(dds::kRecordEventsTopic));
}

void RunRecorder::check_robot(uint32_t robot, const char* what) const {
  if (robot >= fleet_.robots()) {
    throw std::invalid_argument("recording: " + std::string(what) + " names robot " +
                                std::to_string(robot) + " but the fleet has " +
                                std::to_string(fleet_.robots()) + " robots");
  }
}

uint16_t RunRecorder::ros_channel(const std::string& type, const std::string& topic, bool latched) {
  auto [it, fresh] = schemas_.try_emplace(type, 0);
  if (fresh) it->second = writer_.add_schema(type, "ros2msg", ros2msg_definition(type));
  return writer_.add_channel({it->second,
                              dds::ros_view_topic(options_.ros_namespace, topic),
                              "cdr",
                              {{"offered_qos_profiles", qos_yaml(latched)}}});
}

uint16_t RunRecorder::smart_channel(const std::string& type, const std::string& topic) {
  auto [it, fresh] = schemas_.try_emplace(type, 0);
  if (fresh) it->second = writer_.add_schema(type, "omgidl", smart_idl_text());
  return writer_.add_channel({it->second, topic, "cdr"});
}

void RunRecorder::map(const grid::Grid& grid, double cell_m) {
  const auto ch = ros_channel(ros_type_name<nav_msgs_msg_dds__OccupancyGrid_>(),
                              std::string(dds::kRosMapTopic), true);
  MapMessage m(grid, cell_m);
  writer_.write(ch, 0, 0, cdr_.write(m.message()));
}

void RunRecorder::plans(const std::vector<std::vector<grid::WorldPoint>>& paths) {
  for (uint32_t r = 0; r < paths.size(); ++r) {
    check_robot(r, "a plan");
    if (!paths[r].empty()) starts_[r] = paths[r].front();
    if (!points_[r] && starts_[r]) fleet_.set_pose(r, starts_[r]->x_m, starts_[r]->y_m, 0.0);
    const auto ch =
        ros_channel(ros_type_name<nav_msgs_msg_dds__Path_>(), dds::ros_robot_plan_topic(r), true);
    PathMessage m(paths[r]);
    writer_.write(ch, 0, 0, cdr_.write(m.message()));
  }
}

void RunRecorder::plan_view(const monitor::Instance& in, double cell_m, double robot_radius_m) {
  std::vector<std::vector<grid::WorldPoint>> paths;
  for (uint32_t r = 0; r < in.actions.robots(); ++r) {
    paths.push_back(monitor::planned_path(in.actions, in.grid, r, cell_m));
  }
  plans(paths);
  in_ = &in;
  tracker_.emplace(in.actions, in.adg);
  markers_.emplace(std::move(paths), cell_m, robot_radius_m);
  markers_ch_ = ros_channel(ros_type_name<visualization_msgs_msg_dds__MarkerArray_>(),
                            std::string(dds::kRosMarkersTopic), true);
}

void RunRecorder::progress(double t_s, uint32_t robot, int32_t finished_seq) {
  check_robot(robot, "a progress row");
  pending_.push_back({t_s, order_++, -1, robot, finished_seq});
  std::push_heap(pending_.begin(), pending_.end(), [](auto& a, auto& b) { return later(a, b); });
}

void RunRecorder::event(const results::EventRow& row) {
  events_.push_back(row);
  pending_.push_back({row.t_s, order_++, static_cast<int64_t>(events_.size() - 1)});
  std::push_heap(pending_.begin(), pending_.end(), [](auto& a, auto& b) { return later(a, b); });
}

void RunRecorder::drain(double up_to_s, bool all) {
  auto cmp = [](auto& a, auto& b) { return later(a, b); };
  while (!pending_.empty() && (all || pending_.front().t_s <= up_to_s)) {
    std::pop_heap(pending_.begin(), pending_.end(), cmp);
    write_pending(pending_.back());
    pending_.pop_back();
  }
  if (pending_.empty()) events_.clear();
}

void RunRecorder::write_pending(const Pending& p) {
  const uint64_t t = ns_of(p.t_s);
  if (p.event < 0) {
    if (tracker_ && p.robot < tracker_->robots())
      (void)tracker_->on_progress(p.robot, p.finished_seq);
    smart_msg_Progress m{p.robot, run_id_, p.finished_seq, -1};
    writer_.write(progress_ch_, t, t, cdr_.write(m));
    return;
  }
  const auto& e = events_[static_cast<std::size_t>(p.event)];
  smart_msg_RunEvent m{};
  m.run_id = run_id_;
  m.sim_time_s = e.t_s;
  std::string event = e.event, detail = e.detail;
  m.event = event.data();
  m.task = e.task ? static_cast<int64_t>(*e.task) : -1;
  m.robot = e.robot ? static_cast<int32_t>(*e.robot) : -1;
  m.errand = e.errand ? static_cast<int32_t>(*e.errand) : -1;
  m.detail = detail.data();
  writer_.write(events_ch_, t, t, cdr_.write(m));
}

void RunRecorder::write_fleet(double t_s, bool last) {
  const uint64_t t = ns_of(t_s);
  writer_.write(poses_ch_, t, t, cdr_.write(fleet_.pose_array(t_s)));
  writer_.write(tf_ch_, t, t, cdr_.write(fleet_.tf(t_s)));
  for (std::size_t k = 0; k < pose_chs_.size(); ++k) {
    writer_.write(pose_chs_[k], t, t, cdr_.write(fleet_.pose(options_.pose_robots[k], t_s)));
  }
  if (markers_ &&
      (last || !last_markers_ns_ || t - *last_markers_ns_ >= ns_of(options_.markers_period_s))) {
    last_markers_ns_ = t;
    const auto snap = monitor::snapshot(in_->actions, in_->adg, *tracker_);
    writer_.write(markers_ch_, t, t, cdr_.write(markers_->message(snap, points_, t_s)));
  }
  fleet_written_ = true;
  last_fleet_ns_ = t;
}

void RunRecorder::state(const results::StateRow& row) {
  check_robot(row.robot, "a state row");
  if (have_time_ && row.t_s > time_s_) {
    // Every state of time_s_ is in: the fleet as it stood then.
    const bool due = ns_of(time_s_) - last_fleet_ns_ >= ns_of(options_.fleet_period_s);
    if (!fleet_written_ || due) write_fleet(time_s_);
  }
  if (!have_time_ || row.t_s > time_s_) {
    drain(row.t_s, false);
    time_s_ = row.t_s;
    have_time_ = true;
  }
  fleet_.set_pose(row.robot, row.x_m, row.y_m, row.yaw_rad);
  points_[row.robot] = grid::WorldPoint{row.x_m, row.y_m};
  smart_msg_RobotState m{};
  m.robot_id = row.robot;
  m.run_id = run_id_;
  m.sim_time_s = row.t_s;
  m.pose = {row.x_m, row.y_m, row.yaw_rad};
  m.linear_mps = row.v_mps;
  m.angular_radps = row.w_radps;
  m.wheel_left_mps = row.left_mps;
  m.wheel_right_mps = row.right_mps;
  m.queue_length = row.queue;
  const uint64_t t = ns_of(row.t_s);
  writer_.write(state_ch_, t, t, cdr_.write(m));
}

void RunRecorder::finish() {
  drain(0, true);  // progress after the last state: the markers' final activity
  if (have_time_) write_fleet(time_s_, true);
  writer_.finish();
}

}  // namespace smart::record
