// Contract: tracks execution of an ADG (SMART §IV-B, Hönig et al. 2019). Every action is
// staged, enqueued or finished. An action becomes enqueued when its Type-1 predecessor is
// enqueued or finished and all its Type-2 predecessors are finished; so each robot's enqueued
// actions are a prefix of its list. Progress is cumulative: finishing seq k finishes every
// seq <= k of that robot. Progress that is out of range, stale (not newer than what is known)
// or for an action never enqueued is rejected and changes nothing. window() gives the actions
// to send a robot: enqueued and not finished, at most `cap` of them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"

namespace smart::monitor {

enum class ActionState : uint8_t { kStaged, kEnqueued, kFinished };

class ExecutionTracker {
 public:
  enum class Result { kAdvanced, kStale, kRejected };
  struct Update {
    Result result = Result::kStale;
    std::string reason;                    // why it was rejected or stale
    std::vector<uint32_t> robots_changed;  // robots whose window changed (to push to them)
  };
  struct Window {
    uint32_t first = 0;  // seq of the first action in the window
    uint32_t end = 0;    // one past the last seq
    bool empty() const { return first >= end; }
  };

  ExecutionTracker(const ActionPlan& actions, const Adg& adg);

  Update on_progress(uint32_t robot, int64_t finished_seq);

  Window window(uint32_t robot, uint32_t cap) const;
  uint32_t finished(uint32_t robot) const { return finished_[robot]; }  // count finished
  uint32_t enqueued(uint32_t robot) const { return enqueued_[robot]; }  // count enqueued
  ActionState state(uint32_t robot, uint32_t seq) const;
  std::size_t robots() const { return finished_.size(); }
  std::size_t finished_total() const { return finished_total_; }
  std::size_t total() const { return actions_.actions.size(); }
  bool robot_done(uint32_t robot) const { return finished_[robot] == actions_.count(robot); }
  bool complete() const { return finished_total_ == actions_.actions.size(); }
  // No robot has an enqueued unfinished action, yet not everything is finished.
  bool deadlocked() const;

 private:
  bool advance(uint32_t robot);  // enqueues what it can; true when something was enqueued

  const ActionPlan& actions_;
  const Adg& adg_;
  std::vector<uint32_t> pending_;  // unfinished Type-2 predecessors per node
  std::vector<uint32_t> finished_;
  std::vector<uint32_t> enqueued_;
  std::size_t finished_total_ = 0;
};

}  // namespace smart::monitor
