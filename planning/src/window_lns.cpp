#include "smart/planning/window_lns.hpp"

#include <algorithm>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>

#include "smart/planning/space_time_reservations.hpp"

namespace smart::planning {

namespace {

constexpr std::size_t kErrands = 2;  // errands a robot's cost looks at (RHCR: the next goals)

uint64_t vertex_key(uint64_t cell, int32_t t) { return (cell << 16) | uint64_t(uint16_t(t)); }

}  // namespace

// A robot's errands as its cost reads them: the cells, their distance tables, and the distance
// from the first to the second (so the cost stays consistent as an errand is reached).
struct WindowLns::Goals {
  uint32_t start = 0;
  std::vector<uint32_t> cells;
  std::vector<DistanceCache::Table> table;
  int32_t tail = 0;

  int32_t reached(uint32_t cell, int32_t k) const {
    while (static_cast<std::size_t>(k) < cells.size() && cell == cells[static_cast<std::size_t>(k)])
      ++k;
    return k;
  }
  // Distance left from `cell` with `k` errands reached; -1: unreachable.
  int32_t h(uint32_t cell, int32_t k) const {
    if (static_cast<std::size_t>(k) == cells.size()) return 0;
    const int32_t d = (*table[static_cast<std::size_t>(k)])[cell];
    return d < 0 ? -1 : d + (k == 0 ? tail : 0);
  }
};

// One robot's space-time A*: the states (cell, t, errands reached) and the open list.
struct WindowLns::Search {
  struct Node {
    int32_t f, t, h;
    uint32_t cell;
    int32_t k;       // errands reached
    int32_t parent;  // index into nodes; -1 at the start
  };
  std::vector<Node> nodes;
  std::unordered_set<uint64_t> closed;
  // Lowest f; among equals the deepest (a window's end is the goal), then the nearest.
  struct Later {
    const std::vector<Node>* nodes;
    bool operator()(int32_t a, int32_t b) const {
      const Node &x = (*nodes)[a], &y = (*nodes)[b];
      if (x.f != y.f) return x.f > y.f;
      if (x.t != y.t) return x.t < y.t;
      if (x.h != y.h) return x.h > y.h;
      return a > b;
    }
  };
  std::priority_queue<int32_t, std::vector<int32_t>, Later> open{Later{&nodes}};

  void clear() {
    nodes.clear();
    closed.clear();
    open = std::priority_queue<int32_t, std::vector<int32_t>, Later>(Later{&nodes});
  }
};

WindowLns::WindowLns(const grid::Grid& grid, DistanceCache& tables, WindowLnsOptions options)
    : grid_(grid), tables_(tables), options_(options) {}

void WindowLns::check(const WindowRequest& r, const WindowPlan& plan) const {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("window LNS: " + what);
  };
  if (r.goals.size() != r.start.size() || plan.paths.size() != r.start.size()) {
    fail(std::to_string(r.start.size()) + " starts, " + std::to_string(r.goals.size()) +
         " goal lists and " + std::to_string(plan.paths.size()) + " paths: give one each a robot");
  }
  if (r.steps < 1 || r.steps > 4096) fail("a window needs 1-4096 steps");
  if (grid_.cell_count() >= SpaceTimeReservations::kMaxCells) {
    fail("maps of 16 M cells or more are not supported");
  }
  for (std::size_t i = 0; i < plan.paths.size(); ++i) {
    const auto& p = plan.paths[i];
    if (p.size() != static_cast<std::size_t>(r.steps) + 1 || p.front() != r.start[i]) {
      fail("robot " + std::to_string(i) + "'s path does not start at its start or is not " +
           std::to_string(r.steps + 1) + " cells long");
    }
  }
}

// The second errand only when the first is within the window's reach: its table is a BFS over
// the map (PIBT makes one when the robot reaches the first errand, pibt.cpp), too dear for
// every robot every window (2500 robots of LoRR's warehouse: 6 s a window, smart_lifelong_bench).
WindowLns::Goals WindowLns::goals_of(const WindowRequest& r, uint32_t robot) {
  Goals g;
  g.start = static_cast<uint32_t>(grid_.index(r.start[robot]));
  for (const grid::Cell c : r.goals[robot]) {
    if (g.cells.size() == kErrands || !grid_.free(c)) break;
    if (g.cells.size() == 1 && (*g.table[0])[g.start] > r.steps) break;
    g.cells.push_back(static_cast<uint32_t>(grid_.index(c)));
    g.table.push_back(tables_.to(c));
  }
  if (g.cells.size() == 2) {
    g.tail = (*g.table[1])[g.cells[0]];
    if (g.tail < 0) g.cells.pop_back(), g.table.pop_back(), g.tail = 0;  // the second unreachable
  }
  return g;
}

