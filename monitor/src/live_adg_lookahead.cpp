// LiveAdg's switchable-lookahead (live_adg.hpp, "switchable-lookahead"): SwitchableTracker's
// lookahead (switchable_lookahead.cpp; as SES evaluates a setting of switchable edges, Feng et
// al., "Switchable Edge Search", ICAPS 2024, §4: the expected completion times are longest
// paths under expected durations) on the growing graph. A pair's two orders differ in the Type-2
// edges swap_order exchanges: kept, i.leave -> j.enter and j.leave -> k for the robots k after j;
// swapped, j.leave -> i.enter and i.leave -> k. Both are read off the graph as it is, not built.
#include <algorithm>
#include <cmath>
#include <limits>

#include "smart/monitor/live_adg.hpp"

namespace smart::monitor {

namespace {

bool by_robot(NodeRef a, NodeRef b) {
  return a.robot != b.robot ? a.robot < b.robot : a.seq < b.seq;
}
}  // namespace

double LiveAdg::margin() const {
  return switching_->lookahead_actions > 0 ? switching_->lookahead_margin_s : switching_->margin_s;
}

// The comparison switchable-opt decides by: the location's queue (queue_of), or the
// lookahead when on and j is expected to wait for i there; not when j would not wait (nothing to
// save: j enters no sooner, i later), nor when the queue expects the swap to cost the location's
// robots more than one move (SwitchableTracker::saving: the robots behind seldom make that up).
double LiveAdg::saving(const Pair& p) {
  const PairQueue q = queue_of(p);
  if (switching_->lookahead_actions == 0 || !std::isfinite(q.j_arrive_s)) return q.saving;
  // i's entry waits for nobody (try_switch, anticipate): the location is free, and i leaves at
  // its own pace.
  if (std::isfinite(q.i_arrive_s) &&
      (q.i_leave_s <= q.j_arrive_s || q.saving < -durations_.mean_s(ActionType::kMove))) {
    return q.saving;
  }
  return lookahead_saving(p);
}

// Over the first lookahead_first_nodes of the cone, then, unless the swap loses more than one
// move's expected duration there, over the whole cone (SwitchableTracker::lookahead_saving).
double LiveAdg::lookahead_saving(const Pair& p) {
  ++compared_;
  const SwitchOptions& o = *switching_;
  const std::size_t first = std::min(o.lookahead_first_nodes, o.lookahead_nodes);
  if (first < o.lookahead_nodes) {
    const double near = cone_saving(p, first);
    if (near < -durations_.mean_s(ActionType::kMove)) return near;
  }
  ++widened_;
  return cone_saving(p, o.lookahead_nodes, true);
}

// The fleet's expected time saved by j passing i over a cone of `nodes` actions; with `window`,
// with the best setting of the window's pairs in each order (SwitchOptions::window_pairs).
double LiveAdg::cone_saving(const Pair& p, std::size_t nodes, bool window) {
  collect_cone(p, nodes);
  if (window && switching_->window_pairs > 0 && !logging_) return window_saving(p);
  const double kept = cone_cost(p, false);
  return kept - cone_cost(p, true);
}

// The window of p's comparison (SwitchableTracker::collect_window says why each condition): in
// the cone's order, the Type-2 edges from a cone action to another robot's entry in the cone
// that may switch as try_switch's pairs may (switchable_pair: the first's entry not sent nor
// due, the second leaves and does not come back), at most one a location and none at p's. Their
// edges are all at their own locations, so a setting changes none that p's orders read.
void LiveAdg::collect_window(const Pair& p) {
  window_.clear();
  const auto location_of = [this](const Pair& q) {
    return grid_.half_index(action(q.j_enter.robot, q.j_enter.seq).to);
  };
  const auto here = location_of(p);
  for (std::size_t c = 0; c < cone_.size() && window_.size() < switching_->window_pairs; ++c) {
    const NodeRef v = cone_[c];
    for (const NodeRef w : node(v.robot, v.seq).out) {
      if (window_.size() >= switching_->window_pairs) break;
      if (w.robot == v.robot || node(w.robot, w.seq).cone != cone_id_) continue;
      const auto q = switchable_pair(v, w);
      if (!q) continue;
      const auto there = location_of(*q);
      if (there == here || std::any_of(window_.begin(), window_.end(),
                                       [&](const Pair& o) { return location_of(o) == there; })) {
        continue;
      }
      window_.push_back(*q);
    }
  }
}

// The best expected cost over every setting of the window's pairs, with p kept and with p
// swapped: the saving of the swap. Each setting's edges are exchanged, timed, and the nodes they
// touched restored from a copy (their edge lists in their order, their pending counts).
double LiveAdg::window_saving(const Pair& p) {
  collect_window(p);
  ++windowed_;
  saved_.clear();
  const auto save = [this](NodeRef r) {
    const Node& n = node(r.robot, r.seq);
    saved_.push_back({r, n.in, n.out, n.pending});
  };
  for (const Pair& q : window_) {
    for (const NodeRef r : {q.i_enter, q.i_leave, q.j_enter, q.j_leave}) save(r);
    for (const NodeRef k : node(q.j_leave.robot, q.j_leave.seq).out) save(k);
  }
  const std::size_t type2 = type2_total_;
  const auto n = static_cast<uint32_t>(window_.size());
  window_settings_ += std::size_t{1} << n;
  return window_search_saving(
      n,
      [&](uint32_t setting) {
        for (uint32_t b = 0; b < n; ++b) {
          if (setting >> b & 1u) exchange_edges(window_[b]);
        }
      },
      [&](uint32_t setting) {
        if (setting == 0) return;
        for (const SavedEdges& s : saved_) {  // a node copied twice was copied twice the same
          Node& m = node(s.ref.robot, s.ref.seq);
          m.in = s.in;
          m.out = s.out;
          m.pending = s.pending;
        }
        type2_total_ = type2;
      },
      [&](bool swapped) { return cone_cost(p, swapped); });
}

// The successors of u in the pair's kept or swapped order.
void LiveAdg::successors(const Pair& p, NodeRef u, bool swapped, std::vector<NodeRef>& out) const {
  const Refs& own = node(u.robot, u.seq).out;
  if (!swapped || !(u == p.i_leave || u == p.j_leave)) {
    out.insert(out.end(), own.begin(), own.end());
  } else if (u == p.j_leave) {
    out.push_back(p.i_enter);
  } else {
    for (const NodeRef v : own) {
      if (!(v == p.j_enter)) out.push_back(v);
    }
    for (const NodeRef k : node(p.j_leave.robot, p.j_leave.seq).out) {
      if (k.robot != p.i_enter.robot) out.push_back(k);  // i's own later stay needs no edge
    }
  }
}

// The unfinished actions after i's and j's entries in either order, within lookahead_actions of
// their robots' progress, breadth first up to `nodes`: the same set for both orders. Rooted and
// walked in an order that does not depend on which robot is first now (the lower robot id's
// entry first; at the pair's leaves, both orders' successors sorted), so that the pair compared
// again right after a swap gets the same cone, and the opposite answer (a cone that depended on
// it swapped pairs back and forth in one-shot runs, docs/execution.md "switchable-lookahead").
// With `extend`, the walk's actions are added to the cone already collected (a chain's two
// orders, each walked in its own graph: chain_saves), each walk cut at `nodes` on its own.
void LiveAdg::collect_cone(const Pair& p, std::size_t nodes, bool extend) {
  if (!extend) {
    if (++cone_id_ == 0) {
      clear_marks(&Node::cone);
      cone_id_ = 1;
    }
    cone_.clear();
  }
  // This walk's visit mark is `order` (free until cone_cost times the cone, with a new id).
  if (++order_id_ == 0) {
    clear_marks(&Node::order);
    order_id_ = 1;
  }
  walk_.clear();
  const auto add = [&](NodeRef v) {
    const Robot& rb = robots_[v.robot];
    if (v.seq < rb.finished || v.seq >= end(v.robot) ||
        v.seq > rb.finished + switching_->lookahead_actions) {
      return;
    }
    Node& n = node(v.robot, v.seq);
    if (n.order == order_id_ || walk_.size() >= nodes) return;
    n.order = order_id_;
    walk_.push_back(v);
    if (n.cone != cone_id_) {
      n.cone = cone_id_;
      cone_.push_back(v);
    }
  };
  const bool i_low = p.i_enter.robot < p.j_enter.robot;
  add(i_low ? p.i_enter : p.j_enter);
  add(i_low ? p.j_enter : p.i_enter);
  // By index: add() grows walk_ while it is walked. Until the walk is full.
  for (std::size_t q = 0; q < walk_.size() && walk_.size() < nodes; ++q) {
    const NodeRef u = walk_[q];
    add({u.robot, u.seq + 1});
    next_.clear();
    successors(p, u, false, next_);
    if (u == p.i_leave || u == p.j_leave) {
      successors(p, u, true, next_);
      std::sort(next_.begin(), next_.end(), by_robot);
    }
    for (const NodeRef v : next_) add(v);
  }
}

// The expected finish of action v in the pair's kept or swapped order: its robot's previous
// action and its Type-2 predecessors finished (expected, or now), plus its kind's mean duration.
// Outside the cone, a predecessor's time is its robot's own queue (waits not foreseen), the same
// in both orders. Infinite on a cycle (the swap would deadlock).
double LiveAdg::expect(NodeRef v, const Pair& p, bool swapped) {
  Node& n = node(v.robot, v.seq);
  if (n.order == order_id_) {
    // On the path being computed: a cycle.
    if (std::isnan(n.look_s)) return std::numeric_limits<double>::infinity();
    return n.look_s;
  }
  n.order = order_id_;
  const Robot& rb = robots_[v.robot];
  if (v.seq == rb.finished && v.seq < rb.enqueued) {
    return n.look_s = finish_estimate(v.robot, v.seq);  // sent: under way
  }
  n.look_s = std::numeric_limits<double>::quiet_NaN();  // being computed
  double start = now_s_;
  const auto wait_for = [&](NodeRef u) {
    if (u.robot == v.robot && u.seq + 1 != v.seq) return;  // its own earlier stay: Type-1
    if (u.seq < robots_[u.robot].finished) return;
    const bool inside = node(u.robot, u.seq).cone == cone_id_;
    start = std::max(start, inside ? expect(u, p, swapped) : finish_estimate(u.robot, u.seq));
  };
  if (v.seq > rb.finished) wait_for({v.robot, v.seq - 1});
  for (const NodeRef u : n.in) {
    if (!swapped || !(u == p.j_leave || (u == p.i_leave && v == p.j_enter))) {
      wait_for(u);
    } else if (u == p.j_leave && v.robot != p.i_leave.robot) {
      wait_for(p.i_leave);  // k now follows i (and j's entry no longer waits for i)
    }
  }
  if (swapped && v == p.i_enter) wait_for(p.j_leave);
  return n.look_s = start + durations_.mean_s(n.action.type);
}

// The sum over the cone's robots of the expected finish of their last action in it.
double LiveAdg::cone_cost(const Pair& p, bool swapped) {
  if (++order_id_ == 0) {
    clear_marks(&Node::order);
    order_id_ = 1;
  }
  double cost = 0;
  for (const NodeRef v : cone_) {
    const bool last = v.seq + 1 == end(v.robot) || node(v.robot, v.seq + 1).cone != cone_id_;
    if (last) cost += expect(v, p, swapped);
  }
  return cost;
}

}  // namespace smart::monitor
