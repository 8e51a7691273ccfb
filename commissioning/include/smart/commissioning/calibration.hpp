// Contract: `smart calibrate`'s procedures, lab bring-up before a run.
// - Frame: robots (or mocap objects) stand on known cells (place_points: "ID:COL,ROW" checked
//   against the map); fit_frame() records each point's poses for record_s from its pose source
//   (Vicon, odometry or a PoseStamped, in the source's own units and frame), averages them and
//   fits the similarity from the source's frame to the grid (Umeyama, common/geometry); the fit
//   is accepted when its largest residual is within tolerance_m. Writing the transform file
//   (geometry::frame_transform_yaml) is the caller's.
// - Trim: drive_straight() drives one robot with both wheels commanded alike for `seconds`
//   (commands at 50 Hz feed the JetBot's command watchdog) and returns its poses; the wheels stop
//   at the end, on `stop` and on failure. propose_trim() turns the measured trial
//   (agent/wheel_trim.hpp) into the robot file's keys: the JetBot's hardware alpha, a ROS 2
//   base's `trim:`.
// Errors: std::invalid_argument for bad points (naming the text and what to write),
// std::runtime_error when a pose source is silent or the drive fails (naming which).
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "smart/agent/robot_model.hpp"
#include "smart/agent/wheel_trim.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/topics.hpp"
#include "smart/geometry/frame_transform.hpp"
#include "smart/grid/grid.hpp"
#include "smart/hw/robot_io.hpp"

namespace smart::commissioning {

struct FramePoint {
  std::string id;  // robot index or object name, substituted for {id}
  int col = 0, row = 0;
  Eigen::Vector2d world_m = Eigen::Vector2d::Zero();  // the cell's centre in the grid frame
};

// Texts "ID:COL,ROW" (each ID once) on `grid` with cells of cell_m metres; `map` names the map in
// errors.
std::vector<FramePoint> place_points(const std::vector<std::string>& texts, const grid::Grid& grid,
                                     double cell_m, const std::string& map);

struct FrameSources {
  hw::PoseKind pose = hw::PoseKind::kVicon;  // kVicon, kOdom or kRos
  std::string vicon_bind = "0.0.0.0";
  uint16_t vicon_port = 51001;
  std::string vicon_object = "jetbot{id}";
  std::string ros_namespace{dds::kRosNamespacePattern};  // --pose odom; {id}: the point's ID
  std::string ros_topic;                                 // --pose ros; {id} is the point's ID
};

struct FrameFit {
  std::vector<Eigen::Vector2d> source;  // each point's mean pose in the source's frame
  geometry::SimilarityFit fit;
  bool accepted = false;
  nlohmann::json report(const std::vector<FramePoint>& points, double tolerance_m) const;
};

FrameFit fit_frame(const FrameSources& sources, const std::vector<FramePoint>& points,
                   double record_s, double tolerance_m, const dds::Participant& participant);

struct TrimTrial {
  double speed_mps = 0.15;
  double seconds = 3.0;
  double settle_s = 0.5;  // poses ignored at the start (acceleration)
  const std::atomic<bool>* stop = nullptr;
};

std::vector<agent::PoseSample> drive_straight(const TrimTrial& trial, uint32_t robot,
                                              hw::RobotIo& io);

// NOLINTNEXTLINE(bugprone-exception-escape): clang-tidy 14 flags the implicit special members
struct TrimProposal {
  nlohmann::json report;  // measured speed, turn rate, gains, trims and the proposed keys
  std::string yaml;       // the keys to put in the robot file
};
TrimProposal propose_trim(uint32_t robot, const agent::WheelTrial& trial,
                          const agent::RobotModel& model, const hw::RobotIo& io);

}  // namespace smart::commissioning
