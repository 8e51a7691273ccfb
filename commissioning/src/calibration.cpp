#include "smart/commissioning/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "smart/common/steady_clock.hpp"
#include "smart/dds/topics.hpp"
#include "smart/hw/ros_pose.hpp"
#include "smart/hw/vicon.hpp"

namespace smart::commissioning {

namespace {

using common::steady_s;

FramePoint parse_point(const std::string& text) {
  FramePoint p;
  const auto colon = text.find(':');
  char comma = 0;
  std::istringstream cell(colon == std::string::npos ? "" : text.substr(colon + 1));
  if (colon == std::string::npos || colon == 0 || !(cell >> p.col >> comma >> p.row) ||
      comma != ',' || !cell.eof()) {
    throw std::invalid_argument("--point '" + text +
                                "': write ID:COL,ROW, e.g. 3:0,5 (robot 3 "
                                "stands on column 0, row 5 of the map)");
  }
  p.id = text.substr(0, colon);
  return p;
}

// Pose sources in the source's own units and frame (identity transform): what is fitted.
struct RawSources {
  std::unique_ptr<hw::ViconReceiver> vicon;
  std::vector<std::unique_ptr<agent::PoseSource>> sources;  // per point
};

RawSources open_raw_sources(const FrameSources& o, const std::vector<FramePoint>& points,
                            const dds::Participant& participant) {
  RawSources r;
  const geometry::FrameTransform identity;
  if (o.pose == hw::PoseKind::kVicon) {
    std::vector<std::string> objects;
    objects.reserve(points.size());
    for (const auto& p : points) objects.push_back(hw::with_id(o.vicon_object, p.id));
    r.vicon = std::make_unique<hw::ViconReceiver>(o.vicon_bind, o.vicon_port, identity, objects,
                                                  steady_s);
    for (const auto& name : objects) {
      r.sources.push_back(std::make_unique<hw::ViconPoseSource>(*r.vicon, name, 1.0, steady_s));
    }
    return r;
  }
  const bool odom = o.pose == hw::PoseKind::kOdom;
  if (!odom && o.ros_topic.empty()) {
    throw std::invalid_argument("--pose ros needs --ros-topic ({id} is the point's ID)");
  }
  for (const auto& p : points) {
    const auto topic = odom ? dds::ros_odom_topic(hw::with_id(o.ros_namespace, p.id))
                            : hw::with_id(o.ros_topic, p.id);
    r.sources.push_back(std::make_unique<hw::RosPoseSource>(
        participant, topic, identity, 1.0, steady_s,
        odom ? hw::RosPoseSource::Message::kOdometry : hw::RosPoseSource::Message::kPoseStamped));
  }
  return r;
}

// Mean position of each source over record_s (every new sample once); past record_s, waits (up
// to 10 s) only for points with fewer than 3 poses.
std::vector<Eigen::Vector2d> record_means(const std::vector<FramePoint>& points, double record_s,
                                          RawSources& raw) {
  std::vector<Eigen::Vector2d> sum(points.size(), Eigen::Vector2d::Zero());
  std::vector<int> n(points.size(), 0);
  std::vector<double> last(points.size(), -1);
  const double end_s = steady_s() + record_s;
  for (double wait_until = steady_s() + 10.0; steady_s() < end_s || steady_s() < wait_until;) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto s = raw.sources[i]->read();
      if (!s.valid || s.stamp_s == last[i]) continue;
      last[i] = s.stamp_s;
      sum[i] += Eigen::Vector2d(s.pose.x_m, s.pose.y_m);
      ++n[i];
    }
    if (steady_s() >= end_s && std::all_of(n.begin(), n.end(), [](int k) { return k >= 3; })) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::vector<Eigen::Vector2d> means;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (n[i] < 3) {
      throw std::runtime_error("point " + points[i].id + ": " + std::to_string(n[i]) +
                               " poses in 10 s; check that its pose source is streaming");
    }
    means.emplace_back(sum[i] / n[i]);
  }
  return means;
}

}  // namespace

std::vector<FramePoint> place_points(const std::vector<std::string>& texts, const grid::Grid& grid,
                                     double cell_m, const std::string& map) {
  std::vector<FramePoint> points;
  for (const auto& text : texts) {
    auto p = parse_point(text);
    if (!grid.inside({p.col, p.row})) {
      throw std::invalid_argument("--point '" + text + "': the cell is outside the " +
                                  std::to_string(grid.width()) + "x" +
                                  std::to_string(grid.height()) + " map " + map);
    }
    const auto w = grid.to_world({2 * p.col, 2 * p.row}, cell_m);
    p.world_m = {w.x_m, w.y_m};
    if (std::any_of(points.begin(), points.end(), [&](const auto& q) { return q.id == p.id; })) {
      throw std::invalid_argument("--point '" + text + "': " + p.id +
                                  " is already placed; each point is a different robot or "
                                  "object recorded at the same time");
    }
    points.push_back(std::move(p));
  }
  return points;
}

