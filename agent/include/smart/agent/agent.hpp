// Contract: one robot's executor, the same class for simulated and physical robots.
// - Lifecycle (ros2_control style, lifecycle.hpp): configure() opens the backend, activate()
//   allows motion, deactivate() brings the wheels to zero. Only an active agent moves. A call the
//   backend fails leaves the agent in its state (deactivate: inactive all the same, it never
//   moves again unless activated) and returns the backend's result, naming the robot.
// - on_window() feeds the monitor's action window into the ActionQueue (idempotent).
// - step(now_s) is the cyclic read/update/write at the control period: read the pose; if it is
//   invalid or older than pose_timeout_s the wheels are stopped at once (watchdog); otherwise
//   advance the queue and write wheel speeds. Consecutive moves along one heading are merged
//   into one run driven without stopping, and each half-move is reported finished as the
//   robot passes its end (the last one of the run when the robot has stopped on it).
// - Execution uncertainty (model.uncertainty, uncertainty.hpp): the robot's top speed is scaled
//   by its speed factor; an action that starts from rest (a rotation, or a move that does not
//   continue a run of moves along its heading) may first be held for stall_s (stalled()); a
//   delay event (LoRR's, drawn per 0.1 s tick of the robot's clock) stops the robot where it is,
//   braking within its limits, for the event's duration (delayed()).
// - progress: finished_seq() is cumulative (every seq <= it is done); executing_seq() is the
//   action at the front of the queue, -1 when idle.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/agent/action_queue.hpp"
#include "smart/agent/controller.hpp"
#include "smart/agent/interfaces.hpp"
#include "smart/agent/robot_model.hpp"

namespace smart::agent {

struct AgentConfig {
  uint32_t robot_id = 0;
  RobotModel model;
  double period_s = 0.1;
  double pose_timeout_s = 0.5;
};

enum class LifecycleState { kUnconfigured, kInactive, kActive };

// Everything an agent carries from one control period to the next, so that another process can
// continue it bit for bit (a robot moving between sim shards, sim/shard.hpp).
struct AgentSnapshot {
  Twist last_command;  // the controller's
  ActionQueue::Snapshot queue;
  PoseSample pose;
  WheelSpeeds wheels;
  bool stale = false;
  bool had_pose = false;
  uint64_t watchdog_stops = 0;
  double now_s = 0;
  double stall_until_s = -1;
  int64_t stall_checked_seq = -1;
  bool last_front_move = false;
  double last_front_heading_rad = 0;
  uint64_t stalls = 0;
  double delay_until_s = -1;
  int64_t delay_tick = -1;  // the last delay tick drawn
  uint64_t delays = 0;
};

class Agent {
 public:
  Agent(AgentConfig config, DriveBackend& drive, PoseSource& pose);

  LifecycleResult configure();
  LifecycleResult activate();
  LifecycleResult deactivate();
  LifecycleState state() const { return state_; }

  ActionQueue::Result on_window(uint64_t run_id, const std::vector<AgentAction>& window);
  AgentSnapshot snapshot() const;
  // Continues from a snapshot (the lifecycle state is not part of it).
  void restore(const AgentSnapshot& s);
  void step(double now_s);

  uint32_t robot_id() const { return config_.robot_id; }
  uint64_t run_id() const { return queue_.run_id(); }
  int64_t finished_seq() const { return queue_.finished_seq(); }
  int64_t executing_seq() const {
    return queue_.empty() ? int64_t{-1} : static_cast<int64_t>(queue_.front().seq);
  }
  std::size_t queue_length() const { return queue_.pending().size(); }
  const PoseSample& last_pose() const { return pose_sample_; }
  WheelSpeeds last_command() const { return command_; }
  bool pose_stale() const { return stale_; }
  uint64_t watchdog_stops() const { return watchdog_stops_; }
  bool stalled() const { return stall_until_s_ > now_s_; }
  uint64_t stalls() const { return stalls_; }
  bool delayed() const { return delay_until_s_ > now_s_; }
  uint64_t delays() const { return delays_; }
  // True when nothing is queued and the wheels are at rest: the backend may let it sleep.
  bool idle() const { return queue_.empty() && command_.left_mps == 0 && command_.right_mps == 0; }

 private:
  // Prefixes a failed result's message with the robot id.
  LifecycleResult named(LifecycleResult r) const;
  void write(Twist t);
  // Runs the front actions; returns the command for this period.
  Twist update();
  // A new front action, from rest: maybe a stall (uncertainty.hpp).
  void maybe_stall();
  // A new delay tick: maybe a delay event (uncertainty.hpp).
  void maybe_delay();

  AgentConfig config_;
  DriveBackend& drive_;
  PoseSource& pose_;
  Controller controller_;
  ActionQueue queue_;
  LifecycleState state_ = LifecycleState::kUnconfigured;
  PoseSample pose_sample_;
  WheelSpeeds command_;
  bool stale_ = false;
  bool had_pose_ = false;  // a fresh pose was seen once
  uint64_t watchdog_stops_ = 0;
  double now_s_ = 0;
  double stall_until_s_ = -1;
  int64_t stall_checked_seq_ = -1;  // the last action a stall was drawn for
  bool last_front_move_ = false;    // that action's kind and heading
  double last_front_heading_rad_ = 0;
  uint64_t stalls_ = 0;
  double delay_until_s_ = -1;
  int64_t delay_tick_ = -1;
  uint64_t delays_ = 0;
};

}  // namespace smart::agent
