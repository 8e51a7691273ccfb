// Contract: how long the fleet's actions take, learned from its progress reports, and when a
// robot is expected to finish an action of its queue: the expected times `--execution
// switchable-opt` compares passing orders by (switchable_tracker.hpp, issue 29).
// - observe(): one action's duration, from its start (its robot's previous finish, or its
//   sending when later) to its finish. The mean per kind (move, rotate) is a running mean that
//   forgets slowly (weight at least 1/256): durations include the delays robots had, so the
//   estimate carries the expected delay per action, as SES's expected-delay rescheduling does
//   (Feng et al., "Switchable Edge Search", ICAPS 2024, §3: delays as expected extra durations).
// - finish_s(): now, a robot's current action's start and kinds of the actions to go: the
//   current one ends at start + mean (a late one, already past it, is expected to take one more
//   mean from now), each next one a mean later. Waits for other robots are not foreseen.
// - queue_saving(): the expected waiting saved at one location when stay j passes stay i, the
//   comparison both switchable-opt executions make (one-shot and lifelong).
// Pure and deterministic: told the time, never reads a clock.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "smart/grid/action.hpp"

namespace smart::monitor {

class ActionDurations {
 public:
  explicit ActionDurations(double initial_s = 1.0) { mean_s_.fill(initial_s); }

  void observe(grid::ActionType type, double duration_s);
  double mean_s(grid::ActionType type) const { return mean_s_[index(type)]; }
  // When the last of `to_go` ends: to_go[0] is the current action, started at `started_s` (or
  // not started yet: negative `started_s`, it starts now).
  double finish_s(double now_s, double started_s, std::span<const grid::ActionType> to_go) const;
  // The same, told the current action's kind and how many of each kind follow it: O(1) for a
  // caller that counts kinds by prefix sums (SwitchableTracker: a lookahead asks thousands of
  // times a decision; the loop over the queue was most of its cost).
  struct Later {
    uint32_t moves = 0, rotations = 0;
  };
  double finish_s(double now_s, double started_s, grid::ActionType current, Later later) const;

 private:
  static std::size_t index(grid::ActionType t) { return t == grid::ActionType::kMove ? 0 : 1; }
  std::array<double, 2> mean_s_{};
  std::array<uint32_t, 2> samples_{};
};

// Two robots' expected times at one location: when each arrives and how long it stays.
struct ExpectedStay {
  double arrive_s = 0;
  double stay_s = 0;
};

// A location's queue: it frees at `free_s`, stay i then j (or j then i) pass, each entering when
// it arrives and the one before has left; the next robot, expected at `next_arrive_s` (infinite:
// none, or not expected), waits for the last of the two.
struct PassQueue {
  double free_s = 0;
  ExpectedStay i, j;
  double next_arrive_s = 0;
};

// The expected waiting (i's, j's and the next robot's) saved by the order j, i over i, j.
// Inline: out of line it made switchable-opt's replay bench 6 % slower than the lambda it
// replaced (docs/performance.md).
inline double queue_saving(const PassQueue& q) {
  const auto waits = [&q](const ExpectedStay& first, const ExpectedStay& second) {
    const double e1 = std::max(first.arrive_s, q.free_s);
    const double e2 = std::max(second.arrive_s, e1 + first.stay_s);
    const double next =
        std::isfinite(q.next_arrive_s) ? std::max(0.0, e2 + second.stay_s - q.next_arrive_s) : 0.0;
    return (e1 - first.arrive_s) + (e2 - second.arrive_s) + next;
  };
  return waits(q.i, q.j) - waits(q.j, q.i);
}

}  // namespace smart::monitor
