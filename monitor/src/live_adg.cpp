#include "smart/monitor/live_adg.hpp"

#include <algorithm>
#include <limits>

namespace smart::monitor {

namespace {

constexpr double kStanding = -std::numeric_limits<double>::infinity();

template <class Refs>
void erase_ref(Refs& v, NodeRef x) {
  const auto it = std::find(v.begin(), v.end(), x);
  if (it != v.end()) v.erase(it);
}

std::string describe(NodeRef n) {
  return "robot " + std::to_string(n.robot) + " action " + std::to_string(n.seq);
}

}  // namespace

// One robot's stay at a location, as the append links them: rank 0 is the last kept occupant
// that leaves (an old action), rank 1 the window's stays (the robot standing there first).
struct LiveAdg::Occupancy {
  uint32_t location = 0;
  int rank = 1;
  double arrive = kStanding;
  uint32_t robot = 0;
  bool enter_new = false;  // entered by an action of the window
  NodeRef enter;
  bool has_leave = false;
  NodeRef leave;
};

LiveAdg::LiveAdg(const Grid& grid, const std::vector<Cell>& start, Heading initial_heading)
    : grid_(grid), robots_(start.size()) {
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
  while (rb.enqueued < end(r) && node(r, rb.enqueued).pending == 0) ++rb.enqueued;
  return rb.enqueued != before;
}

void LiveAdg::finish(uint32_t r, uint32_t seq, Update& u) {
  Node& n = node(r, seq);
  for (const NodeRef t : n.out) {
    Node& m = node(t.robot, t.seq);
    erase_ref(m.in, {r, seq});
    if (--m.pending == 0 && advance(t.robot)) u.robots_changed.push_back(t.robot);
  }
}

LiveAdg::Update LiveAdg::on_progress(uint32_t robot, int64_t finished_seq,
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
}

// Per location, the kept unfinished occupancy that is left last (the latest leaving plan time).
// A dense table over the grid's locations, reused from call to call: a slot is this call's when
// its stamp is (no clearing, no hashing: 10 000 robots' cut in a few milliseconds).
std::vector<LiveAdg::Occupancy> LiveAdg::kept_last_leavers() {
  if (leaver_stamp_.size() != grid_.half_cell_count()) {
    leaver_stamp_.assign(grid_.half_cell_count(), 0);
    leaver_.resize(grid_.half_cell_count());
  }
  ++stamp_;
  std::vector<uint32_t> touched;
  touched.reserve(robots_.size() * 4);
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    for (uint32_t s = robots_[r].finished; s < end(r); ++s) {
      const Action& a = action(r, s);
      if (a.type != ActionType::kMove) continue;
      const auto loc = static_cast<uint32_t>(grid_.half_index(a.from));
      if (leaver_stamp_[loc] == stamp_) {
        const NodeRef l = leaver_[loc];
        if (action(l.robot, l.seq).start_time >= a.start_time) continue;
      } else {
        leaver_stamp_[loc] = stamp_;
        touched.push_back(loc);
      }
      leaver_[loc] = {r, s};
    }
  }
  std::vector<Occupancy> out;
  out.reserve(touched.size());
  for (const uint32_t loc : touched) {
    out.push_back(Occupancy{loc, 0, kStanding, leaver_[loc].robot, false, {}, true, leaver_[loc]});
  }
  return out;
}

std::vector<LiveAdg::Occupancy> LiveAdg::window_occupancies(
    const std::vector<std::vector<Action>>& acts, std::size_t room) const {
  std::vector<Occupancy> occ;
  std::size_t n = acts.size() + room;  // at most one per action, one per robot, and `room`
  for (const auto& a : acts) n += a.size();
  occ.reserve(n);
  for (uint32_t r = 0; r < acts.size(); ++r) {
    Occupancy cur{static_cast<uint32_t>(grid_.half_index(HalfCell::of(robots_[r].tail_cell))),
                  1,
                  kStanding,
                  r,
                  false,
                  {},
                  false,
                  {}};
    for (const Action& a : acts[r]) {
      if (a.type != ActionType::kMove) continue;
      cur.has_leave = true;
      cur.leave = {r, a.seq};
      occ.push_back(cur);
      cur = {static_cast<uint32_t>(grid_.half_index(a.to)),
             1,
             a.end_time,
             r,
             true,
             {r, a.seq},
             false,
             {}};
    }
    occ.push_back(cur);
  }
  return occ;
}

// Occupancies grouped by location (a counting sort over the locations touched, stamped like
// kept_last_leavers'), each group in passing order: the last kept leaver, then by arrival.
std::vector<LiveAdg::Occupancy> LiveAdg::by_location(const std::vector<Occupancy>& occ) {
  ++stamp_;
  std::vector<uint32_t> count;
  for (const auto& o : occ) {
    if (leaver_stamp_[o.location] != stamp_) {
      leaver_stamp_[o.location] = stamp_;
      leaver_[o.location] = {static_cast<uint32_t>(count.size()), 0};  // the group's id
      count.push_back(0);
    }
    ++count[leaver_[o.location].robot];
  }
  std::vector<uint32_t> start(count.size() + 1, 0);
  for (std::size_t g = 0; g < count.size(); ++g) start[g + 1] = start[g] + count[g];
  std::vector<Occupancy> sorted(occ.size());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (const auto& o : occ) sorted[fill[leaver_[o.location].robot]++] = o;
  for (std::size_t g = 0; g < count.size(); ++g) {
    std::sort(sorted.begin() + start[g], sorted.begin() + start[g + 1],
              [](const Occupancy& a, const Occupancy& b) {
                if (a.rank != b.rank) return a.rank < b.rank;
                if (a.arrive != b.arrive) return a.arrive < b.arrive;
                return a.robot < b.robot;
              });
  }
  return sorted;
}

