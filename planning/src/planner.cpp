#include "smart/planning/planner.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <numeric>
#include <queue>
#include <random>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "smart/planning/generators.hpp"

namespace smart::planning {

namespace {

struct Reservations {
  std::unordered_set<uint64_t> vertex;  // (t << 32) | cell
  std::unordered_set<uint64_t> edge;    // t (24 bits) | from (20) | to (20): a move during [t, t+1]
  std::vector<int32_t> parked_from;     // cell -> time from which a robot sits there for good
  std::vector<int32_t> last_time;       // cell -> latest time any robot is there
  int32_t horizon = 0;

  explicit Reservations(std::size_t cells) : parked_from(cells, INT32_MAX), last_time(cells, -1) {}
  static uint64_t vkey(uint32_t cell, int32_t t) { return (uint64_t(uint32_t(t)) << 32) | cell; }
  static uint64_t ekey(uint32_t from, uint32_t to, int32_t t) {
    return (uint64_t(uint32_t(t)) << 40) | (uint64_t(from) << 20) | to;
  }
  bool vertex_free(uint32_t cell, int32_t t) const {
    return parked_from[cell] > t && !vertex.count(vkey(cell, t));
  }
  void reserve_path(const std::vector<uint32_t>& path) {
    for (std::size_t t = 0; t < path.size(); ++t) {
      vertex.insert(vkey(path[t], int32_t(t)));
      last_time[path[t]] = std::max(last_time[path[t]], int32_t(t));
      if (t + 1 < path.size() && path[t] != path[t + 1]) {
        edge.insert(ekey(path[t], path[t + 1], int32_t(t)));
      }
    }
    parked_from[path.back()] = int32_t(path.size() - 1);
    horizon = std::max(horizon, int32_t(path.size()));
  }
};

// Space-time A*; empty result when no path within the horizon.
std::vector<uint32_t> space_time_astar(const grid::Grid& g, const Reservations& res, uint32_t start,
                                       uint32_t goal, const std::vector<int32_t>& h,
                                       int32_t max_t) {
  struct Node {
    int32_t f, t;
    uint32_t cell;
    int64_t parent;
    int32_t d;  // distance to goal
  };
  std::vector<Node> nodes;
  // Lowest f; among equals the one nearest its goal, then the deepest.
  auto cmp = [&](uint32_t a, uint32_t b) {
    const auto &x = nodes[a], &y = nodes[b];
    if (x.f != y.f) return x.f > y.f;
    if (x.d != y.d) return x.d > y.d;
    return x.t < y.t;
  };
  // Admissible: it cannot park before its goal is last used by an earlier robot.
  const int32_t park_after = res.last_time[goal] + 1;
  auto f_of = [&](int32_t t, uint32_t cell) { return std::max(t + h[cell], park_after); };
  std::priority_queue<uint32_t, std::vector<uint32_t>, decltype(cmp)> open(cmp);
  std::unordered_set<uint64_t> closed;
  nodes.push_back({f_of(0, start), 0, start, -1, h[start]});
  open.push(0);
  const auto W = static_cast<uint32_t>(g.width());
  std::size_t expansions = 0;
  while (!open.empty()) {
    const uint32_t id = open.top();
    open.pop();
    const Node n = nodes[id];
    if (!closed.insert(Reservations::vkey(n.cell, n.t)).second) continue;
    if (n.cell == goal && n.t > res.last_time[goal]) {
      std::vector<uint32_t> path;
      for (int64_t i = id; i >= 0; i = nodes[static_cast<std::size_t>(i)].parent) {
        path.push_back(nodes[static_cast<std::size_t>(i)].cell);
      }
      std::reverse(path.begin(), path.end());
      return path;
    }
    if (n.t >= max_t || ++expansions > 400'000) continue;
    const grid::Cell c{int32_t(n.cell % W), int32_t(n.cell / W)};
    for (const grid::Cell m : {c, grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                               grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
      if (!g.free(m)) continue;
      const auto mc = static_cast<uint32_t>(g.index(m));
      const int32_t t = n.t + 1;
      if (h[mc] < 0 || !res.vertex_free(mc, t)) continue;
      if (mc != n.cell && res.edge.count(Reservations::ekey(mc, n.cell, n.t))) continue;  // swap
      if (closed.count(Reservations::vkey(mc, t))) continue;
      nodes.push_back({f_of(t, mc), t, mc, id, h[mc]});
      open.push(static_cast<uint32_t>(nodes.size() - 1));
    }
  }
  return {};
}

}  // namespace

PlannerResult plan_prioritized(const grid::Grid& g, const grid::Scenario& scen,
                               const PlannerOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  PlannerResult out;
  const std::size_t n = scen.agents.size();
  if (static_cast<std::size_t>(g.width()) * g.height() >= (1u << 20)) {
    out.error = "map too large for the built-in planner (at most 2^20 cells)";
    return out;
  }
  std::vector<std::vector<int32_t>> dist(n);
  for (std::size_t i = 0; i < n; ++i) {
    dist[i] = bfs_distances(g, scen.agents[i].goal);
    if (dist[i][g.index(scen.agents[i].start)] < 0) {
      out.error = "robot " + std::to_string(i) + " cannot reach its goal " +
                  grid::to_string(scen.agents[i].goal) + " from " +
                  grid::to_string(scen.agents[i].start);
      return out;
    }
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return dist[a][g.index(scen.agents[a].start)] > dist[b][g.index(scen.agents[b].start)];
  });
  std::mt19937_64 rng(o.seed);
  for (int attempt = 0; attempt <= o.restarts; ++attempt) {
    out.restarts_used = attempt;
    Reservations res(static_cast<std::size_t>(g.width()) * g.height());
    for (const auto& a : scen.agents)
      res.vertex.insert(Reservations::vkey(uint32_t(g.index(a.start)), 0));
    std::vector<std::vector<uint32_t>> paths(n);
    bool ok = true;
    for (const std::size_t i : order) {
      const auto start = uint32_t(g.index(scen.agents[i].start));
      const auto goal = uint32_t(g.index(scen.agents[i].goal));
      res.vertex.erase(Reservations::vkey(start, 0));  // its own start
      const int32_t max_t = res.horizon + dist[i][start] + (g.width() + g.height()) / 2 + 32;
      paths[i] = space_time_astar(g, res, start, goal, dist[i], max_t);
      if (paths[i].empty()) {
        ok = false;
        out.error = "robot " + std::to_string(i) + " found no path in priority order attempt " +
                    std::to_string(attempt);
        // The robot that failed goes first next time (it was blocked by earlier robots, most
        // often by one parked in a one-cell aisle); every few attempts also shake the rest.
        order.erase(std::find(order.begin(), order.end(), i));
        if (attempt % 5 == 4) std::shuffle(order.begin(), order.end(), rng);
        order.insert(order.begin(), i);
        break;
      }
      res.reserve_path(paths[i]);
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (elapsed > o.time_limit_s) {
        out.error = "time limit of " + std::to_string(o.time_limit_s) + " s reached";
        out.runtime_s = elapsed;
        return out;
      }
    }
    if (!ok) continue;
    const auto W = static_cast<uint32_t>(g.width());
    out.plan.source = "<built-in planner>";
    out.plan.format = grid::PlanFormat::kSmart;
    out.plan.axis = grid::AxisOrder::kXY;
    out.plan.timed = true;
    for (std::size_t i = 0; i < n; ++i) {
      grid::RobotPath rp{static_cast<int>(i), static_cast<int>(i) + 1, {}};
      for (std::size_t t = 0; t < paths[i].size(); ++t) {
        rp.steps.push_back({{int32_t(paths[i][t] % W), int32_t(paths[i][t] / W)},
                            double(t),
                            static_cast<int>(i) + 1});
      }
      out.plan.paths.push_back(std::move(rp));
    }
    out.solved = true;
    out.error.clear();
    break;
  }
  out.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

grid::Plan plan_from_timesteps(const std::vector<std::vector<grid::Cell>>& paths,
                               const std::string& source) {
  grid::Plan plan;
  plan.source = source;
  plan.format = grid::PlanFormat::kSmart;
  plan.axis = grid::AxisOrder::kXY;
  plan.timed = true;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const int robot = static_cast<int>(i);
    grid::RobotPath rp{robot, robot + 1, {}};
    // The last move's cell closes the path: trailing waits on the goal say nothing.
    std::size_t last = paths[i].size() - 1;
    while (last > 0 && paths[i][last - 1] == paths[i][last]) --last;
    for (std::size_t t = 0; t <= last; ++t) rp.steps.push_back({paths[i][t], double(t), robot + 1});
    plan.paths.push_back(std::move(rp));
  }
  return plan;
}

std::vector<std::vector<grid::Cell>> timesteps_of(const grid::Plan& plan) {
  std::vector<std::vector<grid::Cell>> out;
  for (const auto& p : plan.paths) {
    out.emplace_back();
    for (const auto& s : p.steps) out.back().push_back(s.cell);
  }
  return out;
}

std::string to_smart_plan_text(const grid::Plan& plan) {
  std::ostringstream s;
  s << "# axis: xy\n";  // read back without --axis (monitor/plan_reader.hpp)
  for (const auto& p : plan.paths) {
    s << "Agent " << p.robot << ":";
    for (const auto& st : p.steps)
      s << "(" << st.cell.x << "," << st.cell.y << "," << st.time << ")->";
    s << "\n";
  }
  return s.str();
}

}  // namespace smart::planning
