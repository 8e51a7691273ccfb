#include "smart/planning/plan_lns.hpp"

#include <algorithm>
#include <climits>
#include <functional>
#include <stdexcept>
#include <string>

#include "smart/planning/space_time_reservations.hpp"

namespace smart::planning {

namespace {

using Path = std::vector<grid::Cell>;

// One search's scratch, kept between robots (a pass replans every robot). The open list holds
// its keys, each one integer: comparing through node ids read two scattered nodes a comparison,
// half of a pass's time on LaCAM's warehouse plan (docs/performance.md, "Plan LNS"). A bit per
// (cell, t), the reservations' shape, marks the states pushed; the words a search set are
// cleared after it.
struct PathSearch {
  struct Node {
    uint32_t cell;
    int32_t t, parent;
  };
  // Lowest f first; among equals the deepest, then the first pushed: one integer (f and t are
  // below SpaceTimeReservations::kMaxHorizon, 65 535, improve_plan checks; ids below 2^31, push
  // stops there).
  static uint64_t key(int32_t f, int32_t t, std::size_t id) {
    return uint64_t(f) << 48 | uint64_t(0xFFFF - t) << 32 | uint64_t(id);
  }
  std::vector<Node> nodes;
  std::vector<uint64_t> open;  // a min-heap of keys
  std::size_t words;
  std::vector<uint64_t> seen_bits;
  std::vector<std::size_t> touched;

