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
  // below 65 535, improve_plan checks; ids below 2^31, push stops there).
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

// Space-time A* from the path's start to its goal for an arrival before the path's own: f = t +
// distance, only f < the old arrival pushed. Empty when there is none (within `max_expansions`).
// A state is pushed once: pushed again it would have the same f and t and a later id, so it
// would be popped after the first and skipped; the states expanded are the same, in the same
// order, as with a closed list.
Path earlier_path(const grid::Grid& g, const SpaceTimeReservations& res, const Path& old,
                  const std::vector<int32_t>& h, std::size_t max_expansions, PathSearch& s,
                  std::size_t& expansions) {
  const auto bound = static_cast<int32_t>(old.size() - 1);
  const auto goal = g.index(old.back());
  const int32_t last = res.last_use(goal);
  s.clear();
  const auto push = [&](std::size_t cell, int32_t t, int32_t parent) {
    const int32_t f = t + h[cell];
    if (h[cell] < 0 || f >= bound || s.seen(cell, t)) return;
    s.see(cell, t);
    s.push(static_cast<uint32_t>(cell), t, f, parent);
  };
  push(g.index(old.front()), 0, -1);
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

}  // namespace

PlanLnsStats improve_plan(const grid::Grid& grid, std::vector<Path>& paths, DistanceCache& tables,
                          const PlanLnsOptions& options) {
  if (static_cast<std::size_t>(grid.width()) * static_cast<std::size_t>(grid.height()) >=
      (std::size_t{1} << 24)) {
    throw std::invalid_argument("plan LNS: maps of 16 M cells or more are not supported");
  }
  std::size_t horizon = 0;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (paths[i].empty()) {
      throw std::invalid_argument("plan LNS: robot " + std::to_string(i) + " has an empty path");
    }
    horizon = std::max(horizon, paths[i].size());
  }
  if (horizon >= 65535) throw std::invalid_argument("plan LNS: plans of 65535 steps or more");
  SpaceTimeReservations res(grid, horizon);
  for (const auto& p : paths) res.set(p, true, true);
  std::vector<std::pair<int64_t, uint32_t>> order;  // (delay, robot): most delayed first
  for (uint32_t i = 0; i < paths.size(); ++i) {
    const int32_t d = tables.distance(paths[i].front(), paths[i].back());
    const auto delay = static_cast<int64_t>(paths[i].size() - 1) - d;
    if (d >= 0 && delay > 0) order.emplace_back(delay, i);
  }
  std::stable_sort(order.begin(), order.end(), [](auto a, auto b) { return a.first > b.first; });
  PlanLnsStats st;
  PathSearch search(
      static_cast<std::size_t>(grid.width()) * static_cast<std::size_t>(grid.height()), horizon);
  for (int pass = 0; pass < options.passes; ++pass) {
    for (const auto& [delay, i] : order) {
      auto& old = paths[i];
      res.set(old, false, true);
      ++st.replanned;
      const auto table = tables.to(old.back());
      auto better =
          earlier_path(grid, res, old, *table, options.max_expansions, search, st.expansions);
      if (!better.empty()) {
        ++st.improved;
        st.saved += static_cast<int64_t>(old.size()) - static_cast<int64_t>(better.size());
        old = std::move(better);
      }
      res.set(old, true, true);
    }
  }
  return st;
}

}  // namespace smart::planning
