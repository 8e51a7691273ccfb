#include "smart/monitor/switchable_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "smart/grid/grid.hpp"

namespace smart::monitor {

namespace {

// Node -> the stays whose `enter` (or `leave`) it is, as compressed sparse rows.
void index_stays(const std::vector<Stay>& stays, std::size_t nodes, bool enter,
                 std::vector<uint32_t>& begin, std::vector<uint32_t>& list) {
  begin.assign(nodes + 1, 0);
  for (const auto& s : stays) {
    const uint32_t node = enter ? s.enter : s.leave;
    if (node != kNoAction) ++begin[node + 1];
  }
  for (std::size_t i = 0; i < nodes; ++i) begin[i + 1] += begin[i];
  list.resize(begin[nodes]);
  std::vector<uint32_t> fill(begin.begin(), begin.end() - 1);
  for (uint32_t id = 0; id < stays.size(); ++id) {
    const uint32_t node = enter ? stays[id].enter : stays[id].leave;
    if (node != kNoAction) list[fill[node]++] = id;
  }
}

}  // namespace

SwitchableTracker::SwitchableTracker(const ActionPlan& actions, PassingOrders orders,
                                     SwitchOptions options, bool paused)
    : actions_(actions),
      orders_(std::move(orders)),
      options_(options),
      paused_(paused),
      pending_(actions.actions.size(), 0),
      finished_(actions.robots(), 0),
      enqueued_(actions.robots(), 0),
      dirty_(actions.robots()),
      declined_node_(options.anticipate ? actions.robots() : 0, kNoAction),
      declines_(options.anticipate ? actions.robots() : 0, 0),
      mark_(actions.actions.size()),
      parent_(actions.actions.size(), 0),
      refused_(actions.robots()),
      with_refusal_(actions.robots()),
      unsettled_(actions.robots()),
      started_s_(options.anticipate ? actions.robots() : 0, 0.0),
      decided_(options.anticipate ? actions.actions.size() : 0, 0),
      ahead_(actions.robots()) {
  stay_ = std::move(orders_.stays);  // orders_ keeps each location's range of stay ids
  const auto count = static_cast<uint32_t>(stay_.size());
  location_.resize(count);
  link_.resize(count);
  epoch_.assign(orders_.begin.empty() ? 0 : orders_.begin.size() - 1, 0);
  wait_look_.resize(actions.robots());
  const std::size_t nodes = actions.actions.size();
  index_stays(stay_, nodes, true, enter_begin_, enter_stays_);  // before the links: link_prev()
  index_stays(stay_, nodes, false, leave_begin_, leave_stays_);
  near_.resize(nodes);
  for (uint32_t loc = 0; loc + 1 < orders_.begin.size(); ++loc) {
    const uint32_t first = orders_.begin[loc], end = orders_.begin[loc + 1];
    for (uint32_t p = first; p < end; ++p) {
      location_[p] = loc;
      link_prev(p, p == first ? kNoAction : p - 1);
      link_next(p, p + 1 == end ? kNoAction : p + 1);
    }
  }
  for (std::size_t n = 0; n < nodes; ++n) mark_[n].robot = actions.actions[n].robot;
  turn_bits_.assign(nodes / 64 + 1, 0);
  for (std::size_t n = 0; n < nodes; ++n) {
    if (actions.actions[n].type == grid::ActionType::kRotate)
      turn_bits_[n / 64] |= 1ULL << (n % 64);
  }
  if (options_.anticipate) {
    moves_before_.assign(nodes + 1, 0);
    for (std::size_t n = 0; n < nodes; ++n) {
      moves_before_[n + 1] =
          moves_before_[n] + (actions.actions[n].type == grid::ActionType::kMove);
    }
  }
  for (uint32_t s = 0; s < count; ++s) {
    const auto b = before(s);
    if (b.edge && stay_[b.stay].leave != kNoAction && stay_[s].enter != kNoAction) {
      ++pending_[stay_[s].enter];
    }
  }
  init_order();
  turning_.resize(actions.robots());
  for (uint32_t r = 0; r < actions.robots(); ++r) turning_[r] = turn_at(r, 0);
  for (uint32_t r = 0; r < actions.robots(); ++r) advance(r);
  // First come, first served from the robots' first reports on: at the start nobody is late,
  // and the entries about to be sent are decided by anticipation (ahead_) alone.
  dirty_.clear();
  std::vector<uint32_t> changed;  // before the first windows: all are sent then
  try_switches(0.0, changed);
}

// The robots that may switch now are tried at the next progress.
void SwitchableTracker::unpause() {
  if (!paused_) return;
  paused_ = false;
  for (uint32_t r = 0; r < finished_.size(); ++r) {
    if (candidate(r)) dirty_.set(r);
  }
}

SwitchableTracker::Neighbour SwitchableTracker::before(uint32_t stay) const {
  const uint32_t other = link_[stay].prev;
  if (other == kNoAction) return {};
  return {other, stay_[other].robot != stay_[stay].robot};
}

SwitchableTracker::Neighbour SwitchableTracker::after(uint32_t stay) const {
  const uint32_t other = link_[stay].next;
  if (other == kNoAction) return {};
  return {other, stay_[other].robot != stay_[stay].robot};
}

// near_ holds a node's first entered and left stays' neighbours: updated when `stay` is one.
static_assert(grid::kMaxRobots < (int64_t{1} << 31),
              "Near::next_robot holds a robot id in 31 bits");
void SwitchableTracker::link_prev(uint32_t stay, uint32_t prev) {
  link_[stay].prev = prev;
  ++epoch_[location_[stay]];
  const uint32_t node = stay_[stay].enter;
  if (node == kNoAction || enter_stays_[enter_begin_[node]] != stay) return;
  near_[node].prev_robot = prev == kNoAction ? 0 : stay_[prev].robot;
  near_[node].prev_leave = prev == kNoAction ? kNoAction : stay_[prev].leave;
}

void SwitchableTracker::link_next(uint32_t stay, uint32_t next) {
  link_[stay].next = next;
  ++epoch_[location_[stay]];
  if (const uint32_t enter = stay_[stay].enter;
      enter != kNoAction && enter_stays_[enter_begin_[enter]] == stay) {
    near_[enter].shared_next = shares_next(stay);
  }
  const uint32_t node = stay_[stay].leave;
  if (node == kNoAction || leave_stays_[leave_begin_[node]] != stay) return;
  near_[node].next_robot = next == kNoAction ? 0 : stay_[next].robot;
  near_[node].next_enter = next == kNoAction ? kNoAction : stay_[next].enter;
}

// The stay after `stay` is another robot's, which leaves the location again: the entry of
// `stay` could still switch with it.
bool SwitchableTracker::shares_next(uint32_t stay) const {
  const auto next = after(stay);
  return next.edge && stay_[next.stay].leave != kNoAction;
}

// What near_ keeps, for any stay.
SwitchableTracker::Near SwitchableTracker::near_of(uint32_t stay) const {
  Near n;
  if (const uint32_t next = link_[stay].next; next != kNoAction) {
    n.next_robot = stay_[next].robot;
    n.next_enter = stay_[next].enter;
  }
  if (const uint32_t prev = link_[stay].prev; prev != kNoAction) {
    n.prev_robot = stay_[prev].robot;
    n.prev_leave = stay_[prev].leave;
  }
  return n;
}

bool SwitchableTracker::neighbours_hold() const {
  for (uint32_t node = 0; node < near_.size(); ++node) {
    const Near& n = near_[node];
    if (enter_begin_[node] < enter_begin_[node + 1]) {
      const Near want = near_of(enter_stays_[enter_begin_[node]]);
      if (n.prev_robot != want.prev_robot || n.prev_leave != want.prev_leave ||
          n.shared_next != shares_next(enter_stays_[enter_begin_[node]])) {
        return false;
      }
    }
    if (leave_begin_[node] < leave_begin_[node + 1]) {
      const Near want = near_of(leave_stays_[leave_begin_[node]]);
      if (n.next_robot != want.next_robot || n.next_enter != want.next_enter) return false;
    }
  }
  return true;
}

// Whether `robot`'s action `node` has finished (its robot known: no lookup of the action).
bool SwitchableTracker::finished_by(uint32_t robot, uint32_t node) const {
  return node < actions_.offset[robot] + finished_[robot];
}

bool SwitchableTracker::sent_by(uint32_t robot, uint32_t node) const {
  return node < actions_.offset[robot] + enqueued_[robot];
}

// Sent, or due to be sent now (switchable-opt: its robot within commit_actions, nothing to wait
// for, only anticipation's decision pending). First come, first served does not take a due
// entry: the plain tracker would have sent it, and whether a robot still on its way passes it
// is anticipation's to decide, by margin_s. When it took them on a bare expected saving,
// switchable-opt's first come, first served alone (no anticipation) made AET 1.5 % longer than
// plain ADG at 800-1000 robots on random-64-64-10 without delays; now 1.5 % shorter
// (docs/execution.md, "switchable-opt").
bool SwitchableTracker::committed(uint32_t robot, uint32_t node) const {
  if (sent_by(robot, node)) return true;
  const uint32_t seq = node - actions_.offset[robot];  // its place, without reading the action
  return options_.anticipate && seq == enqueued_[robot] && pending_[node] == 0 &&
         finished_[robot] + options_.commit_actions >= seq;
}

// An entry that another robot's stay follows (it could still switch with it) waits to be sent
// until its robot is near (commit_actions): sent actions are never taken back.
// The first entered stay's answer from near_ (four dependent misses each time a robot's next
// action was sent; docs/execution.md, "A chain's cone walked when it is compared").
bool SwitchableTracker::needs_commit(uint32_t node) const {
  const uint32_t begin = enter_begin_[node], end = enter_begin_[node + 1];
  if (begin == end) return false;
  if (near_[node].shared_next) return true;
  for (uint32_t i = begin + 1; i < end; ++i) {
    if (shares_next(enter_stays_[i])) return true;
  }
  return false;
}

bool SwitchableTracker::advance(uint32_t robot) {
  const uint32_t base = actions_.offset[robot], count = actions_.count(robot);
  const uint32_t before_count = enqueued_[robot];
  while (enqueued_[robot] < count) {
    const uint32_t seq = enqueued_[robot], node = base + seq;
    if (pending_[node] > 0) break;
    const bool shared = needs_commit(node);
    if (shared && finished_[robot] + options_.commit_actions < seq) break;
    if (shared && options_.anticipate && !decided_[node]) {
      ahead_.set(robot);  // its place is decided before it is sent (try_switches)
      break;
    }
    if (options_.anticipate && seq == finished_[robot]) started_s_[robot] = now_s_;
    ++enqueued_[robot];
  }
  if (enqueued_[robot] == before_count) return false;
  // Its refusal named an entry sent now: gone. Its next entry may switch (the events that make
  // a robot a candidate: it came near, its entry came next, a count dropped to one, the
  // location emptied, a switch; each tries it).
  with_refusal_.reset(robot);
  unsettled_.reset(robot);
  if (candidate(robot)) dirty_.set(robot);
  return true;
}

// A robot near its next unsent action that waits for exactly one other robot's leave: one that
// might switch.
bool SwitchableTracker::candidate(uint32_t robot) const {
  const uint32_t seq = enqueued_[robot];
  if (seq >= actions_.count(robot) || finished_[robot] + reach() < seq) return false;
  return pending_[actions_.offset[robot] + seq] == 1;
}

void SwitchableTracker::consider(uint32_t stay) {
  const Stay& x = stay_[stay];
  if (x.enter == actions_.offset[x.robot] + enqueued_[x.robot] && candidate(x.robot)) {
    dirty_.set(x.robot);
  }
}

// `node` finished: the entries that waited for it lose a pending predecessor.
void SwitchableTracker::release(uint32_t node, std::vector<uint32_t>& changed) {
  for (uint32_t i = leave_begin_[node]; i < leave_begin_[node + 1]; ++i) {
    const auto next = after(leave_stays_[i]);
    if (!next.edge || stay_[next.stay].enter == kNoAction) continue;
    const uint32_t target = stay_[next.stay].enter;
    if (--pending_[target] == 0) {
      const uint32_t other = stay_[next.stay].robot;
      if (advance(other)) changed.push_back(other);
    } else if (pending_[target] == 1) {
      consider(next.stay);
    }
  }
  // The location `node` left may be free now for the stay after next to pass the next one.
  for (uint32_t i = leave_begin_[node]; i < leave_begin_[node + 1]; ++i) {
    const auto next = after(leave_stays_[i]);
    if (next.stay == kNoAction) continue;
    const auto later = after(next.stay);
    if (later.stay != kNoAction && stay_[later.stay].enter != kNoAction) consider(later.stay);
  }
}

ProgressUpdate SwitchableTracker::on_progress(uint32_t robot, int64_t finished_seq, double time_s) {
  ProgressUpdate u = check_progress(*this, robot, finished_seq);
  if (u.result != ProgressResult::kAdvanced) return u;
  u.robots_changed.push_back(robot);
  const uint32_t base = actions_.offset[robot];
  const auto upto = static_cast<uint32_t>(finished_seq + 1);
  const uint32_t from = finished_[robot];
  now_s_ = std::max(now_s_, time_s);
  if (options_.anticipate) observe(robot, from, upto, time_s);
  finished_total_ += upto - from;
  finished_[robot] = upto;  // first: release() reads finished_by()
  turning_[robot] = turn_at(robot, upto);
  for (uint32_t s = from; s < upto; ++s) release(base + s, u.robots_changed);
  advance(robot);
  if (candidate(robot)) dirty_.set(robot);
  retry_declined(time_s);
  try_switches(time_s, u.robots_changed);
  std::sort(u.robots_changed.begin(), u.robots_changed.end());
  u.robots_changed.erase(std::unique(u.robots_changed.begin(), u.robots_changed.end()),
                         u.robots_changed.end());
  return u;
}

// Tries the robots whose situation changed (dirty_), in id order: the only ones that could
// switch now. A switch may let refused robots switch: they are tried again. Bounded.
// Then the entries about to be sent get their place decided (anticipation): past the budget,
// they keep their place. Every robot in ahead_ is decided before this returns, so no entry
// waits for a decision between progress reports.
void SwitchableTracker::try_switches(double time_s, std::vector<uint32_t>& changed) {
  std::size_t budget = paused_ ? 0 : 4 * finished_.size() + 16;
  while ((dirty_.any() || ahead_.any()) && budget-- > 0) {
    if (dirty_.none()) {
      const uint32_t r = ahead_.take_first();
      if (!anticipate(r, time_s, changed)) {
        decide(r, changed);
        continue;
      }
    } else {
      const uint32_t r = dirty_.take_first();
      if (!candidate(r) || !try_switch(r, time_s, changed)) continue;
    }
    dirty_ |= unsettled_;  // a switch may have opened their way
  }
  dirty_.clear();
  while (ahead_.any()) decide(ahead_.take_first(), changed);
}

// The comparison expected `robot` passing at `node` to lose -gain seconds (or save nothing):
// tried again once that much time has passed, at least kRetryS doubled for each time this entry
// was declined before (asked every 2 s, the retries took 1.3-1.9 points more of the monitor's
// CPU on SMART's plan). Not when it cannot be worth it (a cycle in the compared actions).
void SwitchableTracker::decline(uint32_t robot, uint32_t node, double gain) {
  if (!std::isfinite(gain)) return;
  uint8_t& n = declines_[robot];
  n = declined_node_[robot] == node ? static_cast<uint8_t>(std::min(n + 1, 16)) : 0;
  declined_node_[robot] = node;
  retries_.push({now_s_ + std::max(-gain, std::ldexp(kRetryS, n)), robot, node});
}

// The declined robots whose time came, still waiting at the same entry: tried with the others.
// On LaCAM's dense 1000-robot plan under delays, seeds 0-9, the lookahead waited 0.35 ± 0.33 %
// less so (0.66 ± 0.42 % retried every 2 s, at its CPU cost); trying only those whose robot to
// pass had finished nothing since saved less (docs/execution.md, "Declined switches tried
// again").
void SwitchableTracker::retry_declined(double time_s) {
  while (!retries_.empty() && retries_.top().at_s <= time_s) {
    const Retry r = retries_.top();
    retries_.pop();
    if (actions_.offset[r.robot] + enqueued_[r.robot] == r.node && candidate(r.robot)) {
      dirty_.set(r.robot);
    }
  }
}

// The one stay `node` (of `robot`) enters whose predecessor (another robot) has not left yet,
// when that is all `node` waits for; kNoAction otherwise. The neighbours from near_ (one cache
// line per node; the stay's list entry, its link and the predecessor's stay were a chain of four
// dependent misses; docs/execution.md, "A robot's next actions read together"); the stay's id
// only when it is the one.
uint32_t SwitchableTracker::blocking_stay(uint32_t robot, uint32_t node) const {
  if (pending_[node] != 1) return kNoAction;
  const uint32_t begin = enter_begin_[node], end = enter_begin_[node + 1];
  for (uint32_t i = begin; i < end; ++i) {
    const Near n = i == begin ? near_[node] : near_of(enter_stays_[i]);
    if (n.prev_leave != kNoAction && n.prev_robot != robot &&
        !finished_by(n.prev_robot, n.prev_leave)) {
      return enter_stays_[i];
    }
  }
  return kNoAction;
}

bool SwitchableTracker::try_switch(uint32_t robot, double time_s, std::vector<uint32_t>& changed) {
  const uint32_t seq = enqueued_[robot], node = actions_.offset[robot] + seq;
  if (finished_[robot] + reach() < seq) return false;  // not near yet
  const uint32_t mine = blocking_stay(robot, node);
  if (mine == kNoAction || stay_[mine].leave == kNoAction) return false;
  const uint32_t theirs = before(mine).stay;
  const Stay& first = stay_[theirs];
  if (first.enter == kNoAction || committed(first.robot, first.enter)) return false;
  const auto h = before(theirs);
  if (h.stay != kNoAction && (stay_[h.stay].leave == kNoAction ||
                              !finished_by(stay_[h.stay].robot, stay_[h.stay].leave))) {
    return false;  // not free: j would still wait for h (safe, but no gain now)
  }
  if (still_refused(robot, node, theirs)) return false;
  // switchable-opt: only when expected to save waiting (never back and forth with an
  // anticipated switch, which saved more than margin_s the other way: without this check,
  // thousands of switches a run). Passing a robot further back in the queue, before the
  // location is free, was tried and dropped: under 1 % less waiting at 200 robots, 2-3 % more
  // at 750 (docs/execution.md).
  // The lookahead: a swap at this location alone whose compared actions close a cycle costs for
  // ever; passing at each location where `theirs` goes on ahead (a chain) may not, and the chain
  // is compared as a whole (try_chain).
  bool whole_chain = false;
  if (options_.anticipate) {
    const double gain = saving(theirs, mine);
    whole_chain = compares_chains() && std::isinf(gain) && gain < 0;
    if (!(gain > 0) && !whole_chain) {
      decline(robot, node, gain);
      return false;
    }
  }
  // Would deadlock: remembered with the path that shows it (valid while its Type-2 edges are:
  // nodes downstream of an unfinished entry stay unfinished), or, past the search budget, until
  // the next switch.
  auto& refusal = refused_[robot];
  refusal = {node, theirs, static_cast<uint32_t>(switches_.size()), refusals_++, {}, false};
  switch (reaches(first.enter, stay_[mine].leave, first.leave, node, refusal.path)) {
    case Reach::kPath:
      if (options_.chain_locations > 1 && try_chain(theirs, refusal.path, time_s, changed)) {
        forget_refusal(robot);
        return true;
      }
      refuse(robot, true);
      return false;
    case Reach::kBudget:
      refuse(robot, false);
      return false;
    case Reach::kNone:
      if (whole_chain) {  // no cycle found within the budget: the cone's cycle stands
        refuse(robot, false);
        return false;
      }
      break;
  }
  forget_refusal(robot);
  switches_.push_back(
      {time_s, location_[mine], robot, first.robot, false, stay_[mine].enter, first.enter});
  swap_with_next(theirs, changed);
  return true;
}

bool SwitchableTracker::has_edge(uint32_t from, uint32_t to) const {
  for (uint32_t i = leave_begin_[from]; i < leave_begin_[from + 1]; ++i) {
    const auto next = after(leave_stays_[i]);
    if (next.edge && stay_[next.stay].enter == to) return true;
  }
  return false;
}

// The last search for this robot's entry behind the same stay refused it, and still would.
bool SwitchableTracker::still_refused(uint32_t robot, uint32_t node, uint32_t theirs) const {
  const auto& r = refused_[robot];
  if (r.node != node || r.theirs != theirs) return false;
  if (!r.by_path) return r.epoch == switches_.size();
  return path_holds(robot);
}

bool SwitchableTracker::path_holds(uint32_t robot) const {
  const auto& path = refused_[robot].path;
  return std::all_of(path.begin(), path.end(),
                     [this](const auto& e) { return has_edge(e.first, e.second); });
}

// `robot`'s switch was refused (refused_ filled in): by a path, it waits for one of the path's
// edges to be switched away (watched at each edge's leave); past the budget, for any switch.
void SwitchableTracker::refuse(uint32_t robot, bool by_path) {
  auto& refusal = refused_[robot];
  refusal.by_path = by_path;
  with_refusal_.set(robot);
  if (!by_path) {
    unsettled_.set(robot);
    return;
  }
  unsettled_.reset(robot);
  for (const auto& e : refusal.path) watchers_[e.first].push_back({robot, refusal.id});
}

// `robot` switched: no refusal of it stands.
void SwitchableTracker::forget_refusal(uint32_t robot) {
  refused_[robot].node = kNoAction;
  with_refusal_.reset(robot);
  unsettled_.reset(robot);
}

// The stay's place changed (a switch): its robot's refusal may name another stay to pass now.
void SwitchableTracker::unsettle(uint32_t stay) {
  const uint32_t robot = stay_[stay].robot;
  if (with_refusal_.test(robot)) unsettled_.set(robot);
}

// A switch removed the Type-2 edge from `node` (a leave): the refusals whose path had it and
// lost an edge are tried again; the others keep watching.
void SwitchableTracker::unsettle_watchers(uint32_t node) {
  const auto it = watchers_.find(node);
  if (it == watchers_.end()) return;
  std::erase_if(it->second, [this](const Watcher& w) {
    const auto& refusal = refused_[w.robot];
    if (refusal.id != w.refusal || !with_refusal_.test(w.robot) || unsettled_.test(w.robot)) {
      return true;  // stale, or tried anyway
    }
    if (path_holds(w.robot)) return false;
    unsettled_.set(w.robot);
    return true;
  });
  if (it->second.empty()) watchers_.erase(it);
}

// Is there a path of unfinished actions from `from` to `to` (Type-1 and the current Type-2
// edges, but skip_from -> skip_to)? kPath with its Type-2 edges in `path`; kBudget past the
// search budget. Depth-first backwards, from `to` over its unfinished predecessors (an action
// finishes after its predecessors, so a finished one leads to no unfinished one): what must
// happen before `to`, few actions for a robot near its location. Searching forwards walks the
// whole future of `from` instead: at 1000 robots it ran out of budget in 4216 of 5939 searches
// (each a switch refused) and took 6 % of the monitor's CPU (docs/execution.md, "Cost").
// Two exact bounds (switchable_order.cpp): an action ordered before `from` (before `floor`, when
// a chain's new edges are not ordered yet: chain_floor()) cannot follow it, and
// an action sent already waits for finished actions alone (a switch only adds edges into unsent
// entries), so neither leads back to `from`, unsent; nor does anything before them. Without
// them the searches behind a robot far from its location walked to the budget and gave up.
SwitchableTracker::Reach SwitchableTracker::reaches(
    uint32_t from, uint32_t to, uint32_t skip_from, uint32_t skip_to,
    std::vector<std::pair<uint32_t, uint32_t>>& path, uint32_t floor) {
  next_stamp();
  stack_.assign(1, to);
  mark_[to].seen = stamp_;
  const bool unsent = !sent_by(mark_[from].robot, from);
  const uint32_t lowest = !ordered_ ? 0 : floor == kNoAction ? mark_[from].ord : floor;
  const auto push = [&](uint32_t v, uint32_t u) {  // parent_[v] = u: the path goes v -> u
    Mark& m = mark_[v];
    if (m.seen == stamp_ || m.ord < lowest) return;
    if (unsent ? sent_by(m.robot, v) : finished_by(m.robot, v)) return;
    m.seen = stamp_;
    parent_[v] = u;
    stack_.push_back(v);
  };
  std::size_t visited = 0;
  const auto done = [&](Reach r) {
    search_visits_ += visited;
    return r;
  };
  while (!stack_.empty()) {
    const uint32_t u = stack_.back();
    stack_.pop_back();
    if (u == from) {
      for (uint32_t v = from; v != to; v = parent_[v]) {
        const uint32_t w = parent_[v];
        if (mark_[v].robot != mark_[w].robot) path.emplace_back(v, w);
      }
      return done(Reach::kPath);
    }
    if (++visited > options_.search_budget) return done(Reach::kBudget);
    if (u > actions_.offset[mark_[u].robot]) push(u - 1, u);  // not its robot's first action
    each_edge_in(u, [&](uint32_t v) {
      if (!(v == skip_from && u == skip_to)) push(v, u);
    });
  }
  return done(Reach::kNone);
}

void SwitchableTracker::next_stamp() {
  if (++stamp_ == 0) {
    for (auto& m : mark_) m.seen = 0;
    stamp_ = 1;
  }
}

// h, i, j, k -> h, j, i, k at i's location (i = `stay`), the pending counts following the edges.
void SwitchableTracker::swap_with_next(uint32_t stay, std::vector<uint32_t>& changed) {
  const uint32_t j = after(stay).stay;
  relink(stay);
  order_swapped({stay});
  settle(j);
  const uint32_t robot = stay_[j].robot;
  if (advance(robot)) changed.push_back(robot);
}

// The order and the pending counts alone: undone by relink(j), j now before i (try_chain).
void SwitchableTracker::relink(uint32_t stay) {
  const uint32_t i = stay, j = after(stay).stay;
  const uint32_t h = before(i).stay, k = after(j).stay;
  const auto edge = [&](uint32_t from, uint32_t to, int delta) {
    if (from == kNoAction || to == kNoAction || stay_[from].robot == stay_[to].robot) return;
    if (stay_[from].leave == kNoAction || stay_[to].enter == kNoAction) return;
    if (finished_by(stay_[from].robot, stay_[from].leave)) return;
    pending_[stay_[to].enter] += delta;
  };
  edge(h, i, -1);
  edge(i, j, -1);
  edge(j, k, -1);
  if (h != kNoAction) link_next(h, j);
  if (k != kNoAction) link_prev(k, i);
  link_prev(j, h);
  link_next(j, i);
  link_prev(i, j);
  link_next(i, k);
  edge(h, j, +1);
  edge(j, i, +1);
  edge(i, k, +1);
}

// After j passed the stay after it (h, j, i, k): the refusals that may change and the robots
// that may switch now are marked.
void SwitchableTracker::settle(uint32_t j) {
  const uint32_t i = after(j).stay, h = before(j).stay, k = after(i).stay;
  for (const uint32_t s : {h, i, j}) {  // the edges from their leaves were switched away
    if (s != kNoAction && stay_[s].leave != kNoAction) unsettle_watchers(stay_[s].leave);
  }
  for (const uint32_t s : {i, j, k}) {  // a stay before them changed
    if (s != kNoAction) unsettle(s);
  }
  consider(i);
  if (k != kNoAction && stay_[k].enter != kNoAction) consider(k);
}

// Anticipation (switchable_tracker.hpp). A report of one finished action is a duration sample:
// from its start (the previous finish, or its sending when later) to now. The robot's next
// action starts now if it was sent already (advance() sets the time when it is sent later):
// reports come in time order (lock-step ticks, the monitor's clock), so an action sent before the
// report was sent no later than now. Kept per robot, not per action: reading each action's
// sending time was a cache miss a report, 2.5 % of the monitor's CPU on a dense map
// (docs/execution.md, "A robot's next actions read together").
void SwitchableTracker::observe(uint32_t robot, uint32_t from, uint32_t upto, double time_s) {
  if (upto == from + 1) {  // turning_ tells the kind of seq `from`, the robot's action until now
    durations_.observe(turning_[robot] != 0 ? grid::ActionType::kRotate : grid::ActionType::kMove,
                       time_s - started_s_[robot]);
  }
  started_s_[robot] = time_s;
}

// An action's kind from a bit per node (27 KB for SMART's 1000-robot plan, where the prefix sums
// of moves take 0.9 MB and the plan's actions 10 MB): read once a report, it stays in the cache.
grid::ActionType SwitchableTracker::kind(uint32_t node) const {
  return (turn_bits_[node / 64] >> (node % 64) & 1) != 0 ? grid::ActionType::kRotate
                                                         : grid::ActionType::kMove;
}

bool SwitchableTracker::turn_at(uint32_t robot, uint32_t seq) const {
  return seq < actions_.count(robot) &&
         kind(actions_.offset[robot] + seq) == grid::ActionType::kRotate;
}

// When `robot` is expected to finish action `seq` (not finished yet): O(1), the kinds of the
// actions between counted by prefix sums.
double SwitchableTracker::finish_estimate(uint32_t robot, uint32_t seq) const {
  const uint32_t current = finished_[robot];
  if (seq < current) return now_s_;
  const uint32_t base = actions_.offset[robot];
  const uint32_t moves = moves_before_[base + seq + 1] - moves_before_[base + current + 1];
  const double started = enqueued_[robot] > current ? started_s_[robot] : -1.0;
  return durations_.finish_s(now_s_, started, kind(base + current), {moves, seq - current - moves});
}

// When a stay's robot is expected at the location: when it finishes the action before entering;
// infinite for a robot more than horizon_actions away (not expected anywhere yet).
double SwitchableTracker::arrival(uint32_t stay) const {
  const Stay& x = stay_[stay];
  const uint32_t seq = x.enter - actions_.offset[x.robot];
  if (seq <= finished_[x.robot]) return now_s_;
  if (seq - finished_[x.robot] > options_.horizon_actions) {
    return std::numeric_limits<double>::infinity();
  }
  return finish_estimate(x.robot, seq - 1);
}

// The location's queue for stays i, j: it frees when h (before i) leaves; each enters when it
// arrives and the one before has left, stays as long as it is expected to; the stay k after j
// waits for the last of the two. i and j leave again (their stays have edges). An arrival is
// infinite for a robot not expected yet (then the stays' lengths are not needed).
PassQueue SwitchableTracker::queue_of(uint32_t i, uint32_t j) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  PassQueue q{now_s_, {arrival(i), 0}, {arrival(j), 0}, kInf};
  if (!std::isfinite(q.i.arrive_s) || !std::isfinite(q.j.arrive_s)) return q;
  const auto stay_s = [this](uint32_t x, double arrive_s) {
    const Stay& stay = stay_[x];
    return finish_estimate(stay.robot, stay.leave - actions_.offset[stay.robot]) - arrive_s;
  };
  q.i.stay_s = stay_s(i, q.i.arrive_s);
  q.j.stay_s = stay_s(j, q.j.arrive_s);
  const auto h = before(i);
  if (h.stay != kNoAction && stay_[h.stay].leave != kNoAction &&
      !finished_by(stay_[h.stay].robot, stay_[h.stay].leave)) {
    const Stay& first = stay_[h.stay];
    q.free_s = finish_estimate(first.robot, first.leave - actions_.offset[first.robot]);
  }
  const auto k = after(j);
  if (k.edge && stay_[k.stay].enter != kNoAction && stay_[k.stay].robot != stay_[i].robot) {
    q.next_arrive_s = arrival(k.stay);
  }
  return q;
}

