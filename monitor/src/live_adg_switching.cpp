// LiveAdg's switching of passing orders (live_adg.hpp, "Switching"; the one-shot rule and its
// proof obligations: switchable_tracker.hpp). In half cells a robot's stay at a location begins
// with the move that enters it and ends with the robot's next move, so a Type-2 edge's location
// is the one its target enters.
#include <algorithm>
#include <cmath>

#include "smart/monitor/live_adg.hpp"

namespace smart::monitor {

std::optional<uint32_t> LiveAdg::next_move(uint32_t r, uint32_t after_seq) const {
  for (uint32_t s = after_seq + 1; s < end(r); ++s) {
    if (action(r, s).type == ActionType::kMove) return s;
  }
  return std::nullopt;
}

// A move beginning a stay that another robot follows is sent only when its robot is near: sent
// actions are never taken back, so only unsent entries can still switch.
bool LiveAdg::held(uint32_t r, uint32_t seq) const {
  if (!switching_ || robots_[r].finished + switching_->commit_actions >= seq) return false;
  return shared(r, seq);
}

// A move beginning a stay that another robot follows: it could still switch with it.
bool LiveAdg::shared(uint32_t r, uint32_t seq) const {
  if (action(r, seq).type != ActionType::kMove) return false;
  const auto leave = next_move(r, seq);
  return leave && !node(r, *leave).out.empty();
}

// switchable-opt: an unsent entry that waits for nobody and whose robot is near is due, only its
// decision pending (anticipate): first come, first served does not take it. Plain switchable
// would have sent it; taking it on a bare expected saving cost 3 points of AET in one-shot runs
// (docs/execution.md, "Two changes").
bool LiveAdg::due(NodeRef enter) const {
  return anticipating() && enter.seq == robots_[enter.robot].enqueued &&
         node(enter.robot, enter.seq).pending == 0 &&
         robots_[enter.robot].finished + switching_->commit_actions >= enter.seq;
}

// How far from its entry a robot may switch: commit_actions, or horizon_actions when
// anticipating (a robot up to that far is expected at its entry).
uint32_t LiveAdg::reach() const {
  return anticipating() ? std::max(switching_->commit_actions, switching_->horizon_actions)
                        : switching_->commit_actions;
}

// Robot r is at `location`, or goes through it before its action `seq`.
bool LiveAdg::stays_before(uint32_t r, uint32_t seq, uint32_t location) const {
  if (grid_.half_index(robots_[r].done) == location) return true;
  for (uint32_t s = robots_[r].finished; s < seq; ++s) {
    const Action& a = action(r, s);
    if (a.type == ActionType::kMove &&
        (grid_.half_index(a.from) == location || grid_.half_index(a.to) == location)) {
      return true;
    }
  }
  return false;
}

bool LiveAdg::comes_back(uint32_t r, uint32_t after_seq, uint32_t location) const {
  for (uint32_t s = after_seq + 1; s < end(r); ++s) {
    const Action& a = action(r, s);
    if (a.type == ActionType::kMove && grid_.half_index(a.to) == location) return true;
  }
  return false;
}

// `target` lost a predecessor: its robot may switch now (it waits for one robot only), or, when
// it waits for nobody but is held back (its robot is delayed), the robots behind its stay may
// pass it.
void LiveAdg::dirty_after_release(NodeRef target) {
  const Node& m = node(target.robot, target.seq);
  if (m.pending == 1) {
    if (target.seq == robots_[target.robot].enqueued) dirty_.insert(target.robot);
    return;
  }
  if (m.pending != 0 || target.seq < robots_[target.robot].enqueued) return;
  if (const auto leave = next_move(target.robot, target.seq)) {
    for (const NodeRef k : node(target.robot, *leave).out) dirty_.insert(k.robot);
  }
}

// The robots whose situation changed, in id order; a switch may let refused robots switch:
// they are tried again. Bounded.
// Then (switchable-opt) the due entries are decided; past the budget they keep their place.
void LiveAdg::try_switches(double time_s, std::vector<uint32_t>& changed) {
  std::size_t budget = 4 * robots_.size() + 16;
  while ((!dirty_.empty() || !ahead_.empty()) && budget-- > 0) {
    const bool switched = dirty_.empty() ? decide_due(pop_first(ahead_), true, time_s, changed)
                                         : try_switch(pop_first(dirty_), time_s, changed);
    if (!switched) continue;
    for (uint32_t other = 0; other < refused_.size(); ++other) {
      if (refused_[other].valid) dirty_.insert(other);
    }
  }
  dirty_.clear();
  settle_due(time_s, changed);
}

uint32_t LiveAdg::pop_first(std::set<uint32_t>& robots) {
  const uint32_t r = *robots.begin();
  robots.erase(robots.begin());
  return r;
}

bool LiveAdg::try_switch(uint32_t j, double time_s, std::vector<uint32_t>& changed) {
  const uint32_t seq = robots_[j].enqueued;
  if (seq >= end(j) || robots_[j].finished + reach() < seq) return false;
  const Node& mine = node(j, seq);
  if (mine.pending != 1 || mine.in.size() != 1 || mine.action.type != ActionType::kMove) {
    return false;
  }
  const NodeRef j_enter{j, seq}, i_leave = mine.in[0];
  const auto pair = switchable_pair(i_leave, j_enter);
  if (!pair || node(pair->i_enter.robot, pair->i_enter.seq).pending != 0) return false;
  const NodeRef i_enter = pair->i_enter, j_leave = pair->j_leave;
  const uint32_t i = i_leave.robot;
  const auto location = static_cast<uint32_t>(grid_.half_index(mine.action.to));
  if (still_refused(j, j_enter, i_leave)) return false;
  // switchable-opt: only when expected to save waiting (never back and forth with a decision
  // that saved more than margin_s the other way). The lookahead: a swap here alone whose
  // compared actions close a cycle costs for ever; a chain may not, and is compared as a whole.
  bool whole_chain = false;
  if (anticipating()) {
    const double gain = saving(*pair);
    whole_chain = compares_chains() && std::isinf(gain) && gain < 0;
    if (!(gain > 0) && !whole_chain) return false;
  }
  auto& refusal = refused_[j];
  refusal.path.clear();
  const Reach reach = reaches(i_enter, j_leave, i_leave, j_enter, refusal.path);
  if (reach == Reach::kPath && switching_->chain_locations > 1 &&
      try_chain(*pair, refusal.path, time_s, changed)) {
    refusal.valid = false;
    return true;
  }
  if (reach != Reach::kNone || whole_chain) {  // whole_chain: the cone's cycle stands
    refusal = {j_enter,
               i_leave,
               epoch_,
               truncations_,
               true,
               reach == Reach::kPath,
               std::move(refusal.path)};
    return false;
  }
  refusal.valid = false;
  switches_.push_back({time_s, location, j, i});
  swap_order(i_enter, i_leave, j_enter, j_leave);
  if (advance(j)) changed.push_back(j);
  return true;
}

// The pair of stays at j_enter's location, i (leaving by i_leave) before j, when they may
// switch: i's entry there (its move before the leave) unfinished and never sent, not due, i not
// at the location nor there before; j leaves it again and never comes back within the graph.
std::optional<LiveAdg::Pair> LiveAdg::switchable_pair(NodeRef i_leave, NodeRef j_enter) const {
  const uint32_t i = i_leave.robot, j = j_enter.robot;
  const Action& entry = action(j, j_enter.seq);
  if (entry.type != ActionType::kMove) return std::nullopt;
  const auto location = static_cast<uint32_t>(grid_.half_index(entry.to));
  uint32_t e = i_leave.seq;
  while (e > robots_[i].finished && action(i, e - 1).type != ActionType::kMove) --e;
  if (e == robots_[i].finished || e - 1 < robots_[i].enqueued) return std::nullopt;
  const NodeRef i_enter{i, e - 1};
  if (grid_.half_index(action(i, i_enter.seq).to) != location ||
      stays_before(i, i_enter.seq, location) || due(i_enter)) {
    return std::nullopt;
  }
  const auto leave = next_move(j, j_enter.seq);
  if (!leave || comes_back(j, *leave, location)) return std::nullopt;
  return Pair{i_enter, i_leave, j_enter, {j, *leave}};
}

// A visit mark of every unfinished action back to 0 (its counter wrapped).
void LiveAdg::clear_marks(uint32_t Node::*mark) {
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    for (uint32_t s = robots_[r].finished; s < end(r); ++s) node(r, s).*mark = 0;
  }
}

