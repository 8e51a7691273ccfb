#include "smart/monitor/live_adg.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <tuple>
#include <utility>

namespace smart::monitor {

namespace {

constexpr double kStanding = -std::numeric_limits<double>::infinity();

// Sorts `location << 32 | index` keys by location (stable LSD radix, 12 bits a pass: two passes
// for maps under 16.7 million half cells). Linear: with it instead of Boost.Sort's integer_sort a
// 10 000-robot window's append takes 20 ms instead of 28 (iron), 34 instead of 42 (sortation).
void sort_by_location(std::vector<uint64_t>& keys, uint32_t locations) {
  constexpr int kBits = 12;
  constexpr uint64_t kMask = (1U << kBits) - 1;
  std::vector<uint64_t> out(keys.size());
  std::vector<uint32_t> start(std::size_t{1} << kBits);
  for (int bit = 32; bit < 64 && (uint64_t{locations} >> (bit - 32)) != 0; bit += kBits) {
    std::fill(start.begin(), start.end(), 0);
    for (const uint64_t k : keys) ++start[(k >> bit) & kMask];
    uint32_t sum = 0;
    for (auto& c : start) sum += std::exchange(c, sum);
    for (const uint64_t k : keys) out[start[(k >> bit) & kMask]++] = k;
    keys.swap(out);
  }
}

std::string describe(NodeRef n) {
  return "robot " + std::to_string(n.robot) + " action " + std::to_string(n.seq);
}

}  // namespace

// One robot's stay at a location, as the append links them (32 bytes; a 10 000-robot window has
// a quarter million): rank 0 a kept unfinished move leaving the location (an old action, ordered
// by its pass key: its start time, exchanged by switches, so the last of them leaves last), rank 1
// a stay of the window (ordered by arrival: the robot standing there first).
struct LiveAdg::Occupancy {
  uint32_t location = 0;
  uint32_t robot = 0;
  uint32_t enter_seq = 0;  // the window's action that enters (enter_new)
  uint32_t leave_seq = 0;  // the action that leaves (has_leave)
  double order = kStanding;
  uint8_t rank = 1;
  bool enter_new = false;
  bool has_leave = false;