// Expected waiting saved at the location by passing j before i (queue_of, queue_saving).
// Infinite when i is far (j goes), minus infinite when j is.
double SwitchableTracker::expected_saving(const PassQueue& q) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!std::isfinite(q.j.arrive_s)) return -kInf;
  if (!std::isfinite(q.i.arrive_s)) return kInf;
  return queue_saving(q);
}

// `robot`'s next entry i is about to be sent: the stay j after it passes first when expected
// to save more than margin_s and it is safe (the conditions of try_switch, h having left as
// nothing is pending for i). True when switched (i then waits for j; decided again later).
bool SwitchableTracker::anticipate(uint32_t robot, double time_s, std::vector<uint32_t>& changed) {
  if (enqueued_[robot] >= actions_.count(robot)) return false;
  const uint32_t node = actions_.offset[robot] + enqueued_[robot];
  if (pending_[node] != 0 || decided_[node]) return false;
  for (uint32_t e = enter_begin_[node]; e < enter_begin_[node + 1]; ++e) {
    const uint32_t i = enter_stays_[e];
    const auto j = after(i);
    if (!j.edge || stay_[i].leave == kNoAction) continue;
    const Stay& second = stay_[j.stay];
    if (second.enter == kNoAction || second.leave == kNoAction) continue;
    if (pending_[second.enter] != 1) continue;  // j waits for more than i
    // A chain (try_switch) only where the location's queue expects j passing first to save more
    // than the margin: every chain compared costs deadlock searches and two walks, and without
    // this a 1000-robot run spent 14.6 % of the monitor's CPU in switching (docs/execution.md).
    const double gain = saving(i, j.stay);
    const bool whole_chain = compares_chains() && std::isinf(gain) && gain < 0 &&
                             expected_saving(queue_of(i, j.stay)) > margin();
    if (gain <= margin() && !whole_chain) continue;
    std::vector<std::pair<uint32_t, uint32_t>> path;
    const Reach r = reaches(node, second.leave, stay_[i].leave, second.enter, path);
    if (r == Reach::kPath && whole_chain && try_chain(i, path, time_s, changed, true)) return true;
    if (r != Reach::kNone || whole_chain) continue;
    switches_.push_back({time_s, location_[i], second.robot, robot, true, second.enter, node});
    ++anticipated_;
    swap_with_next(i, changed);
    return true;
  }
  return false;
}

