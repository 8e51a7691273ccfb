// SwitchableTracker's lookahead (switchable_tracker.hpp, "Lookahead"): a pair's two orders
// compared by the expected finish times of every action the pair affects, as SES evaluates a
// setting of switchable edges (Feng et al., "Switchable Edge Search", ICAPS 2024, §4: the
// expected completion times of a graph are its longest paths under expected durations), for
// the one edge about to be decided and a bounded cone of the graph after it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "smart/monitor/switchable_tracker.hpp"

namespace smart::monitor {

// The stay after `stay` in the current order, or with i and j swapped (h, j, i, k).
uint32_t SwitchableTracker::next_in(uint32_t stay, const Swap& s) const {
  if (!s.swapped) return link_[stay].next;
  if (stay == s.j) return s.i;
  if (stay == s.i) return link_[s.j].next;
  const uint32_t next = link_[stay].next;
  return next == s.i ? s.j : next;
}

uint32_t SwitchableTracker::prev_in(uint32_t stay, const Swap& s) const {
  if (!s.swapped) return link_[stay].prev;
  if (stay == s.i) return s.j;
  if (stay == s.j) return link_[s.i].prev;
  const uint32_t prev = link_[stay].prev;
  return prev == s.j ? s.i : prev;
}

// The unfinished actions after i's and j's entries in either order, within lookahead_actions of
// their robots' progress, breadth first up to `nodes`: the same set for both orders. With
// `extend`, the walk's actions are added to the cone already collected (a chain's two orders,
// each walked in its own graph: chain_saves), each walk cut at `nodes` on its own.
void SwitchableTracker::collect_cone(const Swap& s, std::size_t nodes, bool extend) {
  if (look_.empty()) init_look();
  if (extend) {
    // This walk's visit mark is `order` (free until cone_cost times the cone, with a new id).
    next_mark(order_id_, &Look::order);
    walk_.clear();
    walk_robot_.clear();
    walk_cone<true>(s, nodes);
    return;
  }
  next_mark(cone_id_, &Look::cone);
  cone_.clear();
  cone_robot_.clear();
  walk_cone<false>(s, nodes);
}

// One walk: the cone's own (its queue is the cone), or, kExtend, a second one in walk_ whose
// actions not yet in the cone join it. Two instances, so that the first walk, made for every
// comparison, costs what it did before chains were compared (docs/execution.md, "Cost").
template <bool kExtend>
void SwitchableTracker::walk_cone(const Swap& s, std::size_t nodes) {
  std::vector<uint32_t>& queue = kExtend ? walk_ : cone_;
  std::vector<uint32_t>& queue_robot = kExtend ? walk_robot_ : cone_robot_;
  // A stay's robot is known where its entry is found: an action's robot and place in its queue
  // without reading the action (a cache miss each; the walk's largest cost).
  const auto add = [&](uint32_t node, uint32_t robot) {
    const uint32_t seq = node - actions_.offset[robot];
    if (seq < finished_[robot] || seq > finished_[robot] + options_.lookahead_actions) return;
    Look& l = look_[node];
    if constexpr (kExtend) {
      if (l.order == order_id_ || queue.size() >= nodes) return;
      l.order = order_id_;
      if (l.cone != cone_id_) {
        l.cone = cone_id_;
        cone_.push_back(node);
        cone_robot_.push_back(robot);
      }
    } else {
      if (l.cone == cone_id_ || queue.size() >= nodes) return;
      l.cone = cone_id_;
    }
    // Read when the node is walked, later: fetched now, while the queue before it is walked;
    // and the robot's next action, which is added then (one past the end at most: a prefetch
    // never faults). This halved the walk's samples (docs/execution.md, "A robot's next actions
    // read together").
    __builtin_prefetch(near_.data() + node);
    __builtin_prefetch(look_.data() + node + 1);
    queue.push_back(node);
    queue_robot.push_back(robot);
  };
  // In an order that does not depend on which stay is first now (the smaller stay id's entry
  // first, the graph with it first walked first): the pair compared again after a swap, before
  // anything changed, gets the same cone, truncated the same, and the opposite answer. Rooted at
  // i then j, a cone cut at lookahead_nodes differed, and pairs were swapped back and forth.
  const uint32_t low = std::min(s.i, s.j), high = std::max(s.i, s.j);
  add(stay_[low].enter, stay_[low].robot);
  add(stay_[high].enter, stay_[high].robot);
  const Swap orders[2] = {{s.i, s.j, s.j == low}, {s.i, s.j, s.i == low}};
  const uint32_t h = link_[s.i].prev;  // the stays whose next differs between the orders: h, i, j
  // By index: add() grows the queue while it is walked (a range-for's iterators would dangle).
  // Until the walk is full: a full walk's remaining actions would add nothing.
  for (std::size_t q = 0; q < queue.size() && queue.size() < nodes; ++q) {
    const uint32_t u = queue[q], robot = queue_robot[q];
    if (u + 1 < actions_.offset[robot + 1]) add(u + 1, robot);
    const Look& l = look_[u];  // in cache: add() marked it
    const uint32_t leaves = stays_of(l.leaves, leave_begin_, u);
    for (uint32_t e = 0; e < leaves; ++e) {
      const uint32_t x = e == 0 ? l.leave : leave_stays_[leave_begin_[u] + e];
      if (x != h && x != s.i && x != s.j) {
        // The same next stay in both orders (none: no entry), its robot and entry in near_.
        const Near next = e == 0 ? near_[u] : near_of(x);
        if (next.next_enter != kNoAction && next.next_robot != robot) {
          add(next.next_enter, next.next_robot);
        }
        continue;
      }
      for (const Swap& o : orders) {
        const uint32_t next = next_in(x, o);
        if (next != kNoAction && stay_[next].robot != robot && stay_[next].enter != kNoAction) {
          add(stay_[next].enter, stay_[next].robot);
        }
      }
    }
  }
}

// A new id for the marks `mark` of look_ (all cleared when the ids wrap around).
void SwitchableTracker::next_mark(uint32_t& id, uint32_t Look::*mark) {
  if (++id != 0) return;
  for (auto& l : look_) l.*mark = 0;
  id = 1;
}

void SwitchableTracker::init_look() {
  look_.resize(actions_.actions.size());
  for (std::size_t n = 0; n < look_.size(); ++n) {
    const auto& a = actions_.actions[n];
    look_[n].robot = a.robot;
    look_[n].type = a.type;
    // A node's first stay of a CSR and how many (255: more, counted by stays_of()).
    const auto first = [n](const std::vector<uint32_t>& begin, const std::vector<uint32_t>& stays,
                           uint32_t& stay, uint8_t& count) {
      const uint32_t c = begin[n + 1] - begin[n];
      if (c > 0) stay = stays[begin[n]];
      count = static_cast<uint8_t>(std::min<uint32_t>(c, 255));
    };
    first(enter_begin_, enter_stays_, look_[n].enter, look_[n].enters);
    first(leave_begin_, leave_stays_, look_[n].leave, look_[n].leaves);
  }
}

// The expected finish of `node` in order `s`: its robot's previous action and its Type-2
// predecessors finished (expected, or now), plus its kind's mean duration. Outside the cone, a
// predecessor's time is its robot's own queue (waits not foreseen), the same in both orders.
// Infinite on a cycle (the swap would deadlock).
double SwitchableTracker::expect(uint32_t node, const Swap& s) {
  Look& look = look_[node];
  if (look.order == order_id_) {
    // On the path being computed: a cycle.
    if (std::isnan(look.time_s)) return std::numeric_limits<double>::infinity();
    return look.time_s;
  }
  look.order = order_id_;
  const Look& a = look;
  const uint32_t seq = node - actions_.offset[a.robot];
  if (seq == finished_[a.robot] && sent_by(a.robot, node)) {
    return look.time_s = finish_estimate(a.robot, seq);
  }
  look.time_s = std::numeric_limits<double>::quiet_NaN();  // being computed
  const auto done = [&](uint32_t robot, uint32_t pred) {
    if (finished_by(robot, pred)) return now_s_;
    if (look_[pred].cone == cone_id_) return expect(pred, s);
    return finish_estimate(robot, pred - actions_.offset[robot]);
  };
  double start = now_s_;
  if (seq > finished_[a.robot]) start = std::max(start, done(a.robot, node - 1));
  const uint32_t enters = stays_of(a.enters, enter_begin_, node);
  for (uint32_t e = 0; e < enters; ++e) {
    const uint32_t x = e == 0 ? a.enter : enter_stays_[enter_begin_[node] + e];
    // The previous stay's robot and leaving from near_, unless the swap changes it (x is i, j,
    // or the stay after j: prev_in).
    const Near near = e == 0 ? near_[node] : near_of(x);
    uint32_t robot = near.prev_robot, leave = near.prev_leave;
    if (s.swapped && (x == s.i || x == s.j || x == link_[s.j].next)) {
      const uint32_t prev = prev_in(x, s);
      robot = prev == kNoAction ? 0 : stay_[prev].robot;
      leave = prev == kNoAction ? kNoAction : stay_[prev].leave;
    }
    if (leave == kNoAction || robot == a.robot) continue;
    start = std::max(start, done(robot, leave));
  }
  return look_[node].time_s = start + durations_.mean_s(a.type);
}

// The sum over the cone's robots of the expected finish of their last action in it.
double SwitchableTracker::cone_cost(const Swap& s) {
  next_mark(order_id_, &Look::order);
  double cost = 0;
  for (const uint32_t u : cone_) {
    const Look& a = look_[u];
    const bool last = u + 1 == actions_.offset[a.robot + 1] || look_[u + 1].cone != cone_id_;
    if (last) cost += expect(u, s);
  }
  return cost;
}

// The fleet's expected time saved by j passing i (i before j now, adjacent at one location) over
// a cone of `nodes` actions; with `window`, with the best setting of the window's pairs in each
// order (SwitchOptions::window_pairs).
double SwitchableTracker::cone_saving(uint32_t i, uint32_t j, std::size_t nodes, bool window) {
  const Swap s{i, j, false};
  collect_cone(s, nodes);
  if (window && options_.window_pairs > 0) return window_saving(s);
  const double kept = cone_cost(s);
  const double swapped = cone_cost({i, j, true});
  return kept - swapped;
}

// Over the first lookahead_first_nodes of the cone, then, unless the swap loses more than one
// move's expected duration there, over the whole cone. On SMART's 1000-robot plan without
// delays, 83 % of the comparisons lost more than that over the first 16 actions, and 21 of those
// 21 694 saved more than the margin over the whole cone (docs/execution.md, "Cost").
double SwitchableTracker::lookahead_saving(uint32_t i, uint32_t j) {
  ++compared_;
  const std::size_t first = std::min(options_.lookahead_first_nodes, options_.lookahead_nodes);
  if (first < options_.lookahead_nodes) {
    const double near = cone_saving(i, j, first);
    if (near < -durations_.mean_s(grid::ActionType::kMove)) return near;
  }
  ++widened_;
  return cone_saving(i, j, options_.lookahead_nodes, true);
}

// The window of `s`'s comparison: the cone's first stays x (in the cone's order, which does not
// depend on which of s's stays is first now: the pair compared back gets the same window) whose
// entry is not sent, with a stay y of another robot after it that is entered in the cone and
// leaves again: the pair y may pass. At most one a location, none at s's: their swaps touch
// neither each other's stays nor h, i, j, k, which s's orders read (next_in, prev_in).
void SwitchableTracker::collect_window(const Swap& s) {
  window_.clear();
  const uint32_t here = location_[s.i];
  for (std::size_t q = 0; q < cone_.size() && window_.size() < options_.window_pairs; ++q) {
    const uint32_t u = cone_[q];
    const Look& l = look_[u];
    if (l.enters == 0 || l.enter == kNoAction) continue;
    const uint32_t x = l.enter, y = link_[x].next;
    if (y == kNoAction || location_[x] == here) continue;
    const Stay& b = stay_[y];
    if (b.robot == l.robot || b.enter == kNoAction || b.leave == kNoAction) continue;
    if (look_[b.enter].cone != cone_id_ || sent_by(l.robot, u)) continue;
    const bool taken = std::any_of(window_.begin(), window_.end(),
                                   [&](uint32_t w) { return location_[w] == location_[x]; });
    if (!taken) window_.push_back(x);
  }
}

// The best expected cost over every setting of the window's pairs, with s's pair kept and with
// it swapped: the saving of the swap. Each setting is made on the orders (relink), timed, and
// undone, the last made first: nothing is sent in between, and the orders come back as they were.
double SwitchableTracker::window_saving(const Swap& s) {
  collect_window(s);
  ++windowed_;
  const auto n = static_cast<uint32_t>(window_.size());
  window_settings_ += std::size_t{1} << n;
  return window_search_saving(
      n,
      [&](uint32_t setting) {
        for (uint32_t b = 0; b < n; ++b) {
          if (setting >> b & 1u) relink(window_[b]);
        }
      },
      [&](uint32_t setting) {
        for (uint32_t b = n; b-- > 0;) {
          if (setting >> b & 1u) relink(before(window_[b]).stay);
        }
      },
      [&](bool swapped) {
        return cone_cost({s.i, s.j, swapped});
      });
}

// The comparison switchable-opt decides by: the location's queue (expected_saving), or the
// lookahead when on and j is expected to wait for i there. Not when j would not wait (then j
// passing first cannot save anything: j enters no sooner, i later), nor when the queue expects
// the swap to cost the location's robots more than one move's expected duration: the robots
// after them seldom make that up. On SMART's 1000-robot plan, such pairs were 45 % of the
// comparisons, and 30 of the 1196 lookahead savings over the margin (docs/execution.md, "Cost").
double SwitchableTracker::saving(uint32_t i, uint32_t j) {
  const PassQueue q = queue_of(i, j);
  const double at_location = expected_saving(q);
  if (options_.lookahead_actions == 0 || !std::isfinite(q.j.arrive_s)) return at_location;
  if (std::isfinite(q.i.arrive_s) &&
      (std::max(q.i.arrive_s, q.free_s) + q.i.stay_s <= q.j.arrive_s ||
       at_location < -durations_.mean_s(grid::ActionType::kMove))) {
    return at_location;
  }
  return lookahead_saving(i, j);
}

}  // namespace smart::monitor