  auto key() const { return std::tie(rank, order, robot, enter_seq, leave_seq); }
};

void LiveAdg::erase_ref(Refs& v, NodeRef x) {
  const auto it = std::find(v.begin(), v.end(), x);
  if (it != v.end()) v.erase(it);
}

LiveAdg::LiveAdg(const Grid& grid, const std::vector<Cell>& start, Heading initial_heading)
    : grid_(grid), robots_(start.size()), refused_(start.size()) {
  for (std::size_t r = 0; r < start.size(); ++r) {
    auto& rb = robots_[r];
    rb.done = HalfCell::of(start[r]);
    rb.tail_cell = start[r];
    rb.done_heading = rb.tail_heading = initial_heading;
  }
}

bool LiveAdg::advance(uint32_t r) {
  auto& rb = robots_[r];
  const uint32_t before = rb.enqueued;
  while (rb.enqueued < end(r) && node(r, rb.enqueued).pending == 0 && !held(r, rb.enqueued)) {
    if (anticipating() && shared(r, rb.enqueued)) {
      ahead_.insert(r);  // due: its place is decided before it is sent (try_switches)
      break;
    }
    node(r, rb.enqueued).sent_s = now_s_;
    ++rb.enqueued;
  }
  // Its next entry came up waiting for one robot: it may switch (tried in try_switches).
  if (switching_ && rb.enqueued != before && rb.enqueued < end(r) &&
      node(r, rb.enqueued).pending == 1) {
    dirty_.insert(r);
  }
  return rb.enqueued != before;
}

void LiveAdg::finish(uint32_t r, uint32_t seq, Update& u) {
  Node& n = node(r, seq);
  for (const NodeRef t : n.out) {
    Node& m = node(t.robot, t.seq);
    erase_ref(m.in, {r, seq});
    if (--m.pending == 0 && advance(t.robot)) u.robots_changed.push_back(t.robot);
    if (switching_) dirty_after_release(t);
  }
}

LiveAdg::Update LiveAdg::on_progress(uint32_t robot, int64_t finished_seq, double time_s,
                                     const std::function<void(const Action&)>& finished) {
  Update u;
  auto reject = [&](ExecutionTracker::Result why, std::string reason) {
    u.result = why;
    u.reason = "robot " + std::to_string(robot) + " " + std::move(reason);
    return u;
  };
  if (robot >= robots_.size()) {
    return reject(ExecutionTracker::Result::kRejected,
                  "does not exist (the run has " + std::to_string(robots_.size()) + " robots)");
  }
  auto& rb = robots_[robot];
  if (finished_seq < static_cast<int64_t>(rb.finished)) {
    return reject(ExecutionTracker::Result::kStale,
                  "already finished " + std::to_string(rb.finished) + " actions");
  }
  if (finished_seq >= static_cast<int64_t>(rb.enqueued)) {
    return reject(ExecutionTracker::Result::kRejected,
                  "reports action " + std::to_string(finished_seq) +
                      " finished but only actions below " + std::to_string(rb.enqueued) +
                      " were enqueued");
  }
  u.result = ExecutionTracker::Result::kAdvanced;
  u.robots_changed.push_back(robot);
  const auto upto = static_cast<uint32_t>(finished_seq + 1);
  now_s_ = std::max(now_s_, time_s);
  if (anticipating()) observe(robot, upto, time_s);
  for (uint32_t s = rb.finished; s < upto; ++s) {
    finish(robot, s, u);
    const Action& a = rb.nodes.front().action;
    rb.done = a.to;
    rb.done_heading = a.heading;
    if (finished) finished(a);
    rb.nodes.pop_front();
    ++rb.base;
  }
  finished_total_ += upto - rb.finished;
  rb.finished = upto;
  if (switching_) {
    advance(robot);  // a held move may be near enough now
    dirty_.insert(robot);
    try_switches(time_s, u.robots_changed);
  }
  std::sort(u.robots_changed.begin(), u.robots_changed.end());
  u.robots_changed.erase(std::unique(u.robots_changed.begin(), u.robots_changed.end()),
                         u.robots_changed.end());
  return u;
}

LiveAdg::Window LiveAdg::window(uint32_t r, uint32_t cap) const {
  const auto& rb = robots_[r];
  return {rb.finished, std::min(rb.enqueued, rb.finished + cap)};
}

bool LiveAdg::deadlocked() const {
  bool any_left = false;
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    if (robots_[r].enqueued > robots_[r].finished) return false;
    any_left = any_left || end(r) > robots_[r].finished;
  }
  return any_left;
}

std::vector<NodeRef> LiveAdg::waits_for(uint32_t r, uint32_t seq) const {
  const auto& in = node(r, seq).in;
  return {in.begin(), in.end()};
}

std::optional<WaitCause> LiveAdg::wait_cause(uint32_t r) const {
  const auto& rb = robots_[r];
  if (rb.enqueued > rb.finished) return std::nullopt;
  if (rb.enqueued >= end(r)) return WaitCause::kNoAction;
  const Node& n = node(r, rb.enqueued);
  if (n.pending == 0) return WaitCause::kHeld;
  auto cause = WaitCause::kAtLocation;
  for (const NodeRef p : n.in) cause = std::max(cause, blocker_state(p));
  return cause;
}

// What the robot of an unfinished leave is doing (its stays are half cells:
// live_adg_switching.cpp).
WaitCause LiveAdg::blocker_state(NodeRef leave) const {
  const auto& ib = robots_[leave.robot];
  return half_cell_blocker_cause(
      leave.seq, ib.finished, ib.enqueued,
      switching_ ? switching_->commit_actions : SwitchOptions{}.commit_actions,
      [&](uint32_t s) { return action(leave.robot, s).type; });
}

