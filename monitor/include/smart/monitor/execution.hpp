// Contract: what a run executes, as the run supervisor (run_supervisor.hpp) and the monitor's
// DDS edge see it: per robot, a list of actions of which a prefix is finished and a longer
// prefix enqueued (may be executed), the window to send, and whether the run's work is done.
// Two implementations: ExecutionTracker (one plan, a fixed ADG: execution_tracker.hpp) and a
// lifelong run's (lifelong/lifelong_execution.hpp: the ADG grows while robots execute, tasks
// stream in). Pure: times are given, never read.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "smart/grid/action.hpp"
#include "smart/monitor/switching.hpp"

namespace smart::monitor {

enum class ProgressResult { kAdvanced, kStale, kRejected };

struct ProgressUpdate {
  ProgressResult result = ProgressResult::kStale;
  std::string reason;                    // why it was rejected or stale
  std::vector<uint32_t> robots_changed;  // robots whose window changed (to push to them)
};

struct ActionWindowRange {
  uint32_t first = 0;  // seq of the first action in the window
  uint32_t end = 0;    // one past the last seq
  bool empty() const { return first >= end; }
};

class Execution {
 public:
  virtual ~Execution() = default;

  virtual std::size_t robots() const = 0;
  // Cumulative progress of `robot` (seq k finished: every seq <= k), taken at `time_s` (sim
  // time in lock-step, the monitor's wall time in real time).
  virtual ProgressUpdate on_progress(uint32_t robot, int64_t finished_seq, double time_s) = 0;
  // Time passed without progress (each answered tick, each real-time poll); `sent[r]` is one past
  // the last action sent to robot r. Returns the robots whose windows changed.
  virtual std::vector<uint32_t> on_time(double /*time_s*/, const std::vector<uint32_t>& /*sent*/) {
    return {};
  }
  virtual ActionWindowRange window(uint32_t robot, uint32_t cap) const = 0;
  virtual uint32_t finished(uint32_t robot) const = 0;  // count finished
  virtual uint32_t enqueued(uint32_t robot) const = 0;  // count enqueued
  virtual uint32_t known(uint32_t robot) const = 0;     // actions known so far (the wire's total)
  // An action not finished yet (seq in [finished, known)), or, for a fixed plan, any action.
  virtual const grid::Action& action(uint32_t robot, uint32_t seq) const = 0;
  // Done for good: no action will ever come for it (never, in a lifelong run).
  virtual bool robot_done(uint32_t robot) const = 0;
  virtual std::size_t finished_total() const = 0;
  virtual std::size_t total() const = 0;  // actions known so far, all robots
  // The run's work is done: every action finished (a plan), the duration passed (lifelong).
  virtual bool complete() const = 0;
  // No robot has an enqueued unfinished action, yet some remain.
  virtual bool deadlocked() const = 0;
  // A lifelong run never brings robots to a final goal (the goal check is skipped).
  virtual bool lifelong() const { return false; }
  // The passing orders switched so far, in order (issue 29: switching.hpp); null when this
  // execution never switches (plain ADG).
  virtual const std::vector<PassingSwitch>* switches() const { return nullptr; }
};

// The checks every Execution makes of a robot's progress report: kAdvanced when `finished_seq`
// is new and was enqueued, otherwise kRejected (unknown robot, action out of range or never
// enqueued) or kStale (not newer), with the reason.
ProgressUpdate check_progress(const Execution& e, uint32_t robot, int64_t finished_seq);

}  // namespace smart::monitor