// The entry keeps its place: it is sent, with what follows it.
void SwitchableTracker::decide(uint32_t robot, std::vector<uint32_t>& changed) {
  if (enqueued_[robot] >= actions_.count(robot)) return;
  const uint32_t node = actions_.offset[robot] + enqueued_[robot];
  if (pending_[node] != 0) return;  // it waits again (a switch): decided when it is free
  decided_[node] = 1;
  if (advance(robot)) changed.push_back(robot);
}

ActionWindowRange SwitchableTracker::window(uint32_t robot, uint32_t cap) const {
  return {finished_[robot], std::min(enqueued_[robot], finished_[robot] + cap)};
}

bool SwitchableTracker::deadlocked() const {
  if (complete()) return false;
  for (std::size_t r = 0; r < finished_.size(); ++r) {
    if (enqueued_[r] > finished_[r]) return false;
  }
  return true;
}

// The robot before each stay the next action enters, as the orders are now: its stay's entry
// tells where it is (execution.hpp blocker_cause; any footprint, as the stays are the
// footprint's). The stays before are kept with the waiting robot while their locations' orders
// stay as they were (epoch_): asked again every 0.5 s, a wait reads per-robot arrays only.
std::optional<WaitCause> SwitchableTracker::wait_cause(uint32_t robot) const {
  if (robot_done(robot) || enqueued_[robot] > finished_[robot]) return std::nullopt;
  const uint32_t node = actions_.offset[robot] + enqueued_[robot];
  WaitLook& w = wait_look_[robot];
  if (!w.valid(node, epoch_)) w.fill(*this, node);
  auto cause = WaitCause::kAtLocation;
  bool held = true;  // no blocker left to wait for: pending_[node] == 0
  const auto take = [&](const Stay& theirs) {
    if (theirs.leave == kNoAction || finished_by(theirs.robot, theirs.leave)) return;
    held = false;
    const uint32_t base = actions_.offset[theirs.robot], done = finished_[theirs.robot];
    const auto enter =
        theirs.enter == kNoAction ? std::nullopt : std::optional<uint32_t>(theirs.enter - base);
    cause = std::max(cause, blocker_cause(enter, done, enqueued_[theirs.robot],
                                          turning_[theirs.robot] != 0, options_.commit_actions));
  };
  if (w.count <= WaitLook::kKept) {
    for (uint32_t k = 0; k < w.count; ++k) {
      if (w.before[k].edge) take(w.before[k].stay);
    }
  } else {  // more stays than are kept: read each time
    for (uint32_t k = enter_begin_[node]; k < enter_begin_[node + 1]; ++k) {
      const auto b = before(enter_stays_[k]);
      if (b.edge) take(stay_[b.stay]);
    }
  }
  return held ? WaitCause::kHeld : cause;
}

