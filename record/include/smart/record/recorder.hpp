// Contract: a run as an MCAP recording with profile ros2 (issue 30; docs/ros2.md "Recordings").
// Channels, in this order:
// - the ROS 2 view, ros2msg schemas (schemas.hpp), CDR, named as the live topics under the run's
//   ROS namespace: <ns>/map (nav_msgs/OccupancyGrid, once at t = 0), <ns>/robot_<i>/plan
//   (nav_msgs/Path, once at t = 0, when the plan is known), <ns>/smart/markers
//   (visualization_msgs/MarkerArray with a fleet write, at most one per markers_period_s, when
//   the plan is known),
//   <ns>/smart/poses (geometry_msgs/PoseArray, robot i at index i), <ns>/tf (tf2_msgs/TFMessage)
//   and, for the chosen robots, <ns>/robot_<i>/pose (geometry_msgs/PoseStamped);
// - the run's own topics, omgidl schemas (idl/smart.idl), CDR, named as on DDS: smart/state
//   (smart::msg::RobotState, a message per states.csv row), smart/progress (smart::msg::Progress,
//   a message per finished action) and smart/events (smart::msg::RunEvent, events.csv rows).
// Messages are stamped (log and publish time) with sim time in nanoseconds, headers with the
// same time (dds::ros_stamp). States are given in time order (states.csv's order; a row older
// than the last is recorded but moves no clock); once the sim time moves on, the fleet's poses at
// the last time are written as one PoseArray and one TFMessage (every robot at its last reported
// pose; a robot never reported stands at its plan's start, else at the origin), at most one per
// fleet_period_s of sim time. Progress and events may be given in any order before or between
// states: each is written once the states have passed its time, so the file is in time order
// (at one time: progress by robot and action, then events as given).
// Memory: one chunk, the fleet's poses and the progress and events not yet written.
// Throws std::invalid_argument for a chosen robot or a row's robot outside the fleet and for an
// invalid namespace (dds::check_ros_namespace).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/monitor/execution_tracker.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/record/cdr.hpp"
#include "smart/record/mcap_writer.hpp"
#include "smart/record/ros_messages.hpp"

namespace smart::record {

struct RecorderOptions {
  std::string ros_namespace;          // "" or "/run_a"
  std::vector<uint32_t> pose_robots;  // robots with their own PoseStamped topic
  double fleet_period_s = 0.1;        // at most one PoseArray + TFMessage per this much sim time
  // At most one MarkerArray per this much sim time: a fleet's markers are 600 bytes a robot, and
  // the live plan view draws them a few times a second of wall time, i.e. far more rarely.
  double markers_period_s = 1.0;
  McapOptions mcap;
};

class RunRecorder {
 public:
  RunRecorder(ByteSink& sink, RecorderOptions options, std::size_t robots, uint64_t run_id);
  // The map (once, before the states).
  void map(const grid::Grid& grid, double cell_m);
  // Each robot's planned path (plan_view.hpp planned_path), once, before the states.
  void plans(const std::vector<std::vector<grid::WorldPoint>>& paths);
  // The plan view: the instance's paths (plans()), and with each fleet write a MarkerArray on
  // <ns>/smart/markers as the live monitor draws it (ros_messages.hpp MarkerMessages), from the
  // instance's ADG replayed with the progress written so far. Once, before the states; `in`
  // must outlive the recorder.
  void plan_view(const monitor::Instance& in, double cell_m, double robot_radius_m);
  // A file carried with the recording (an MCAP attachment; import.hpp names them).
  void attach(std::string_view name, std::string_view media_type, std::string_view data) {
    writer_.attach(name, media_type, data);
  }
  void progress(double t_s, uint32_t robot, int32_t finished_seq);
  void event(const results::EventRow& row);
  void state(const results::StateRow& row);
  void finish();
  uint64_t messages() const { return writer_.messages(); }
  double background_cpu_s() const { return writer_.background_cpu_s(); }
  std::vector<McapWriter::ChannelCount> channel_counts() const { return writer_.channel_counts(); }

 private:
  struct Pending {
    double t_s;
    uint64_t order;      // ties keep the order of the calls
    int64_t event = -1;  // in events_; -1: a progress
    uint32_t robot = 0;
    int32_t finished_seq = -1;
  };
  uint16_t ros_channel(const std::string& type, const std::string& topic, bool latched);
  uint16_t smart_channel(const std::string& type, const std::string& topic);
  void check_robot(uint32_t robot, const char* what) const;
  void write_fleet(double t_s, bool last = false);  // last: the markers too, whatever the period
  void drain(double up_to_s, bool all);
  void write_pending(const Pending& p);

  RecorderOptions options_;
  McapWriter writer_;
  uint64_t run_id_;
  FleetMessages fleet_;
  std::vector<std::optional<grid::WorldPoint>> starts_;
  std::vector<std::optional<grid::WorldPoint>> points_;  // each robot's last reported position
  const monitor::Instance* in_ = nullptr;
  std::optional<monitor::ExecutionTracker> tracker_;
  std::optional<MarkerMessages> markers_;
  uint16_t markers_ch_ = 0;
  uint16_t poses_ch_ = 0, tf_ch_ = 0, state_ch_ = 0, progress_ch_ = 0, events_ch_ = 0;
  std::vector<uint16_t> pose_chs_;
  std::map<std::string, uint16_t> schemas_;  // by type name
  std::vector<Pending> pending_;             // a min-heap by (t_s, order)
  std::vector<results::EventRow> events_;    // the pending events' rows
  CdrWriter cdr_;
  uint64_t order_ = 0;
  bool have_time_ = false, fleet_written_ = false;
  double time_s_ = 0;
  // The periods are counted in the file's own nanoseconds: a clock summed in steps of 0.1 s
  // gives 0.8 - 0.7 < 0.1 in doubles, and the fleet at 0.8 s would go missing.
  uint64_t last_fleet_ns_ = 0;
  std::optional<uint64_t> last_markers_ns_;
};

}  // namespace smart::record