  PathSearch(std::size_t cells, std::size_t horizon)
      : words((horizon + 64) / 64), seen_bits(cells * words, 0) {}
  bool seen(std::size_t cell, int32_t t) const {
    return (seen_bits[cell * words + std::size_t(t) / 64] >> (t % 64) & 1) != 0;
  }
  void see(std::size_t cell, int32_t t) {
    const std::size_t w = cell * words + std::size_t(t) / 64;
    if (seen_bits[w] == 0) touched.push_back(w);
    seen_bits[w] |= uint64_t{1} << (t % 64);
  }
  void clear() {
    nodes.clear();
    open.clear();
    for (const std::size_t w : touched) seen_bits[w] = 0;
    touched.clear();
  }
  // Past 2^31 nodes nothing more is pushed: the search is cut, as by max_expansions.
  void push(uint32_t cell, int32_t t, int32_t f, int32_t parent) {
    if (nodes.size() >= std::size_t{INT32_MAX}) return;
    open.push_back(key(f, t, nodes.size()));
    nodes.push_back({cell, t, parent});
    std::push_heap(open.begin(), open.end(), std::greater<>{});
  }
  // The id of the node of the lowest key, taken out of the open list.
  int32_t pop() {
    std::pop_heap(open.begin(), open.end(), std::greater<>{});
    const auto id = static_cast<int32_t>(open.back() & 0xFFFFFFFFu);
    open.pop_back();
    return id;
  }
};

// Space-time A* from `start` to `goal` for an arrival before `bound`: f = t + distance, only f
// < bound pushed; the robot parks at the goal, so it arrives only after every other path's last
// visit there. Empty when there is none (within `max_expansions`). A state is pushed once:
// pushed again it would have the same f and t and a later id, so it would be popped after the
// first and skipped; the states expanded are the same, in the same order, as with a closed list.
Path earlier_path(const grid::Grid& g, const SpaceTimeReservations& res, grid::Cell start,
                  grid::Cell goal_cell, int32_t bound, const std::vector<int32_t>& h,
                  std::size_t max_expansions, PathSearch& s, std::size_t& expansions) {
  const auto goal = g.index(goal_cell);
  const int32_t last = res.last_use(goal);
  s.clear();
  const auto push = [&](std::size_t cell, int32_t t, int32_t parent) {
    const int32_t f = t + h[cell];
    if (h[cell] < 0 || f >= bound || s.seen(cell, t)) return;
    s.see(cell, t);
    s.push(static_cast<uint32_t>(cell), t, f, parent);
  };
  push(g.index(start), 0, -1);
  const auto width = static_cast<int32_t>(g.width());
  for (std::size_t n_exp = 0; !s.open.empty() && n_exp < max_expansions;) {
    const int32_t id = s.pop();
    const PathSearch::Node n = s.nodes[std::size_t(id)];
    ++n_exp, ++expansions;
    if (n.cell == goal && n.t > last) {
      Path out(std::size_t(n.t) + 1);
      for (int32_t i = id; i >= 0; i = s.nodes[std::size_t(i)].parent) {
        const auto& m = s.nodes[std::size_t(i)];
        out[std::size_t(m.t)] = {static_cast<int32_t>(m.cell) % width,
                                 static_cast<int32_t>(m.cell) / width};
      }
      return out;
    }
    const grid::Cell c{static_cast<int32_t>(n.cell) % width, static_cast<int32_t>(n.cell) / width};
    for (const grid::Cell m : {c, grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                               grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
      if (!g.free(m)) continue;
      const auto mc = g.index(m);
      if (res.taken(mc, n.t + 1) || res.swaps(n.cell, mc, n.t)) continue;
      push(mc, n.t + 1, id);
    }
  }
  return {};
}

int64_t arrival(const Path& p) { return static_cast<int64_t>(p.size()) - 1; }

// One improve_plan call: the plan, its reservations, which robots visit each cell (for the
// neighbourhoods; entries of paths since replaced stay, and are checked against the path).
class Lns {
 public:
  Lns(const grid::Grid& grid, std::vector<Path>& paths, DistanceCache& tables,
      const PlanLnsOptions& options, std::size_t horizon)
      : grid_(grid),
        paths_(paths),
        tables_(tables),
        options_(options),
        horizon_(static_cast<int32_t>(horizon)),
        res_(grid, horizon),
        search_(grid.cell_count(), horizon),
        visits_(grid.cell_count()) {
    for (uint32_t i = 0; i < paths.size(); ++i) add(i);
  }

  // The robot with its neighbourhood, and alone when that finds nothing better.
  void improve(uint32_t robot) {
    if (options_.neighbourhood > 1) {
      const auto group = neighbourhood(robot);
      if (group.size() > 1 && improve_group(group)) return;
    }
    improve_group({robot});
  }
  PlanLnsStats stats() const { return st_; }

 private:
  grid::Cell at(uint32_t robot, int32_t t) const {
    const Path& p = paths_[robot];
    return p[std::min(static_cast<std::size_t>(t), p.size() - 1)];
  }
  void add(uint32_t robot) {
    res_.set(paths_[robot], true, true);
    note_visits(robot);
  }
  void note_visits(uint32_t robot) {
    for (std::size_t t = 0; t < paths_[robot].size(); ++t) {
      if (t == 0 || paths_[robot][t] != paths_[robot][t - 1]) {
        visits_[grid_.index(paths_[robot][t])].push_back(robot);
      }
    }
  }
  std::vector<uint32_t> neighbourhood(uint32_t robot) const;
  bool improve_group(const std::vector<uint32_t>& group);
  bool replan_group(const std::vector<uint32_t>& group);

  const grid::Grid& grid_;
  std::vector<Path>& paths_;
  DistanceCache& tables_;
  const PlanLnsOptions& options_;
  int32_t horizon_;
  SpaceTimeReservations res_;
  PathSearch search_;
  std::vector<std::vector<uint32_t>> visits_;
  PlanLnsStats st_;
};

// The robot and the robots in the way of its shortest path, as if it went now (MAPF-LNS §4.3's
// agent-based neighbourhood, without its random walk): walked down the robot's distance table,
// each robot at the walk's cell at that time (or parked there by then) joins, up to
// `neighbourhood` robots in all.
std::vector<uint32_t> Lns::neighbourhood(uint32_t robot) const {
  std::vector<uint32_t> group{robot};
  const auto table = tables_.to(paths_[robot].back());
  grid::Cell c = paths_[robot].front();
  for (int32_t t = 1; (*table)[grid_.index(c)] > 0; ++t) {
    const int32_t d = (*table)[grid_.index(c)];
    for (const grid::Cell m : {grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                               grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
      if (grid_.free(m) && (*table)[grid_.index(m)] == d - 1) {
        c = m;
        break;
      }
    }
    for (const uint32_t r : visits_[grid_.index(c)]) {
      if (at(r, t) != c || std::find(group.begin(), group.end(), r) != group.end()) continue;
      group.push_back(r);
      if (group.size() == static_cast<std::size_t>(options_.neighbourhood)) return group;
    }
  }
  return group;
}

// The group's paths taken out and planned again one after the other, each against the others'
// (the ones planned first included), each bounded so that the group's sum of arrivals can still
// come out lower (the ones after it at least their distance); kept when all are found, else put
// back. True when kept.
bool Lns::improve_group(const std::vector<uint32_t>& group) {
  std::vector<Path> old;
  for (const uint32_t r : group) {
    old.push_back(paths_[r]);
    res_.set(paths_[r], false, true);
  }
  ++st_.replanned;
  if (replan_group(group)) {
    ++st_.improved;
    for (std::size_t k = 0; k < group.size(); ++k) {
      st_.saved += arrival(old[k]) - arrival(paths_[group[k]]);
      note_visits(group[k]);
    }
    return true;
  }
  for (std::size_t k = 0; k < group.size(); ++k) {
    paths_[group[k]] = std::move(old[k]);
    res_.set(paths_[group[k]], true, true);
  }
  return false;
}

// True when every robot of the group has a new path (in paths_ and the reservations) and their
// arrivals sum lower than before; false with the group's reservations taken out.
bool Lns::replan_group(const std::vector<uint32_t>& group) {
  int64_t budget = 0, rest = 0;
  for (const uint32_t r : group) {
    budget += arrival(paths_[r]);
    rest += tables_.distance(paths_[r].front(), paths_[r].back());
  }
  std::vector<Path> found;
  for (const uint32_t r : group) {
    rest -= tables_.distance(paths_[r].front(), paths_[r].back());
    const auto bound = static_cast<int32_t>(std::min<int64_t>(budget - rest, horizon_));
    auto p = earlier_path(grid_, res_, paths_[r].front(), paths_[r].back(), bound,
                          *tables_.to(paths_[r].back()), options_.max_expansions, search_,
                          st_.expansions);
    if (p.empty()) break;
    budget -= arrival(p);
    res_.set(p, true, true);
    found.push_back(std::move(p));
  }
  if (found.size() < group.size()) {
    for (const auto& p : found) res_.set(p, false, true);
    return false;
  }
  for (std::size_t k = 0; k < group.size(); ++k) paths_[group[k]] = std::move(found[k]);
  return true;
}

}  // namespace

PlanLnsStats improve_plan(const grid::Grid& grid, std::vector<Path>& paths, DistanceCache& tables,
                          const PlanLnsOptions& options) {
  if (grid.cell_count() >= SpaceTimeReservations::kMaxCells) {
    throw std::invalid_argument("plan LNS: maps of 16 M cells or more are not supported");
  }
  if (options.neighbourhood < 1 || options.neighbourhood > 64) {
    throw std::invalid_argument("plan LNS: a neighbourhood of 1-64 robots, not " +
                                std::to_string(options.neighbourhood));
  }
  std::size_t horizon = 0;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (paths[i].empty()) {
      throw std::invalid_argument("plan LNS: robot " + std::to_string(i) + " has an empty path");
    }
    horizon = std::max(horizon, paths[i].size());
  }
  if (horizon >= SpaceTimeReservations::kMaxHorizon) {
    throw std::invalid_argument("plan LNS: plans of " +
                                std::to_string(SpaceTimeReservations::kMaxHorizon) +
                                " steps or more are not supported");
  }
  std::vector<std::pair<int64_t, uint32_t>> order;  // (delay, robot): most delayed first
  for (uint32_t i = 0; i < paths.size(); ++i) {
    const int32_t d = tables.distance(paths[i].front(), paths[i].back());
    const auto delay = arrival(paths[i]) - d;
    if (d >= 0 && delay > 0) order.emplace_back(delay, i);
  }
  std::stable_sort(order.begin(), order.end(), [](auto a, auto b) { return a.first > b.first; });
  Lns lns(grid, paths, tables, options, horizon);
  for (int pass = 0; pass < options.passes; ++pass) {
    for (const auto& [delay, i] : order) lns.improve(i);
  }
  return lns.stats();
}

}  // namespace smart::planning