bool SwitchableTracker::WaitLook::valid(uint32_t at, const std::vector<uint32_t>& epoch) const {
  if (node != at) return false;
  for (uint32_t k = 0; k < std::min(count, kKept); ++k) {
    if (epoch[before[k].location] != before[k].epoch) return false;
  }
  return true;
}

void SwitchableTracker::WaitLook::fill(const SwitchableTracker& t, uint32_t at) {
  node = at;
  count = t.enter_begin_[at + 1] - t.enter_begin_[at];
  for (uint32_t k = 0; k < std::min(count, kKept); ++k) {
    const uint32_t stay = t.enter_stays_[t.enter_begin_[at] + k];
    const auto b = t.before(stay);
    const uint32_t location = t.location_[stay];
    before[k] = {location, t.epoch_[location], b.edge, b.edge ? t.stay_[b.stay] : Stay{}};
  }
}

void SwitchableTracker::predecessors(uint32_t node, std::vector<uint32_t>& out) const {
  each_edge_in(node, [&](uint32_t leave) { out.push_back(leave); });
}

std::vector<uint32_t> SwitchableTracker::order_at(uint32_t location) const {
  std::vector<uint32_t> out;
  if (orders_.begin[location] == orders_.begin[location + 1]) return out;
  // Stay ids are the plan's positions: the location's first one is one of its stays, wherever
  // the switches moved it; the list's head is found from it.
  uint32_t stay = orders_.begin[location];
  while (link_[stay].prev != kNoAction) stay = link_[stay].prev;
  for (; stay != kNoAction; stay = link_[stay].next) out.push_back(stay_[stay].robot);
  return out;
}

}  // namespace smart::monitor
