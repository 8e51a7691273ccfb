// Contract: what switching passing orders (issue 29) is told and what it records, shared by the
// one-shot SwitchableTracker (switchable_tracker.hpp) and the lifelong LiveAdg (live_adg.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace smart::monitor {

// commit_actions: how near its robot a switchable entry is sent. Near (1) leaves the most room
// to switch, but a robot that does not know its next actions brakes before each such entry: on
// SMART's 100-robot warehouse plan it cost 16 % AET without delays; 6 keeps AET
// (docs/execution.md).
//
// anticipate (`--execution switchable-opt`): besides first come, first served, the order is
// chosen by expected times when an entry is about to be sent (switchable_tracker.hpp,
// "Anticipation"); a switch needs an expected saving of more than margin_s. 10 s: at 0.5 s it
// held ready robots for small expected savings, and lost at 750-1000 robots (1000 robots on
// random-64-64-10 without delays: AET +1.1 % against plain ADG, -1.5 % at 10 s); at 50-200
// robots 10 s is as good (docs/execution.md, "switchable-opt").
// switchable-lookahead's reach unless told otherwise (`--switch-lookahead-actions`): the
// reasons are SwitchOptions::lookahead_actions'.
inline constexpr uint32_t kDefaultLookaheadActions = 24;

struct SwitchOptions {
  uint32_t commit_actions = 6;       // a switchable entry is sent this many actions ahead
  std::size_t search_budget = 4096;  // actions the deadlock search may visit per candidate
  bool anticipate = false;
  double margin_s = 10.0;         // expected fleet waiting an anticipated switch must save
  uint32_t horizon_actions = 12;  // farther robots are not expected anywhere (no switch)
  // Lookahead (`--execution switchable-lookahead`, with anticipate): a pair's two orders are
  // compared by the expected finish times of the actions they affect, up to lookahead_actions
  // ahead of each robot and lookahead_nodes in all (0: at the location alone, as above), and an
  // anticipated switch must save more than lookahead_margin_s. 24 actions, 512 nodes and 0.5 s:
  // on random-64-64-10 at 200 and 750 robots (LoRR-style delays, ten seeds) fewer nodes cut
  // the cone where it differs between decisions and pairs switched back and forth (9-24
  // thousand switches a run at 750 robots, against 0.9-1.3 thousand); 12 actions waited 1-2
  // points more (docs/execution.md, "switchable-lookahead").
  uint32_t lookahead_actions = 0;  // switchable-lookahead: kDefaultLookaheadActions unless told
  std::size_t lookahead_nodes = 512;
  // A pair is first compared over this many of the cone's actions, and not over the rest when
  // the swap loses more than one move's expected duration there (switchable_lookahead.cpp).
  std::size_t lookahead_first_nodes = 16;
  double lookahead_margin_s = 0.5;
  // A ready robot refused because the robot it would pass goes on ahead of it (the deadlock
  // search's path enters its leaving from that robot's stay directly before its own at the
  // next location) passes it there too, up to this many locations at once, when that closes
  // no cycle (switchable_chain.cpp). 1: one location, as BTPG's bidirectional pairs.
  uint32_t chain_locations = 8;
  // Window search (`--switch-window-pairs`, switchable-lookahead): a pair's widened comparison
  // also tries both orders of up to this many other pairs in its cone (at other locations, one
  // a location, their first robot not yet sent its entry), every setting of them, and the pair
  // swaps when the best setting with it swapped beats the best with it kept: SES's optimal
  // search (Feng et al., ICAPS 2024, §5) over a bounded window, decided for the one edge due,
  // the window's others left to their own turn (receding horizon). 2^n settings of n pairs,
  // so bounded by kMaxWindowPairs. 0: off (one pair's two orders, as before).
  uint32_t window_pairs = 0;
};

inline constexpr uint32_t kMaxWindowPairs = 6;

// The window search's rule, shared by SwitchableTracker and LiveAdg: over every setting of
// `pairs` window pairs (bit b set: pair b in its other order, made by set(setting) and undone by
// reset(setting)), the expected cost cost(swapped) of the compared pair kept and swapped; the
// saving of the swap is the best kept setting's cost less the best swapped one's.
template <class Set, class Reset, class Cost>
double window_search_saving(uint32_t pairs, Set&& set, Reset&& reset, Cost&& cost) {
  double kept = std::numeric_limits<double>::infinity(), swapped = kept;
  for (uint32_t setting = 0; setting < (1u << pairs); ++setting) {
    set(setting);
    kept = std::min(kept, cost(false));
    swapped = std::min(swapped, cost(true));
    reset(setting);
  }
  return kept - swapped;
}

// The execution's name in summary.json and results.csv (`smart run --execution`).
inline const char* execution_name(const SwitchOptions& o) {
  if (!o.anticipate) return "switchable";
  return o.lookahead_actions > 0 ? "switchable-lookahead" : "switchable-opt";
}

// One switch: at `location` (half-cell index), `first` now passes before `second`, at `time_s`.
// The two stays are named by the actions that enter them (node ids of the run's ActionPlan),
// which tell a robot's visits to one location apart: a resumed monitor replays the switches
// onto exactly the stays they swapped (adg.hpp apply_switches). kUnrecorded where not known
// (lifelong runs; switches.csv files written before 2026-12-02).
inline constexpr uint32_t kUnrecorded = 0xffffffffu;
struct PassingSwitch {
  double time_s = 0;
  uint32_t location = 0;
  uint32_t first = 0;        // the robot that was ready
  uint32_t second = 0;       // the robot that was meant to pass first
  bool anticipated = false;  // by expected times before `second` was sent (switchable-opt)
  uint32_t first_enter = kUnrecorded, second_enter = kUnrecorded;  // node ids
  bool operator==(const PassingSwitch&) const = default;
};

}  // namespace smart::monitor