// A path of unfinished actions (Type-1 and Type-2 edges but skip_from -> skip_to) from `from`
// to `to`: kPath with its Type-2 edges in `path`; kBudget past the search budget (the switch is
// refused then too).
LiveAdg::Reach LiveAdg::reaches(NodeRef from, NodeRef to, NodeRef skip_from, NodeRef skip_to,
                                std::vector<std::pair<NodeRef, NodeRef>>& path) {
  if (++stamp_ == 0) {
    clear_marks(&Node::stamp);
    stamp_ = 1;
  }
  std::vector<NodeRef> stack;
  const auto push = [&](NodeRef v, NodeRef parent) {
    Node& n = node(v.robot, v.seq);
    if (n.stamp != stamp_) {
      n.stamp = stamp_;
      n.parent = parent;
      stack.push_back(v);
    }
  };
  push(from, from);
  std::size_t visited = 0;
  while (!stack.empty()) {
    const NodeRef u = stack.back();
    stack.pop_back();
    if (u == to) {
      for (NodeRef v = to; !(v == from);) {
        const NodeRef p = node(v.robot, v.seq).parent;
        if (p.robot != v.robot || p.seq + 1 != v.seq) path.emplace_back(p, v);
        v = p;
      }
      return Reach::kPath;
    }
    if (++visited > switching_->search_budget) return Reach::kBudget;
    if (u.seq + 1 < end(u.robot)) push({u.robot, u.seq + 1}, u);
    for (const NodeRef v : node(u.robot, u.seq).out) {
      if (!(u == skip_from && v == skip_to)) push(v, u);
    }
  }
  return Reach::kNone;
}

