// Contract: where a plain ADG run's waiting went (issue 29, docs/execution.md "What switching
// can reach"), from the finish time of every action. Under plain ADG a robot is sent an action
// once every Type-2 predecessor has finished (SMART §IV-B); it waits from the end of its previous
// action (0 for its first) until the last of them ends. That wait is charged to the robot whose
// leave ended last (the blocker) and split by what the blocker was doing meanwhile:
// - on_its_way: it had not begun its action that enters the location (started: its previous
//   action finished and its own predecessors had): the order of such a pair could still be
//   switched (switchable_tracker.hpp: an entry sent is never taken back). Of it,
//   on_its_way_waiting: the blocker was itself waiting for another robot meanwhile (a queue:
//   switching moves such a wait along rather than removing it); the rest it was executing its
//   actions towards the location (moving, turning, or delayed doing so). Also of it,
//   uncommitted: the blocker was more than `commit_actions` actions from its entry, which
//   switchable execution would not have sent yet: the only part of a wait its rule may switch;
//   and of that, uncommitted_cycle: letting the waiter pass would have closed a cycle (its
//   leaving depended on the blocker's entry otherwise, e.g. the blocker goes on ahead of it:
//   switchable_tracker.hpp's deadlock search at the wait's start, on the plan's edges);
// - entering: it was executing that action;
// - at_location: it had entered (or stood there from the start) and not left: no passing order
//   lets the waiting robot in before it leaves.
// An attribution to the last predecessor, not a bound: a switch elsewhere can shorten a wait
// behind a robot at the location (its blocker's own wait), and one behind a robot on its way
// moves to that robot when switched. Dispatch delays (a tick, the network) are not in finish
// times, so total_s is a little below the run's own waiting (robots.csv). Pure.
#pragma once

#include <cstddef>
#include <vector>

#include "smart/monitor/adg.hpp"
#include "smart/monitor/switching.hpp"

namespace smart::monitor {

struct WaitCauses {
  double total_s = 0;
  double on_its_way_s = 0;
  double on_its_way_waiting_s = 0;  // of on_its_way_s: the blocker waited for others meanwhile
  double uncommitted_s = 0;         // of on_its_way_s: its entry more than commit_actions away
  double uncommitted_cycle_s = 0;   // of uncommitted_s: passing would have closed a cycle
  double entering_s = 0;
  double at_location_s = 0;
  std::size_t waits = 0;  // actions waited for (a wait over zero)
};

// `orders`: the passing orders the run kept (passing_orders() of a plain ADG run); `finish_s`:
// by ADG node, NaN where never finished (a robot's actions after it are not counted). Throws
// std::invalid_argument when finish_s is not one time per action.
// `commit_actions`: switchable execution's (`--switch-commit-actions`).
WaitCauses wait_causes(const ActionPlan& actions, const PassingOrders& orders,
                       const std::vector<double>& finish_s,
                       uint32_t commit_actions = SwitchOptions{}.commit_actions);

}  // namespace smart::monitor
