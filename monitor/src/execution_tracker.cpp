#include "smart/monitor/execution_tracker.hpp"

#include <algorithm>

namespace smart::monitor {

ExecutionTracker::ExecutionTracker(const ActionPlan& actions, const Adg& adg)
    : actions_(actions),
      adg_(adg),
      pending_(actions.actions.size()),
      finished_(actions.robots(), 0),
      enqueued_(actions.robots(), 0) {
  for (std::size_t v = 0; v < pending_.size(); ++v) {
    pending_[v] = adg.in_begin[v + 1] - adg.in_begin[v];
  }
  init_look();
  for (uint32_t r = 0; r < actions.robots(); ++r) advance(r);
}

void ExecutionTracker::init_look() {
  static_assert(grid::kMaxRobots < (int64_t{1} << 31),
                "NodeLook::robot holds a robot id in 31 bits");
  if (adg_.footprint != Footprint::kHalfCells) return;
  look_.resize(actions_.actions.size());
  turning_.assign(actions_.robots(), 0);
  wait_look_.assign(actions_.robots(), {});
  for (uint32_t r = 0; r < actions_.robots(); ++r) {
    uint32_t prev_move = kNoMove;
    for (uint32_t s = 0; s < actions_.count(r); ++s) {
      const auto type = actions_.at(r, s).type;
      look_[actions_.offset[r] + s] = {r, type == grid::ActionType::kRotate, prev_move};
      if (type == grid::ActionType::kMove) prev_move = s;
    }
    turning_[r] = actions_.count(r) > 0 && look_[actions_.offset[r]].turn;
  }
}

bool ExecutionTracker::advance(uint32_t robot) {
  const uint32_t base = actions_.offset[robot];
  const uint32_t count = actions_.count(robot);
  const uint32_t before = enqueued_[robot];
  while (enqueued_[robot] < count && pending_[base + enqueued_[robot]] == 0) ++enqueued_[robot];
  return enqueued_[robot] != before;
}

const char* to_string(WaitCause cause) {
  switch (cause) {
    case WaitCause::kAtLocation:
      return "at_location";
    case WaitCause::kAtLocationTurning:
      return "at_location_turning";
    case WaitCause::kAtLocationWaiting:
      return "at_location_waiting";
    case WaitCause::kEntering:
      return "entering";
    case WaitCause::kOnItsWayNear:
      return "on_its_way_near";
    case WaitCause::kOnItsWayFar:
      return "on_its_way_far";
    case WaitCause::kOnItsWayWaiting:
      return "on_its_way_waiting";
    case WaitCause::kHeld:
      return "held";
    case WaitCause::kNoAction:
      return "no_action";
  }
  return "unknown";
}

WaitCause blocker_cause(std::optional<uint32_t> enter_seq, uint32_t finished, uint32_t enqueued,
                        bool turning, uint32_t commit_actions) {
  if (!enter_seq || *enter_seq < finished) {
    if (enqueued == finished) return WaitCause::kAtLocationWaiting;
    return turning ? WaitCause::kAtLocationTurning : WaitCause::kAtLocation;
  }
  if (*enter_seq == finished) {
    return enqueued > finished ? WaitCause::kEntering : WaitCause::kOnItsWayWaiting;
  }
  if (enqueued == finished) return WaitCause::kOnItsWayWaiting;
  return *enter_seq - finished > commit_actions ? WaitCause::kOnItsWayFar
                                                : WaitCause::kOnItsWayNear;
}

// The robot leaving before the node of in-edge `e`, from its node's look_.
ExecutionTracker::Blocker ExecutionTracker::blocker(uint32_t e) const {
  const uint32_t leave = adg_.in[e];
  const NodeLook l = look_[leave];
  return {l.robot, leave - actions_.offset[l.robot], l.prev_move};
}

// Half-cell stays only: the cells footprint's span several moves, and its entries are not
// read from the edges (not told).
std::optional<WaitCause> ExecutionTracker::wait_cause(uint32_t robot) const {
  if (robot_done(robot) || enqueued_[robot] > finished_[robot]) return std::nullopt;
  if (adg_.footprint != Footprint::kHalfCells) return std::nullopt;
  const uint32_t node = actions_.offset[robot] + enqueued_[robot];
  WaitLook& w = wait_look_[robot];
  if (w.node != node) {  // a new wait: its blockers read from the ADG once
    w.node = node;
    w.count = adg_.in_begin[node + 1] - adg_.in_begin[node];
    for (uint32_t k = 0; k < std::min<uint32_t>(w.count, WaitLook::kKept); ++k) {
      w.blockers[k] = blocker(adg_.in_begin[node] + k);
    }
  }
  auto cause = WaitCause::kAtLocation;
  bool held = true;  // every blocker has left: pending_[node] == 0
  const auto take = [&](const Blocker& b) {
    const uint32_t done = finished_[b.robot];
    if (b.leave_seq < done) return;
    held = false;
    // half_cell_blocker_cause's walk back, read from the leaving node's look_.
    const auto enter = b.prev_move != kNoMove && b.prev_move >= done
                           ? std::optional<uint32_t>(b.prev_move)
                           : std::nullopt;
    cause = std::max(cause, blocker_cause(enter, done, enqueued_[b.robot], turning_[b.robot] != 0,
                                          SwitchOptions{}.commit_actions));
  };
  for (uint32_t k = 0; k < w.count; ++k) {
    take(k < WaitLook::kKept ? w.blockers[k] : blocker(adg_.in_begin[node] + k));
  }
  return held ? WaitCause::kHeld : cause;
}

ProgressUpdate check_progress(const Execution& e, uint32_t robot, int64_t finished_seq) {
  ProgressUpdate u;
  if (robot >= e.robots()) {
    u.result = ProgressResult::kRejected;
    u.reason = "robot " + std::to_string(robot) + " does not exist (the plan has " +
               std::to_string(e.robots()) + " robots)";
    return u;
  }
  const int64_t count = e.known(robot);
  if (finished_seq >= count) {
    u.result = ProgressResult::kRejected;
    u.reason = "robot " + std::to_string(robot) + " reports action " +
               std::to_string(finished_seq) + " finished but has only " + std::to_string(count) +
               " actions";
    return u;
  }
  if (finished_seq < static_cast<int64_t>(e.finished(robot))) {
    u.result = ProgressResult::kStale;
    u.reason = "robot " + std::to_string(robot) + " already finished " +
               std::to_string(e.finished(robot)) + " actions";
    return u;
  }
  if (finished_seq >= static_cast<int64_t>(e.enqueued(robot))) {
    u.result = ProgressResult::kRejected;
    u.reason = "robot " + std::to_string(robot) + " reports action " +
               std::to_string(finished_seq) + " finished but only actions below " +
               std::to_string(e.enqueued(robot)) + " were enqueued";
    return u;
  }
  u.result = ProgressResult::kAdvanced;
  return u;
}

ExecutionTracker::Update ExecutionTracker::on_progress(uint32_t robot, int64_t finished_seq) {
  Update u = check_progress(*this, robot, finished_seq);
  if (u.result != Result::kAdvanced) return u;
  u.robots_changed.push_back(robot);
  const uint32_t base = actions_.offset[robot];
  const auto upto = static_cast<uint32_t>(finished_seq + 1);
  for (uint32_t s = finished_[robot]; s < upto; ++s) {
    const uint32_t node = base + s;
    for (uint32_t i = adg_.out_begin[node]; i < adg_.out_begin[node + 1]; ++i) {
      const uint32_t v = adg_.out[i];
      if (--pending_[v] == 0) {
        const uint32_t other = actions_.actions[v].robot;
        if (advance(other)) u.robots_changed.push_back(other);
      }
    }
  }
  finished_total_ += upto - finished_[robot];
  finished_[robot] = upto;
  if (!turning_.empty()) turning_[robot] = upto < actions_.count(robot) && look_[base + upto].turn;
  std::sort(u.robots_changed.begin(), u.robots_changed.end());
  u.robots_changed.erase(std::unique(u.robots_changed.begin(), u.robots_changed.end()),
                         u.robots_changed.end());
  return u;
}

ExecutionTracker::Window ExecutionTracker::window(uint32_t robot, uint32_t cap) const {
  return {finished_[robot], std::min(enqueued_[robot], finished_[robot] + cap)};
}

ActionState ExecutionTracker::state(uint32_t robot, uint32_t seq) const {
  if (seq < finished_[robot]) return ActionState::kFinished;
  if (seq < enqueued_[robot]) return ActionState::kEnqueued;
  return ActionState::kStaged;
}

bool ExecutionTracker::deadlocked() const {
  if (complete()) return false;
  for (std::size_t r = 0; r < finished_.size(); ++r) {
    if (enqueued_[r] > finished_[r]) return false;
  }
  return true;
}

}  // namespace smart::monitor
