// SwitchableTracker's topological order of the actions (switchable_tracker.hpp): the deadlock
// search looks for a path of unfinished actions from i.enter to j.leave, and every action on such
// a path comes after i.enter in any topological order of the graph. So the search (backwards
// from j.leave) need not walk the actions ordered before i.enter: on LaCAM's 1000-robot plan of
// random-64-64-10 under delays, most of its visits were searches that walked 4096 actions (its
// budget) behind a robot far from the location, and gave up (docs/execution.md, "Cost").
//
// The order is Kahn's at the start (the plan's orders, or a resumed run's), and kept up by Pearce
// and Kelly's algorithm ("A dynamic topological sort algorithm for directed acyclic graphs",
// ACM Journal of Experimental Algorithmics 11, 2006, section 2): a new edge x -> y with y ordered
// before x reorders only the actions reachable from y ordered before x and those reaching x
// ordered after y, within their own places. A swap h, i, j, k -> h, j, i, k adds one such edge
// (j.leave -> i.enter; h -> j and i -> k follow the order already); a chain one per location.
// Finished actions are left out: the search never walks them, and nothing unfinished waits for
// them any more.
#include <algorithm>

#include "smart/monitor/switchable_tracker.hpp"

namespace smart::monitor {

// Kahn's algorithm over Type-1 and the current Type-2 edges, first in first out from the robots'
// first actions: deterministic. A cycle (orders that cannot be executed) gives the order up.
void SwitchableTracker::init_order() {
  const auto nodes = static_cast<uint32_t>(actions_.actions.size());
  std::vector<uint32_t> in(nodes, 0), queue;
  queue.reserve(nodes);
  for (uint32_t n = 0; n < nodes; ++n) {
    in[n] = (n > actions_.offset[mark_[n].robot] ? 1 : 0);
    each_edge_in(n, [&](uint32_t) { ++in[n]; });
    if (in[n] == 0) queue.push_back(n);
  }
  const auto visit = [&](uint32_t v) {
    if (--in[v] == 0) queue.push_back(v);
  };
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const uint32_t u = queue[head];
    mark_[u].ord = static_cast<uint32_t>(head);
    const uint32_t robot = mark_[u].robot;
    if (u + 1 < actions_.offset[robot] + actions_.count(robot)) visit(u + 1);
    each_edge_out(u, visit);
  }
  ordered_ = queue.size() == nodes;
}

// The stays of a swap, or of a chain's swaps, just made (each now after the stay it was passed
// by): their new edges are ordered one at a time, the others left out of each reordering's walk
// until their turn (so each walk sees a graph the order holds on, a part of the acyclic one).
void SwitchableTracker::order_swapped(const std::vector<uint32_t>& stays) {
  if (!ordered_) return;
  unordered_.clear();
  const auto add = [&](uint32_t u, uint32_t v) {  // stays u before v
    if (u == kNoAction || v == kNoAction || stay_[u].robot == stay_[v].robot) return;
    const uint32_t from = stay_[u].leave, to = stay_[v].enter;
    if (from == kNoAction || to == kNoAction || finished_by(stay_[u].robot, from) ||
        finished_by(stay_[v].robot, to)) {
      return;
    }
    unordered_.emplace_back(from, to);
  };
  for (const uint32_t i : stays) {
    const uint32_t j = before(i).stay;
    add(before(j).stay, j);
    add(j, i);
    add(i, after(i).stay);
  }
  while (!unordered_.empty() && ordered_) {
    const auto [from, to] = unordered_.back();
    unordered_.pop_back();
    ordered_ = order_edge(from, to);
  }
  unordered_.clear();
}

bool SwitchableTracker::unordered(uint32_t from, uint32_t to) const {
  return std::find(unordered_.begin(), unordered_.end(), std::pair{from, to}) != unordered_.end();
}

// The edge from -> to is in the graph: reorders when `to` came first (Pearce and Kelly). False
// when the edge closes a cycle (the deadlock search said it did not: a broken invariant).
bool SwitchableTracker::order_edge(uint32_t from, uint32_t to) {
  const uint32_t lower = mark_[to].ord, upper = mark_[from].ord;
  if (upper < lower) return true;
  next_stamp();
  forward_.clear();
  backward_.clear();
  if (!order_walk(to, upper, true, from, forward_)) return false;
  order_walk(from, lower, false, kNoAction, backward_);
  const auto by_ord = [this](uint32_t a, uint32_t b) { return mark_[a].ord < mark_[b].ord; };
  std::sort(forward_.begin(), forward_.end(), by_ord);
  std::sort(backward_.begin(), backward_.end(), by_ord);
  pool_.clear();
  for (const uint32_t n : backward_) pool_.push_back(mark_[n].ord);
  for (const uint32_t n : forward_) pool_.push_back(mark_[n].ord);
  std::sort(pool_.begin(), pool_.end());
  std::size_t k = 0;
  for (const uint32_t n : backward_) mark_[n].ord = pool_[k++];
  for (const uint32_t n : forward_) mark_[n].ord = pool_[k++];
  return true;
}

// Depth first from `start` over unfinished actions ordered before `bound` (forward: successors)
// or after it (backwards: predecessors), the edges not ordered yet left out; the actions met in
// `out`. False when the walk meets `stop` (a cycle).
bool SwitchableTracker::order_walk(uint32_t start, uint32_t bound, bool forward, uint32_t stop,
                                   std::vector<uint32_t>& out) {
  stack_.assign(1, start);
  mark_[start].seen = stamp_;
  bool cycle = false;
  const auto push = [&](uint32_t v) {
    Mark& m = mark_[v];
    cycle |= v == stop;
    if (m.seen == stamp_ || finished_by(m.robot, v) || !(forward ? m.ord < bound : m.ord > bound)) {
      return;
    }
    m.seen = stamp_;
    stack_.push_back(v);
  };
  while (!stack_.empty() && !cycle) {
    const uint32_t u = stack_.back();
    stack_.pop_back();
    out.push_back(u);
    const uint32_t robot = mark_[u].robot, first = actions_.offset[robot];
    if (forward) {
      if (u + 1 < first + actions_.count(robot)) push(u + 1);
      each_edge_out(u, [&](uint32_t v) {
        if (!unordered(u, v)) push(v);
      });
    } else {
      if (u > first) push(u - 1);
      each_edge_in(u, [&](uint32_t v) {
        if (!unordered(v, u)) push(v);
      });
    }
  }
  return !cycle;
}

// Every edge between unfinished actions goes up the order.
bool SwitchableTracker::order_holds() const {
  if (!ordered_) return false;
  for (uint32_t u = 0; u < mark_.size(); ++u) {
    const uint32_t robot = mark_[u].robot;
    if (finished_by(robot, u)) continue;
    if (u + 1 < actions_.offset[robot] + actions_.count(robot) &&
        mark_[u + 1].ord <= mark_[u].ord) {
      return false;
    }
    bool up = true;
    each_edge_out(u, [&](uint32_t v) { up = up && mark_[v].ord > mark_[u].ord; });
    if (!up) return false;
  }
  return true;
}

}  // namespace smart::monitor