// Timesteps plus the distance left at the window's end; -1 when the path leaves the errands'
// reach (it cannot: the first errand was checked reachable, but a caller's window is untrusted).
int32_t WindowLns::cost(const Goals& goals, const std::vector<grid::Cell>& path) const {
  int32_t k = 0;
  for (const grid::Cell c : path) k = goals.reached(static_cast<uint32_t>(grid_.index(c)), k);
  const int32_t h = goals.h(static_cast<uint32_t>(grid_.index(path.back())), k);
  return h < 0 ? -1 : static_cast<int32_t>(path.size()) - 1 + h;
}

// A* over (cell, t, errands reached) for t <= steps against the others' reservations; the first
// state taken at t = steps ends the search (its cost, steps + distance left, is then the least).
// False when none is reached within the expansion bound.
bool WindowLns::replan(const Goals& goals, int steps, const SpaceTimeReservations& res, Search& s,
                       std::vector<grid::Cell>& path) {
  s.clear();
  const auto push = [&](uint32_t cell, int32_t t, int32_t k, int32_t parent) {
    k = goals.reached(cell, k);
    const int32_t h = goals.h(cell, k);
    if (h < 0) return;
    s.nodes.push_back({t + h, t, h, cell, k, parent});
    s.open.push(static_cast<int32_t>(s.nodes.size() - 1));
  };
  push(goals.start, 0, 0, -1);
  const auto width = static_cast<uint32_t>(grid_.width());
  std::size_t expansions = 0;
  while (!s.open.empty() && expansions < options_.max_expansions) {
    const int32_t id = s.open.top();
    s.open.pop();
    const auto n = s.nodes[static_cast<std::size_t>(id)];
    if (!s.closed.insert((vertex_key(n.cell, n.t) << 2) | uint64_t(n.k)).second) continue;
    ++expansions;
    if (n.t == steps) {
      for (int32_t i = id; i >= 0; i = s.nodes[static_cast<std::size_t>(i)].parent) {
        const auto& m = s.nodes[static_cast<std::size_t>(i)];
        path[static_cast<std::size_t>(m.t)] = {int32_t(m.cell % width), int32_t(m.cell / width)};
      }
      stats_.expansions += expansions;
      return true;
    }
    const grid::Cell c{int32_t(n.cell % width), int32_t(n.cell / width)};
    for (const grid::Cell m : {c, grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                               grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
      if (!grid_.free(m)) continue;
      const auto mc = static_cast<uint32_t>(grid_.index(m));
      if (res.taken(mc, n.t + 1) || res.swaps(n.cell, mc, n.t)) continue;
      push(mc, n.t + 1, n.k, id);
    }
  }
  stats_.expansions += expansions;
  return false;
}

void WindowLns::improve(const WindowRequest& r, WindowPlan& plan) {
  check(r, plan);
  ++stats_.windows;
  SpaceTimeReservations res(grid_, static_cast<std::size_t>(r.steps));
  for (const auto& p : plan.paths) res.set(p, true);
  std::vector<Goals> goals;
  std::vector<std::pair<int32_t, uint32_t>> order;  // (distance left at the start, robot)
  for (uint32_t i = 0; i < r.start.size(); ++i) {
    goals.push_back(goals_of(r, i));
    const int32_t h = goals.back().cells.empty() ? -1 : goals.back().h(goals.back().start, 0);
    if (h > 0) order.emplace_back(h, i);
  }
  std::stable_sort(order.begin(), order.end(), [](auto a, auto b) { return a.first > b.first; });
  Search search;
  std::vector<grid::Cell> path;
  for (int pass = 0; pass < options_.passes; ++pass) {
    for (const auto& [h, i] : order) {
      auto& old = plan.paths[i];
      const int32_t before = cost(goals[i], old);
      res.set(old, false);
      path = old;
      ++stats_.replanned;
      if (replan(goals[i], r.steps, res, search, path) && cost(goals[i], path) < before) {
        ++stats_.improved;
        stats_.saved += before - cost(goals[i], path);
        old = path;
      }
      res.set(old, true);
    }
  }
  plan.moves = 0;
  for (const auto& p : plan.paths) {
    for (std::size_t t = 1; t < p.size(); ++t) plan.moves += p[t] != p[t - 1] ? 1 : 0;
  }
}

}  // namespace smart::planning