CommitCut LiveAdg::commit_cut(const std::vector<uint32_t>& keep, uint32_t lookahead) const {
  const auto n = static_cast<uint32_t>(robots_.size());
  CommitCut cut;
  cut.end.resize(n);
  std::vector<uint32_t> scanned(n), work;
  for (uint32_t r = 0; r < n; ++r) {
    const uint32_t want = std::max(r < keep.size() ? keep[r] : 0, robots_[r].finished + lookahead);
    cut.end[r] = std::min(want, end(r));
    scanned[r] = robots_[r].finished;
    work.push_back(r);
  }
  while (!work.empty()) {
    const uint32_t r = work.back();
    work.pop_back();
    // Never stop on an edge midpoint (a robot may stand on one after finishing a half-move):
    // keep the half-move that reaches the next cell.
    auto stands = [&] {
      return cut.end[r] == robots_[r].finished ? robots_[r].done : action(r, cut.end[r] - 1).to;
    };
    while (!stands().is_cell()) ++cut.end[r];
    for (; scanned[r] < cut.end[r]; ++scanned[r]) {
      for (const NodeRef p : node(r, scanned[r]).in) {
        if (p.seq + 1 <= cut.end[p.robot]) continue;
        cut.end[p.robot] = p.seq + 1;
        work.push_back(p.robot);
      }
    }
  }
  cut.cell.resize(n);
  cut.heading.resize(n);
  for (uint32_t r = 0; r < n; ++r) {
    cut.kept_unfinished += cut.end[r] - robots_[r].finished;
    const HalfCell at =
        cut.end[r] == robots_[r].finished ? robots_[r].done : action(r, cut.end[r] - 1).to;
    cut.cell[r] = {at.x2 / 2, at.y2 / 2};
    cut.heading[r] = cut.end[r] == robots_[r].finished ? robots_[r].done_heading
                                                       : action(r, cut.end[r] - 1).heading;
  }
  return cut;
}

void LiveAdg::truncate(const CommitCut& cut) {
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    auto& rb = robots_[r];
    while (end(r) > cut.end[r]) {
      const uint32_t s = end(r) - 1;
      for (const NodeRef p : node(r, s).in) {
        // A predecessor of a dropped action may be dropped already (its robot came first).
        if (p.seq < end(p.robot)) erase_ref(node(p.robot, p.seq).out, {r, s});
      }
      type2_total_ -= node(r, s).in.size();
      rb.nodes.pop_back();
      --appended_total_;
    }
    rb.enqueued = std::min(rb.enqueued, end(r));
    rb.tail_cell = cut.cell[r];
    rb.tail_heading = cut.heading[r];
  }
  ++epoch_;
  ++truncations_;
}

std::vector<Problem> LiveAdg::build_window(const std::vector<std::vector<Cell>>& paths, double t0,
                                           NewActions& acts, double& t_end) const {
  std::vector<Problem> problems;
  std::size_t steps_total = 0;
  for (const auto& p : paths) steps_total += p.size();
  acts.all.reserve(3 * steps_total);  // at most a rotation and two half-moves a step
  acts.first.assign(1, 0);
  std::vector<PathStep> steps;
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    const auto& path = paths[r];
    if (path.empty() || path.front() != robots_[r].tail_cell) {
      problems.push_back({"lifelong window", 0, static_cast<int>(r),
                          "starts at " +
                              (path.empty() ? std::string("nowhere") : to_string(path.front())) +
                              " but the robot stops at " + to_string(robots_[r].tail_cell)});
      continue;
    }
    for (std::size_t k = 1; k < path.size(); ++k) {
      if (std::abs(path[k].x - path[k - 1].x) + std::abs(path[k].y - path[k - 1].y) > 1 ||
          !grid_.free(path[k])) {
        problems.push_back({"lifelong window", 0, static_cast<int>(r),
                            "step " + std::to_string(k) + " to " + to_string(path[k]) +
                                " is not a free neighbour of " + to_string(path[k - 1])});
        break;
      }
    }
    steps.clear();
    for (std::size_t k = 0; k < path.size(); ++k) steps.push_back({path[k], t0 + double(k), 0});
    Heading h = robots_[r].tail_heading;
    append_robot_actions(r, end(r), h, steps, acts.all);
    acts.first.push_back(static_cast<uint32_t>(acts.all.size()));
    t_end = std::max(t_end, steps.back().time);
  }
  return problems;
}

