// Contract: tracks execution of an ADG (SMART §IV-B, Hönig et al. 2019). Every action is
// staged, enqueued or finished. An action becomes enqueued when its Type-1 predecessor is
// enqueued or finished and all its Type-2 predecessors are finished; so each robot's enqueued
// actions are a prefix of its list. Progress is cumulative: finishing seq k finishes every
// seq <= k of that robot. Progress that is out of range, stale (not newer than what is known)
// or for an action never enqueued is rejected and changes nothing. window() gives the actions
// to send a robot: enqueued and not finished, at most `cap` of them. A fixed plan's Execution
// (execution.hpp).
#pragma once

#include <array>
#include <climits>
#include <cstdint>
#include <string>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/execution.hpp"

namespace smart::monitor {

enum class ActionState : uint8_t { kStaged, kEnqueued, kFinished };

class ExecutionTracker final : public Execution {
 public:
  using Result = ProgressResult;
  using Update = ProgressUpdate;
  using Window = ActionWindowRange;

  ExecutionTracker(const ActionPlan& actions, const Adg& adg);

  Update on_progress(uint32_t robot, int64_t finished_seq);
  Update on_progress(uint32_t robot, int64_t finished_seq, double /*time_s*/) override {
    return on_progress(robot, finished_seq);
  }

  Window window(uint32_t robot, uint32_t cap) const override;
  uint32_t finished(uint32_t robot) const override { return finished_[robot]; }
  uint32_t enqueued(uint32_t robot) const override { return enqueued_[robot]; }
  uint32_t known(uint32_t robot) const override { return actions_.count(robot); }
  const grid::Action& action(uint32_t robot, uint32_t seq) const override {
    return actions_.at(robot, seq);
  }
  ActionState state(uint32_t robot, uint32_t seq) const;
  std::size_t robots() const override { return finished_.size(); }
  std::size_t finished_total() const override { return finished_total_; }
  std::size_t total() const override { return actions_.actions.size(); }
  bool robot_done(uint32_t robot) const override {
    return finished_[robot] == actions_.count(robot);
  }
  bool complete() const override { return finished_total_ == actions_.actions.size(); }
  // No robot has an enqueued unfinished action, yet not everything is finished.
  bool deadlocked() const override;
  std::optional<WaitCause> wait_cause(uint32_t robot) const override;

 private:
  bool advance(uint32_t robot);  // enqueues what it can; true when something was enqueued
  void init_look();

  const ActionPlan& actions_;
  const Adg& adg_;
  std::vector<uint32_t> pending_;  // unfinished Type-2 predecessors per node
  // What wait_cause() reads of a blocker's action, per node (half-cell footprints only): its
  // robot, whether it is a turn, and its robot's last move before it (kNoMove: none). One 8-byte
  // read where the plan's 48-byte actions took one per action walked back: 6.7 % of the
  // monitor's CPU under delays (docs/performance.md, "Wait causes read from records, and robots
  // without a goal ranked without a table").
  struct NodeLook {
    uint32_t robot : 31;
    uint32_t turn : 1;
    uint32_t prev_move;
  };
  static constexpr uint32_t kNoMove = UINT32_MAX;
  std::vector<NodeLook> look_;
  std::vector<uint8_t> turning_;  // robot -> its action now (seq finished_) is a turn
  // A waiting robot's blockers, read from the ADG when its wait begins and kept per robot: the
  // run supervisor asks again every 0.5 s of a wait, and each ask read three node-indexed
  // arrays, a cache miss each. Mutable: a cache of what the const ADG says.
  struct Blocker {
    uint32_t robot, leave_seq, prev_move;
  };
  struct WaitLook {
    static constexpr uint32_t kKept = 4;  // more Type-2 predecessors are read each time
    uint32_t node = UINT32_MAX, count = 0;
    std::array<Blocker, kKept> blockers{};
  };
  mutable std::vector<WaitLook> wait_look_;
  Blocker blocker(uint32_t e) const;  // of in-edge e
  std::vector<uint32_t> finished_;
  std::vector<uint32_t> enqueued_;
  std::size_t finished_total_ = 0;
};

}  // namespace smart::monitor
