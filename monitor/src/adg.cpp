#include "smart/monitor/adg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace smart::monitor {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// One robot's stay at one location: entered by `enter` (kNone: its start) and left by `leave`
// (kNone: it stays for good).
struct Occupancy {
  uint32_t location;
  double arrive;  // plan time; -1 for the start location
  uint32_t robot;
  uint32_t enter;
  uint32_t leave;
};

std::string time_text(double t) {
  std::ostringstream s;
  s << "t=" << t;
  return s.str();
}

HalfCell location_of(const Grid& grid, uint32_t index) {
  const auto w = static_cast<uint32_t>(2 * grid.width() - 1);
  return {static_cast<int32_t>(index % w), static_cast<int32_t>(index / w)};
}

void build_csr(std::size_t n, const std::vector<std::pair<uint32_t, uint32_t>>& edges, bool by_src,
               std::vector<uint32_t>& begin, std::vector<uint32_t>& list) {
  begin.assign(n + 1, 0);
  for (const auto& [u, v] : edges) ++begin[(by_src ? u : v) + 1];
  for (std::size_t i = 0; i < n; ++i) begin[i + 1] += begin[i];
  list.resize(edges.size());
  std::vector<uint32_t> fill(begin.begin(), begin.end() - 1);
  for (const auto& [u, v] : edges) list[fill[by_src ? u : v]++] = by_src ? v : u;
}

// Every stay of every robot at a location (cell or edge midpoint), robot by robot.
std::vector<Occupancy> half_cell_occupancies(const ActionPlan& ap, const Grid& grid) {
  std::vector<Occupancy> occ;
  occ.reserve(ap.moves + ap.robots());
  for (uint32_t r = 0; r < ap.robots(); ++r) {
    Occupancy cur{static_cast<uint32_t>(grid.half_index(ap.start[r])), -1.0, r, kNone, kNone};
    for (uint32_t node = ap.offset[r]; node < ap.offset[r + 1]; ++node) {
      const Action& a = ap.actions[node];
      if (a.type != ActionType::kMove) continue;
      cur.leave = node;
      occ.push_back(cur);
      cur = {static_cast<uint32_t>(grid.half_index(a.to)), a.end_time, r, node, kNone};
    }
    occ.push_back(cur);
  }
  return occ;
}

// The cells a robot standing at `h` holds (Footprint::kCells), as half-cell indices: the cell
// itself, or both cells of an edge midpoint; `n` says how many.
std::array<uint32_t, 2> held_cells(const Grid& grid, HalfCell h, std::size_t& n) {
  auto at = [&grid](int32_t x2, int32_t y2) {
    return static_cast<uint32_t>(grid.half_index({x2, y2}));
  };
  n = h.is_cell() ? 1 : 2;
  if (h.is_cell()) return {at(h.x2, h.y2), kNone};
  if (h.x2 % 2 != 0) return {at(h.x2 - 1, h.y2), at(h.x2 + 1, h.y2)};
  return {at(h.x2, h.y2 - 1), at(h.x2, h.y2 + 1)};
}

// Every stay of every robot in a cell it holds (Footprint::kCells): a move that reaches an edge
// midpoint enters the next cell, the move that leaves the midpoint leaves the previous one.
std::vector<Occupancy> cell_occupancies(const ActionPlan& ap, const Grid& grid) {
  std::vector<Occupancy> occ;
  occ.reserve(ap.moves + ap.robots());
  for (uint32_t r = 0; r < ap.robots(); ++r) {
    std::vector<Occupancy> open{
        {static_cast<uint32_t>(grid.half_index(ap.start[r])), -1.0, r, kNone, kNone}};
    for (uint32_t node = ap.offset[r]; node < ap.offset[r + 1]; ++node) {
      const Action& a = ap.actions[node];
      if (a.type != ActionType::kMove) continue;
      std::size_t n = 0;
      const auto held = held_cells(grid, a.to, n);
      const auto holds = [&](uint32_t cell) {
        return held[0] == cell || (n == 2 && held[1] == cell);
      };
      for (auto it = open.begin(); it != open.end();) {
        if (holds(it->location)) {
          ++it;
          continue;
        }
        it->leave = node;
        occ.push_back(*it);
        it = open.erase(it);
      }
      for (std::size_t i = 0; i < n; ++i) {
        const bool is_open = std::any_of(open.begin(), open.end(),
                                         [&](const Occupancy& o) { return o.location == held[i]; });
        if (!is_open) open.push_back({held[i], a.end_time, r, node, kNone});
      }
    }
    occ.insert(occ.end(), open.begin(), open.end());
  }
  return occ;
}