bool LiveAdg::has_edge(NodeRef from, NodeRef to) const {
  if (from.seq < robots_[from.robot].finished || from.seq >= end(from.robot)) return false;
  const auto& out = node(from.robot, from.seq).out;
  return std::find(out.begin(), out.end(), to) != out.end();
}

// The robot's last search for this move behind this leave refused it, and still would: the
// Type-2 edges of the path it found are all there (the nodes of a path from an unfinished entry
// stay unfinished, so only a switch removes them, or a truncation, after which seqs past the cut
// name other actions), or, past the budget, no switch or truncation happened since.
bool LiveAdg::still_refused(uint32_t j, NodeRef mine, NodeRef theirs) const {
  const auto& r = refused_[j];
  if (!r.valid || !(r.mine == mine) || !(r.theirs == theirs)) return false;
  if (r.truncations != truncations_) return false;
  if (!r.by_path) return r.epoch == epoch_;
  return std::all_of(r.path.begin(), r.path.end(),
                     [this](const auto& e) { return has_edge(e.first, e.second); });
}

void LiveAdg::add_edge(NodeRef from, NodeRef to) {
  if (logging_) chain_log_.push_back({true, from, to});
  node(from.robot, from.seq).out.push_back(to);
  Node& m = node(to.robot, to.seq);
  m.in.push_back(from);
  ++m.pending;
  ++type2_total_;
}

void LiveAdg::remove_edge(NodeRef from, NodeRef to) {
  if (logging_) chain_log_.push_back({false, from, to});
  erase_ref(node(from.robot, from.seq).out, to);
  Node& m = node(to.robot, to.seq);
  erase_ref(m.in, from);
  --m.pending;
  --type2_total_;
}

// i, j -> j, i at their location: j.leave -> i.enter replaces i.leave -> j.enter, whoever
// followed j follows i (robot i's own later stay needs no edge), and the leaves' pass keys are
// exchanged so the order's last occupant is still the one with the greatest key.
void LiveAdg::swap_order(NodeRef i_enter, NodeRef i_leave, NodeRef j_enter, NodeRef j_leave) {
  for (const NodeRef k : node(j_leave.robot, j_leave.seq).out) dirty_.insert(k.robot);
  exchange_edges({i_enter, i_leave, j_enter, j_leave});
  if (logging_) chain_keys_.emplace_back(i_leave, j_leave);
  std::swap(node(i_leave.robot, i_leave.seq).pass_key, node(j_leave.robot, j_leave.seq).pass_key);
  ++epoch_;
}

// swap_order's edges alone (the window search's settings, live_adg_lookahead.cpp, are made
// with this and restored from a copy: no robot marked, no epoch, no pass key).
void LiveAdg::exchange_edges(const Pair& p) {
  remove_edge(p.i_leave, p.j_enter);
  const Refs followers = node(p.j_leave.robot, p.j_leave.seq).out;
  for (const NodeRef k : followers) {
    remove_edge(p.j_leave, k);
    if (k.robot != p.i_leave.robot) add_edge(p.i_leave, k);
  }
  add_edge(p.j_leave, p.i_enter);
}

}  // namespace smart::monitor