// Every kept unfinished move leaving a location (rank 0), then each robot's stays in the window:
// where it stands at the cut, and after each move it makes (rank 1).
std::vector<LiveAdg::Occupancy> LiveAdg::occupancies(const NewActions& acts) const {
  std::vector<Occupancy> occ;
  occ.reserve(unfinished_total() + acts.all.size() + robots_.size());
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    for (uint32_t s = robots_[r].finished; s < end(r); ++s) {
      const Action& a = action(r, s);
      if (a.type != ActionType::kMove) continue;
      occ.push_back({static_cast<uint32_t>(grid_.half_index(a.from)), r, 0, s, node(r, s).pass_key,
                     0, false, true});
    }
  }
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    Occupancy cur{static_cast<uint32_t>(grid_.half_index(HalfCell::of(robots_[r].tail_cell))), r};
    for (uint32_t i = acts.first[r]; i < acts.first[r + 1]; ++i) {
      const Action& a = acts.all[i];
      if (a.type != ActionType::kMove) continue;
      cur.has_leave = true;
      cur.leave_seq = a.seq;
      occ.push_back(cur);
      cur = {
          static_cast<uint32_t>(grid_.half_index(a.to)), r, a.seq, 0, a.end_time, 1, true, false};
    }
    occ.push_back(cur);
  }
  return occ;
}

// Occupancies grouped by location (a radix sort of location-index keys: no table over the grid's
// locations, which are 13.7 million half cells on a 1800x1912 map), each group in passing order;
// consecutive occupants of different robots are linked when the later one enters in the window.
std::vector<Problem> LiveAdg::link(const std::vector<Occupancy>& occ,
                                   std::vector<std::pair<NodeRef, NodeRef>>& edges) const {
  std::vector<uint64_t> keys(occ.size());
  for (std::size_t i = 0; i < occ.size(); ++i) keys[i] = uint64_t{occ[i].location} << 32 | i;
  sort_by_location(keys, static_cast<uint32_t>(grid_.half_cell_count()));
  auto at = [&](uint64_t k) -> const Occupancy& { return occ[k & 0xffffffffU]; };
  std::vector<Problem> problems;
  for (std::size_t g = 0, e = 0; g < keys.size(); g = e) {
    for (e = g + 1; e < keys.size() && at(keys[e]).location == at(keys[g]).location;) ++e;
    if (e - g < 2) continue;
    std::sort(keys.begin() + std::ptrdiff_t(g), keys.begin() + std::ptrdiff_t(e),
              [&](uint64_t a, uint64_t b) { return at(a).key() < at(b).key(); });
    for (std::size_t i = g + 1; i < e; ++i) {
      const Occupancy& p = at(keys[i - 1]);
      const Occupancy& q = at(keys[i]);
      if (p.robot == q.robot || !q.enter_new) continue;
      if (p.has_leave) {
        edges.push_back({{p.robot, p.leave_seq}, {q.robot, q.enter_seq}});
        continue;
      }
      const auto w = static_cast<int32_t>(2 * grid_.width() - 1);
      const HalfCell cell{static_cast<int32_t>(q.location) % w,
                          static_cast<int32_t>(q.location) / w};
      problems.push_back({"lifelong window", 0, static_cast<int>(q.robot),
                          "enters " + to_string(cell) + " (" + describe({q.robot, q.enter_seq}) +
                              ") where robot " + std::to_string(p.robot) +
                              " stays until the window ends; the planner's window collides"});
    }
  }
  return problems;
}