std::vector<Problem> LiveAdg::link(const std::vector<Occupancy>& unsorted,
                                   std::vector<std::pair<NodeRef, NodeRef>>& edges) {
  const auto occ = by_location(unsorted);
  std::vector<Problem> problems;
  for (std::size_t i = 1; i < occ.size(); ++i) {
    const Occupancy& p = occ[i - 1];
    const Occupancy& q = occ[i];
    if (p.location != q.location || p.robot == q.robot || !q.enter_new) continue;
    if (!p.has_leave) {
      const auto w = static_cast<int32_t>(2 * grid_.width() - 1);
      const HalfCell at{static_cast<int32_t>(q.location) % w, static_cast<int32_t>(q.location) / w};
      problems.push_back({"lifelong window", 0, static_cast<int>(q.robot),
                          "enters " + to_string(at) + " (" + describe(q.enter) + ") where robot " +
                              std::to_string(p.robot) +
                              " stays until the window ends; the planner's window collides"});
      continue;
    }
    edges.emplace_back(p.leave, q.enter);
  }
  return problems;
}

std::vector<Problem> LiveAdg::check_window_acyclic(
    const std::vector<std::vector<Action>>& acts,
    const std::vector<std::pair<NodeRef, NodeRef>>& edges) const {
  // Dense ids of the new actions; old actions never wait for new ones, so only new-to-new edges
  // can close a cycle. Type-1 successors are implicit (k -> k + 1 within a robot), Type-2 ones in
  // compressed rows.
  std::vector<uint32_t> first(acts.size() + 1, 0);
  for (std::size_t r = 0; r < acts.size(); ++r) first[r + 1] = first[r] + uint32_t(acts[r].size());
  const uint32_t n = first.back();
  auto id = [&](NodeRef x) -> int64_t {
    return x.seq < end(x.robot) ? -1 : int64_t{first[x.robot] + (x.seq - end(x.robot))};
  };
  std::vector<uint32_t> indegree(n, 0), begin(n + 1, 0), list;
  std::vector<uint8_t> last(n, 0);  // the last new action of its robot (no Type-1 successor)
  for (std::size_t r = 0; r < acts.size(); ++r) {
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
  std::vector<std::vector<Action>> acts(robots_.size());
  std::vector<Problem> problems;
  double t_end = t0;
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    const auto& path = paths[r];
    if (path.empty() || path.front() != robots_[r].tail_cell) {
      problems.push_back({"lifelong window", 0, static_cast<int>(r),
                          "starts at " +
                              (path.empty() ? std::string("nowhere") : to_string(path.front())) +
                              " but the robot stops at " + to_string(robots_[r].tail_cell)});
      continue;
    }
    std::vector<PathStep> steps;
    for (std::size_t k = 0; k < path.size(); ++k) steps.push_back({path[k], t0 + double(k), 0});
    for (std::size_t k = 1; k < path.size(); ++k) {
      if (std::abs(path[k].x - path[k - 1].x) + std::abs(path[k].y - path[k - 1].y) > 1 ||
          !grid_.free(path[k])) {
        problems.push_back({"lifelong window", 0, static_cast<int>(r),
                            "step " + std::to_string(k) + " to " + to_string(path[k]) +
                                " is not a free neighbour of " + to_string(path[k - 1])});
        break;
      }
    }
    Heading h = robots_[r].tail_heading;
    acts[r] = build_robot_actions(r, end(r), h, steps);
    t_end = std::max(t_end, steps.back().time);
  }
  if (!problems.empty()) return problems;
  const auto kept = kept_last_leavers();
  auto occ = window_occupancies(acts, kept.size());
  occ.insert(occ.end(), kept.begin(), kept.end());
  std::vector<std::pair<NodeRef, NodeRef>> edges;
  problems = link(occ, edges);
  if (problems.empty()) problems = check_window_acyclic(acts, edges);
  if (!problems.empty()) return problems;

  AppendStats st;
  for (uint32_t r = 0; r < robots_.size(); ++r) {
    auto& rb = robots_[r];
    for (const Action& a : acts[r]) rb.nodes.push_back(Node{a, 0, {}, {}});
    if (!acts[r].empty()) {
      rb.tail_cell = paths[r].back();
      rb.tail_heading = acts[r].back().heading;
    }
    st.actions += acts[r].size();
  }
  for (const auto& [u, v] : edges) {
    node(u.robot, u.seq).out.push_back(v);
    Node& m = node(v.robot, v.seq);
    m.in.push_back(u);
    ++m.pending;
  }
  st.type2 = edges.size();
  appended_total_ += st.actions;
  type2_total_ += st.type2;
  last_plan_time_s_ = t_end;
  for (uint32_t r = 0; r < robots_.size(); ++r) advance(r);
  if (stats) *stats = st;
  return {};
}

}  // namespace smart::monitor