// Grouped by location (a counting sort keeps each robot's order); location l's occupancies are
// [start[l], start[l + 1]).
std::vector<Occupancy> by_location(const std::vector<Occupancy>& occ, std::size_t locations,
                                   std::vector<uint32_t>& start) {
  start.assign(locations + 1, 0);
  for (const auto& o : occ) ++start[o.location + 1];
  for (std::size_t i = 0; i < locations; ++i) start[i + 1] += start[i];
  std::vector<Occupancy> sorted(occ.size());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (const auto& o : occ) sorted[fill[o.location]++] = o;
  return sorted;
}

// Every stay, grouped by location and in passing order (plan arrival, then robot); location l's
// stays are [start[l], start[l + 1]).
std::vector<Occupancy> passing_order(const ActionPlan& ap, const Grid& grid, Footprint footprint,
                                     std::vector<uint32_t>& start) {
  std::vector<Occupancy> sorted = by_location(
      footprint == Footprint::kCells ? cell_occupancies(ap, grid) : half_cell_occupancies(ap, grid),
      grid.half_cell_count(), start);
  for (std::size_t loc = 0; loc + 1 < start.size(); ++loc) {
    std::sort(sorted.begin() + start[loc], sorted.begin() + start[loc + 1],
              [](const Occupancy& x, const Occupancy& y) {
                return x.arrive != y.arrive ? x.arrive < y.arrive : x.robot < y.robot;
              });
  }
  return sorted;
}

}  // namespace

PassingOrders passing_orders(const ActionPlan& actions, const Grid& grid, Footprint footprint) {
  PassingOrders out;
  const auto sorted = passing_order(actions, grid, footprint, out.begin);
  out.stays.reserve(sorted.size());
  for (const auto& o : sorted) out.stays.push_back({o.robot, o.enter, o.leave});
  return out;
}

std::optional<Footprint> footprint_for(double radius_m, double cell_m) {
  if (4 * radius_m <= cell_m) return Footprint::kHalfCells;
  if (2 * radius_m < cell_m) return Footprint::kCells;
  return std::nullopt;
}

std::string to_string(Footprint f) { return f == Footprint::kCells ? "cells" : "half cells"; }

Adg build_adg(const ActionPlan& ap, const Grid& grid, const std::string& source,
              std::vector<Problem>& problems, Footprint footprint) {
  Adg adg;
  adg.footprint = footprint;
  const std::size_t n = ap.actions.size();
  const std::size_t robots = ap.robots();

  const std::size_t locations = grid.half_cell_count();
  std::vector<uint32_t> start;
  const std::vector<Occupancy> sorted = passing_order(ap, grid, footprint, start);

  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(ap.moves);
  std::vector<uint32_t> same_robot_seen(robots, 0), stamp(robots, kNone);
  for (std::size_t loc = 0; loc < locations; ++loc) {
    const auto b = sorted.begin() + start[loc], e = sorted.begin() + start[loc + 1];
    if (b == e) continue;
    ++adg.stats.locations;
    std::size_t index = 0;
    for (auto it = b; it != e; ++it, ++index) {
      // All-pairs rule: one edge from every earlier occupancy of another robot.
      if (stamp[it->robot] != loc) {
        stamp[it->robot] = static_cast<uint32_t>(loc);
        same_robot_seen[it->robot] = 0;
      }
      adg.stats.type2_all_pairs += index - same_robot_seen[it->robot];
      ++same_robot_seen[it->robot];
      if (it == b) continue;
      const Occupancy& p = *(it - 1);
      const Occupancy& q = *it;
      if (p.robot == q.robot) continue;
      const auto where = to_string(location_of(grid, static_cast<uint32_t>(loc)));
      if (p.leave == kNone) {
        problems.push_back({source, 0, static_cast<int>(q.robot),
                            "enters " + where + " at " + time_text(q.arrive) + " after robot " +
                                std::to_string(p.robot) +
                                " parked there for good; the plan is invalid"});
        continue;
      }
      if (q.enter == kNone) {
        problems.push_back({source, 0, static_cast<int>(q.robot),
                            "starts at " + where + " where robot " + std::to_string(p.robot) +
                                " also starts; the plan is invalid"});
        continue;
      }
      edges.emplace_back(p.leave, q.enter);
    }
  }

  build_csr(n, edges, true, adg.out_begin, adg.out);
  build_csr(n, edges, false, adg.in_begin, adg.in);
  adg.stats.nodes = n;
  adg.stats.type1 = 0;
  for (uint32_t r = 0; r < robots; ++r) adg.stats.type1 += ap.count(r) > 0 ? ap.count(r) - 1 : 0;
  adg.stats.type2 = edges.size();
  adg.stats.moves = ap.moves;
  adg.stats.rotations = ap.rotations;
  return adg;
}