FrameFit fit_frame(const FrameSources& sources, const std::vector<FramePoint>& points,
                   double record_s, double tolerance_m, const dds::Participant& participant) {
  auto raw = open_raw_sources(sources, points, participant);
  FrameFit f;
  f.source = record_means(points, record_s, raw);
  std::vector<Eigen::Vector2d> world;
  world.reserve(points.size());
  for (const auto& p : points) world.push_back(p.world_m);
  f.fit = geometry::fit_similarity(f.source, world);
  f.accepted = f.fit.max_m <= tolerance_m;
  return f;
}

nlohmann::json FrameFit::report(const std::vector<FramePoint>& points, double tolerance_m) const {
  nlohmann::json j = {
      {"accepted", accepted},
      {"tolerance_m", tolerance_m},
      {"scale", fit.transform.scale},
      {"yaw_rad", fit.transform.yaw_rad},
      {"translation_m", {fit.transform.translation_m.x(), fit.transform.translation_m.y()}},
      {"rms_m", fit.rms_m},
      {"max_m", fit.max_m},
      {"points", nlohmann::json::array()}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    j["points"].push_back({{"id", points[i].id},
                           {"cell", {points[i].col, points[i].row}},
                           {"source", {source[i].x(), source[i].y()}},
                           {"residual_m", fit.residuals_m[i]}});
  }
  return j;
}

std::vector<agent::PoseSample> drive_straight(const TrimTrial& trial, uint32_t robot,
                                              hw::RobotIo& io) {
  const auto stopped = [&trial] { return trial.stop != nullptr && trial.stop->load(); };
  std::vector<agent::PoseSample> samples;
  auto ready = io.drive->configure();
  if (ready.ok()) ready = io.drive->activate();
  if (!ready.ok()) throw std::runtime_error(ready.message);
  double last_stamp = -1;
  const double start_s = steady_s(), first_pose_deadline_s = start_s + 5.0;
  for (double now = start_s; now < start_s + trial.seconds && !stopped(); now = steady_s()) {
    const auto p = io.pose->read();
    if (p.valid && p.stamp_s != last_stamp) {
      samples.push_back(p);
      last_stamp = p.stamp_s;
    }
    if (samples.empty() && now > first_pose_deadline_s) break;
    io.drive->set_wheel_speeds(samples.empty()
                                   ? agent::WheelSpeeds{}
                                   : agent::WheelSpeeds{trial.speed_mps, trial.speed_mps});
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (auto r = io.drive->deactivate(); !r.ok()) throw std::runtime_error(r.message);
  if (stopped()) throw std::runtime_error("stopped by signal; the wheels are off");
  if (samples.empty()) {
    throw std::runtime_error("robot " + std::to_string(robot) + ": no pose from " + io.pose_name +
                             " in 5 s; check the pose stream");
  }
  return samples;
}

TrimProposal propose_trim(uint32_t robot, const agent::WheelTrial& t,
                          const agent::RobotModel& model, const hw::RobotIo& io) {
  TrimProposal p;
  p.report = {{"robot_id", robot},
              {"speed_mps", t.speed_mps},
              {"turn_rate_radps", t.turn_rate_radps},
              {"gain", {{"left", t.gain.left}, {"right", t.gain.right}}},
              {"trim", {{"left", t.trim.left}, {"right", t.trim.right}}}};
  std::ostringstream yaml;
  if (io.jetbot != nullptr) {  // the board's per-wheel alpha is the JetBot's trim
    const double left = io.hardware.left.alpha * t.trim.left;
    const double right = io.hardware.right.alpha * t.trim.right;
    yaml << "hardware:\n  left: {alpha: " << left << "}\n  right: {alpha: " << right << "}\n";
    p.report["proposed"] = {{"hardware.left.alpha", left}, {"hardware.right.alpha", right}};
  } else {
    const double left = model.trim.left * t.trim.left, right = model.trim.right * t.trim.right;
    yaml << "trim: {left: " << left << ", right: " << right << "}\n";
    p.report["proposed"] = {{"trim.left", left}, {"trim.right", right}};
  }
  p.yaml = yaml.str();
  return p;
}

}  // namespace smart::commissioning