std::vector<Problem> LiveAdg::check_window_acyclic(
    const NewActions& acts, const std::vector<std::pair<NodeRef, NodeRef>>& edges) const {
  // Dense ids of the new actions; old actions never wait for new ones, so only new-to-new edges
  // can close a cycle. Type-1 successors are implicit (k -> k + 1 within a robot), Type-2 ones in
  // compressed rows.
  const auto& first = acts.first;
  const uint32_t n = first.back();
  auto id = [&](NodeRef x) -> int64_t {
    return x.seq < end(x.robot) ? -1 : int64_t{first[x.robot] + (x.seq - end(x.robot))};
  };
  std::vector<uint32_t> indegree(n, 0), begin(n + 1, 0), list;
  std::vector<uint8_t> last(n, 0);  // the last new action of its robot (no Type-1 successor)
  for (std::size_t r = 0; r + 1 < first.size(); ++r) {
    for (uint32_t k = first[r] + 1; k < first[r + 1]; ++k) ++indegree[k];
    if (first[r + 1] > first[r]) last[first[r + 1] - 1] = 1;
  }
  std::vector<std::pair<uint32_t, uint32_t>> t2;
  for (const auto& [u, v] : edges) {
    if (id(u) < 0) continue;
    t2.emplace_back(static_cast<uint32_t>(id(u)), static_cast<uint32_t>(id(v)));
    ++begin[t2.back().first + 1];
    ++indegree[t2.back().second];
  }
  for (uint32_t v = 0; v < n; ++v) begin[v + 1] += begin[v];
  list.resize(t2.size());
  std::vector<uint32_t> fill(begin.begin(), begin.end() - 1);
  for (const auto& [u, v] : t2) list[fill[u]++] = v;
  std::vector<uint32_t> queue;
  for (uint32_t v = 0; v < n; ++v) {
    if (indegree[v] == 0) queue.push_back(v);
  }
  for (std::size_t h = 0; h < queue.size(); ++h) {
    const uint32_t u = queue[h];
    if (!last[u] && --indegree[u + 1] == 0) queue.push_back(u + 1);
    for (uint32_t i = begin[u]; i < begin[u + 1]; ++i) {
      if (--indegree[list[i]] == 0) queue.push_back(list[i]);
    }
  }
  if (queue.size() == n) return {};
  return {{"lifelong window", 0, -1,
           "the window's passing orders form a cycle (" + std::to_string(n - queue.size()) +
               " actions could never start); the window is refused and robots stop at the cut"}};
}

std::vector<Problem> LiveAdg::append(const std::vector<std::vector<Cell>>& paths,
                                     double plan_time_s, AppendStats* stats) {
  if (paths.size() != robots_.size()) {
    return {{"lifelong window", 0, -1,
             "has " + std::to_string(paths.size()) + " paths for " +
                 std::to_string(robots_.size()) + " robots"}};
  }
  const double t0 = std::max(plan_time_s, last_plan_time_s_);
  NewActions acts;
  double t_end = t0;
  auto problems = build_window(paths, t0, acts, t_end);
  if (!problems.empty()) return problems;
  std::vector<std::pair<NodeRef, NodeRef>> edges;
  problems = link(occupancies(acts), edges);
  if (problems.empty()) problems = check_window_acyclic(acts, edges);
  if (!problems.empty()) return problems;
  insert(acts, edges);
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    if (acts.first[r + 1] == acts.first[r]) continue;
    robots_[r].tail_cell = paths[r].back();
    robots_[r].tail_heading = acts.all[acts.first[r + 1] - 1].heading;
  }
  appended_total_ += acts.all.size();
  type2_total_ += edges.size();
  last_plan_time_s_ = t_end;
  window_start_ = t0;
  now_s_ = std::max(now_s_, plan_time_s);
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    advance(r);
    if (switching_) dirty_.insert(r);  // tried at the next progress (its time stamps a switch)
  }
  std::vector<uint32_t> decided;  // sent to at once: the caller sends to robots that advanced
  settle_due(plan_time_s, decided);
  if (stats) *stats = {acts.all.size(), edges.size()};
  return {};
}

void LiveAdg::insert(const NewActions& acts,
                     const std::vector<std::pair<NodeRef, NodeRef>>& edges) {
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    auto& nodes = robots_[r].nodes;
    nodes.reserve(nodes.size() + (acts.first[r + 1] - acts.first[r]));
    for (uint32_t i = acts.first[r]; i < acts.first[r + 1]; ++i) {
      Node& n = nodes.push_back();  // a reused slot: its edge lists keep their storage
      n.action = acts.all[i];
      n.pass_key = n.action.start_time;
      n.stamp = 0;
      n.cone = n.order = 0;
      n.pending = 0;
      n.in.clear();
      n.out.clear();
    }
  }
  for (const auto& [u, v] : edges) {
    node(u.robot, u.seq).out.push_back(v);
    Node& m = node(v.robot, v.seq);
    m.in.push_back(u);
    ++m.pending;
  }
}

}  // namespace smart::monitor