Adg adg_of_orders(const PassingOrders& orders, const ActionPlan& actions, Footprint footprint) {
  Adg adg;
  adg.footprint = footprint;
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (std::size_t loc = 0; loc + 1 < orders.begin.size(); ++loc) {
    for (uint32_t k = orders.begin[loc] + 1; k < orders.begin[loc + 1]; ++k) {
      const Stay& p = orders.stays[k - 1];
      const Stay& q = orders.stays[k];
      if (p.robot != q.robot && p.leave != kNoAction && q.enter != kNoAction) {
        edges.emplace_back(p.leave, q.enter);
      }
    }
  }
  const std::size_t n = actions.actions.size();
  build_csr(n, edges, true, adg.out_begin, adg.out);
  build_csr(n, edges, false, adg.in_begin, adg.in);
  adg.stats.nodes = n;
  adg.stats.type2 = edges.size();
  return adg;
}

std::size_t apply_switches(PassingOrders& orders, const std::vector<PassingSwitch>& switches,
                           const std::vector<double>& finish_s) {
  std::size_t unmatched = 0;
  const auto entered_by = [&](uint32_t node, double t) {
    return node != kNoAction && node < finish_s.size() && !std::isnan(finish_s[node]) &&
           finish_s[node] <= t;
  };
  for (const auto& sw : switches) {
    bool matched = false;
    // size_t: location + 1 wraps for the largest uint32 (a row naming no location).
    if (std::size_t{sw.location} + 1 < orders.begin.size()) {
      for (uint32_t k = orders.begin[sw.location] + 1;
           !matched && k < orders.begin[sw.location + 1]; ++k) {
        auto& a = orders.stays[k - 1];
        auto& b = orders.stays[k];
        if (a.robot != sw.second || b.robot != sw.first) continue;
        if (sw.first_enter != kUnrecorded || sw.second_enter != kUnrecorded) {
          if (b.enter != sw.first_enter || a.enter != sw.second_enter) continue;  // those stays
        } else if (entered_by(b.enter, sw.time_s)) {
          continue;
        }
        std::swap(a, b);
        matched = true;
      }
    }
    unmatched += matched ? 0 : 1;
  }
  return unmatched;
}

// Each switch of a passing order, its location in cells (half-cell index: x2 + y2 * (2w - 1)).
results::SwitchRow switch_row(const Grid& grid, const ActionPlan* actions, const PassingSwitch& s) {
  const auto across = static_cast<uint32_t>(2 * grid.width() - 1);
  const uint32_t x2 = s.location % across, y2 = s.location / across;  // half cells
  results::SwitchRow row{s.time_s, x2 / 2.0, y2 / 2.0, s.first, s.second, {}, {}, s.anticipated};
  const auto seq = [actions](uint32_t robot, uint32_t node) -> std::optional<uint32_t> {
    if (actions == nullptr || node == kUnrecorded || robot >= actions->robots()) return {};
    return node - actions->offset[robot];
  };
  row.first_seq = seq(s.first, s.first_enter);
  row.second_seq = seq(s.second, s.second_enter);
  return row;
}

