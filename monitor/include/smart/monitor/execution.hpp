// Contract: what a run executes, as the run supervisor (run_supervisor.hpp) and the monitor's
// DDS edge see it: per robot, a list of actions of which a prefix is finished and a longer
// prefix enqueued (may be executed), the window to send, and whether the run's work is done.
// Two implementations: ExecutionTracker (one plan, a fixed ADG: execution_tracker.hpp) and a
// lifelong run's (lifelong/lifelong_execution.hpp: the ADG grows while robots execute, tasks
// stream in). Pure: times are given, never read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
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

// Why a robot waits now (not done, nothing enqueued to execute), as the run supervisor samples
// it each tick (issue 29: where a lifelong run's waiting goes; the offline attribution of a plan
// run is wait_causes.hpp, whose classes these follow). Its next action waits for the Type-2
// predecessors' robots (the blockers) to leave a location; of several, the latest class counts:
// - kAtLocation: the blocker entered the location (or stood there) and has not left: no passing
//   order lets the waiting robot in sooner; it is executing its move out (or is delayed doing
//   so);
// - kAtLocationTurning: the same, but it is turning there first;
// - kAtLocationWaiting: the same, but the blocker waits itself there (a queue: the waiting
//   robot's wait ends when the blocker's ends);
// - kEntering: the blocker is executing its move into the location;
// - kOnItsWayNear / kOnItsWayFar: the blocker has not begun entering and executes its actions
//   towards it, within / more than SwitchOptions::commit_actions of its entry (far: what a
//   switchable execution would not have sent yet, the part its rule may still switch);
// - kOnItsWayWaiting: the blocker has not begun entering and waits itself (a queue);
// Not behind a robot:
// - kHeld: its next action waits for nobody but is held back (a switchable execution sends a
//   shared entry only near, or decides a due one first);
// - kNoAction: it has no action to execute (a lifelong run: until the planner's next window).
enum class WaitCause : uint8_t {
  kAtLocation,
  kAtLocationTurning,
  kAtLocationWaiting,
  kEntering,
  kOnItsWayNear,
  kOnItsWayFar,
  kOnItsWayWaiting,
  kHeld,
  kNoAction,
};
inline constexpr std::size_t kWaitCauses = 9;
// summary.json's name of each (waiting_time_s.by_cause).
const char* to_string(WaitCause cause);
// A blocker's class from its stay at the location: `enter_seq` its move into it (nullopt: it
// stood there from the start), its robot's progress, and whether the action it executes now
// (seq `finished`) is a turn. Pure: every execution's wait_cause() decides with it.
WaitCause blocker_cause(std::optional<uint32_t> enter_seq, uint32_t finished, uint32_t enqueued,
                        bool turning, uint32_t commit_actions);
// The same for half-cell stays, which begin with the move that enters and end with the next move
// (adg.cpp): the entry is the blocker's last move before `leave_seq` among its unfinished actions
// (none: it is at the location). `type_of(seq)`: the blocker's action types.
template <class TypeOf>
WaitCause half_cell_blocker_cause(uint32_t leave_seq, uint32_t finished, uint32_t enqueued,
                                  uint32_t commit_actions, TypeOf&& type_of) {
  std::optional<uint32_t> enter;
  for (uint32_t s = leave_seq; s-- > finished;) {
    if (type_of(s) == grid::ActionType::kMove) {
      enter = s;
      break;
    }
  }
  return blocker_cause(enter, finished, enqueued, type_of(finished) == grid::ActionType::kRotate,
                       commit_actions);
}

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
  // Why a waiting robot (enqueued == finished, not done) waits; nullopt when it does not wait or
  // this execution does not tell (plain ADG with the cells footprint).
  virtual std::optional<WaitCause> wait_cause(uint32_t /*robot*/) const { return std::nullopt; }
};

// The checks every Execution makes of a robot's progress report: kAdvanced when `finished_seq`
// is new and was enqueued, otherwise kRejected (unknown robot, action out of range or never
// enqueued) or kStale (not newer), with the reason.
ProgressUpdate check_progress(const Execution& e, uint32_t robot, int64_t finished_seq);

}  // namespace smart::monitor
