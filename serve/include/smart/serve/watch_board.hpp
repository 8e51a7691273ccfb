// Contract: what `smart serve --watch` knows of the runs live on a DDS domain, built from samples
// the DDS edge (fleet_watch.hpp) has already checked (wire/validate.hpp). Pure: no DDS, no
// clock read (every event carries the wall time now_s), deterministic.
// - Robots are keyed by (run, robot id); the board shows one run: the one asked for, else the
//   one heard of most recently. Physical and simulated robots look alike here (the same
//   RobotState and Progress topics), so a mixed run shows all of them.
// - A robot's status, from what its host says it does (Progress, RobotState's queue), not from
//   its speed (issue 26: a JetBot's Vicon noise made every robot "moving" at 0 m/s): "moving"
//   (executing an action), "waiting" (actions queued, none executing: its dependencies are not
//   finished), "idle" (nothing queued: done, or waiting for its next window), "stale" (nothing
//   heard for stale_s: lost, or the run ended).
// - The run's time is the newest robot time heard: sim hosts report sim time, agents the time
//   since their run's first window (tools/src/agent_command.cpp; issue 26: an agent reported
//   its host's uptime, 3272 s shown 15 s into a run).
// - At most kMaxRobots robots and kMaxRuns runs are kept (samples are untrusted: a flood of
//   made-up ids cannot grow memory without bound); the oldest run is dropped first.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace smart::serve {

struct WatchedState {
  uint32_t robot = 0;
  uint64_t run_id = 0;
  double sim_time_s = 0;
  double x_m = 0, y_m = 0, yaw_rad = 0;
  double linear_mps = 0, angular_radps = 0;
  uint32_t queue = 0;
};

struct WatchedProgress {
  uint32_t robot = 0;
  uint64_t run_id = 0;
  int64_t finished_seq = -1, executing_seq = -1;
};

struct WatchedMonitor {
  uint64_t run_id = 0;
  std::string host;
  int64_t pid = 0;
  std::string run;  // the run's name (--run), as its monitor announces it
};

class WatchBoard {
 public:
  static constexpr std::size_t kMaxRobots = 100000;
  static constexpr std::size_t kMaxRuns = 16;
  explicit WatchBoard(double stale_s = 3.0) : stale_s_(stale_s) {}

  void on_state(const WatchedState& s, double now_s);
  void on_progress(const WatchedProgress& p, double now_s);
  void on_monitor(const WatchedMonitor& m, double now_s);

  // {"runs": [{"run_id", "name", "robots", "heard_s_ago"}], "run_id" (shown; 0: none), "name"
  // (its name, "" until its monitor is heard), "monitor": {"host", "pid"} or null, "t_s" (the
  // run's time), "robots": [{"id", "x_m", "y_m",
  // "yaw_rad", "status", "queue", "finished_seq", "executing_seq", "linear_mps"}]} by robot id.
  // run_id 0: the run heard of most recently.
  nlohmann::json snapshot(double now_s, uint64_t run_id = 0) const;

 private:
  struct Robot {
    WatchedState state;
    WatchedProgress progress;
    double heard_s = -1;  // wall time of the last state or progress
  };
  struct Run {
    std::map<uint32_t, Robot> robots;
    WatchedMonitor monitor;
    bool monitor_known = false;
    double heard_s = 0;
    double sim_time_s = 0;
  };
  Run* run_for(uint64_t run_id, double now_s);  // nullptr when the robot limit is reached
  Robot* robot_for(uint64_t run_id, uint32_t robot, double now_s);
  nlohmann::json robot_json(const Robot& r, double now_s) const;

  double stale_s_;
  std::map<uint64_t, Run> runs_;
  std::size_t robots_ = 0;
};

}  // namespace smart::serve