std::vector<PassingSwitch> passing_switches(const Grid& grid, const ActionPlan& actions,
                                            const std::vector<results::SwitchRow>& rows) {
  std::vector<PassingSwitch> out;
  const double w = grid.width(), h = grid.height();
  const auto none = static_cast<uint32_t>(actions.actions.size());  // no stay enters it
  const auto node = [&](uint32_t robot, const std::optional<uint32_t>& seq) {
    if (!seq) return kUnrecorded;
    return robot < actions.robots() && *seq < actions.count(robot) ? actions.offset[robot] + *seq
                                                                   : none;
  };
  for (const auto& r : rows) {
    const double x2 = 2 * r.x, y2 = 2 * r.y;
    const bool on_map =
        x2 == std::floor(x2) && y2 == std::floor(y2) && r.x <= w - 1 && r.y <= h - 1;
    const auto location = on_map ? static_cast<uint32_t>(grid.half_index(
                                       {static_cast<int32_t>(x2), static_cast<int32_t>(y2)}))
                                 : kNoAction;  // matches no location
    out.push_back({r.time_s, location, r.first, r.second, r.anticipated, node(r.first, r.first_seq),
                   node(r.second, r.second_seq)});
  }
  return out;
}

std::vector<Problem> check_acyclic(const Adg& adg, const ActionPlan& ap,
                                   const std::string& source) {
  const std::size_t n = adg.nodes();
  std::vector<uint32_t> indegree(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    indegree[v] = adg.in_begin[v + 1] - adg.in_begin[v] + (ap.actions[v].seq > 0 ? 1 : 0);
  }
  std::vector<uint32_t> queue;
  queue.reserve(n);
  for (uint32_t v = 0; v < n; ++v) {
    if (indegree[v] == 0) queue.push_back(v);
  }
  std::vector<uint8_t> done(n, 0);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const uint32_t u = queue[head];
    done[u] = 1;
    auto release = [&](uint32_t v) {
      if (--indegree[v] == 0) queue.push_back(v);
    };
    const Action& a = ap.actions[u];
    if (a.seq + 1 < ap.count(a.robot)) release(u + 1);
    for (uint32_t i = adg.out_begin[u]; i < adg.out_begin[u + 1]; ++i) release(adg.out[i]);
  }
  if (queue.size() == n) return {};

  // Walk backwards through unfinished predecessors until a node repeats: that is a cycle.
  uint32_t v = 0;
  while (done[v]) ++v;
  std::vector<uint32_t> path;
  std::vector<int64_t> position(n, -1);
  while (position[v] < 0) {
    position[v] = static_cast<int64_t>(path.size());
    path.push_back(v);
    const Action& a = ap.actions[v];
    uint32_t next = v;
    if (a.seq > 0 && !done[v - 1]) {
      next = v - 1;
    } else {
      for (uint32_t i = adg.in_begin[v]; i < adg.in_begin[v + 1]; ++i) {
        if (!done[adg.in[i]]) {
          next = adg.in[i];
          break;
        }
      }
    }
    v = next;
  }
  std::string desc;
  for (auto i = static_cast<std::size_t>(position[v]); i < path.size(); ++i) {
    const Action& a = ap.actions[path[i]];
    if (!desc.empty()) desc += " <- ";
    desc += "robot " + std::to_string(a.robot) + " action " + std::to_string(a.seq) + " (" +
            (a.type == ActionType::kMove ? "move " + to_string(a.from) + "->" + to_string(a.to)
                                         : "rotate at " + to_string(a.from)) +
            ")";
  }
  return {{source, 0, -1,
           "the action dependency graph has a cycle, so execution would deadlock: " + desc +
               "; the plan's passing order at these locations is contradictory" +
               (adg.footprint == Footprint::kCells
                    ? " for robots this wide: a robot crossing an edge holds both its cells, so "
                      "robots cannot follow each other round a loop (use smaller robots, larger "
                      "cells with --cell-m, or a plan without such loops)"
                    : "")}};
}

}  // namespace smart::monitor
