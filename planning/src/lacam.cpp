#include "smart/planning/lacam.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "smart/planning/distance_cache.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "smart/planning/pibt_step.hpp"

namespace smart::planning {

namespace {

using Config = std::vector<grid::Cell>;

struct Constraint {
  uint32_t robot;
  grid::Cell to;
};

// A configuration kept (the paper's high-level node): its robots' order for PIBT and the
// low-level nodes (constraint lists, each one robot longer than its parent) not yet tried.
struct HighNode {
  Config config;
  std::vector<double> priority;
  std::vector<uint32_t> order;
  std::deque<std::vector<Constraint>> tree;
  int64_t parent = -1;
};

uint64_t hash_of(const Config& c) {  // FNV-1a over the cells
  uint64_t h = 0xcbf29ce484222325ULL;
  for (const auto& cell : c) {
    h = (h ^ static_cast<uint32_t>(cell.x)) * 0x100000001b3ULL;
    h = (h ^ static_cast<uint32_t>(cell.y)) * 0x100000001b3ULL;
  }
  return h;
}

class Search {
 public:
  Search(const grid::Grid& grid, const grid::Scenario& scen, const LacamOptions& o)
      : grid_(grid), o_(o), tables_(grid), heur_(tables_), step_(grid), rng_(o.seed) {
    for (const auto& a : scen.agents) {
      start_.push_back(a.start);
      goal_.push_back(a.goal);
    }
    if (o.swap) step_.enable_swaps(goal_);
  }

  PlannerResult run(LacamStats& stats);

 private:
  void check();
  std::size_t keep(Config config, int64_t parent);
  void branch(HighNode& h, const std::vector<Constraint>& fixed);
  bool successor(const HighNode& h, const std::vector<Constraint>& fixed, Config& out);
  int64_t find(const Config& c) const;
  std::vector<std::vector<grid::Cell>> paths(std::size_t last) const;
  std::size_t bytes_per_node() const { return start_.size() * (sizeof(grid::Cell) + 12) + 160; }

  const grid::Grid& grid_;
  LacamOptions o_;
  DistanceCache tables_;
  TableHeuristic heur_;
  PibtStep step_;
  std::mt19937_64 rng_;
  Config start_, goal_;
  std::deque<HighNode> nodes_;  // references stay valid as it grows
  std::unordered_multimap<uint64_t, std::size_t> explored_;
  std::size_t low_bytes_ = 0;  // constraint lists waiting in the nodes' trees
};

void Search::check() {
  std::unordered_map<std::size_t, std::size_t> at, bound;
  for (std::size_t i = 0; i < start_.size(); ++i) {
    const std::string who = "LaCAM: robot " + std::to_string(i);
    if (!grid_.free(start_[i]) || !grid_.free(goal_[i])) {
      throw std::invalid_argument(who + ": start " + grid::to_string(start_[i]) + " or goal " +
                                  grid::to_string(goal_[i]) + " is not a free cell");
    }
    if (const auto [it, fresh] = at.emplace(grid_.index(start_[i]), i); !fresh) {
      throw std::invalid_argument(who + " starts on " + grid::to_string(start_[i]) + " as robot " +
                                  std::to_string(it->second) + " does");
    }
    if (const auto [it, fresh] = bound.emplace(grid_.index(goal_[i]), i); !fresh) {
      throw std::invalid_argument(who + " has the goal " + grid::to_string(goal_[i]) +
                                  " of robot " + std::to_string(it->second) +
                                  ": goals must differ");
    }
    if (!heur_.aim(static_cast<uint32_t>(i), start_[i], goal_[i])) {
      throw std::invalid_argument(who + " at " + grid::to_string(start_[i]) +
                                  " cannot reach its goal " + grid::to_string(goal_[i]));
    }
  }
}

// A new high-level node, its priorities from its parent's (the paper's code: +1 away from the
// goal, the fraction alone on it) and its tree's root, the node without constraints.
std::size_t Search::keep(Config config, int64_t parent) {
  const std::size_t n = config.size();
  HighNode h{std::move(config), std::vector<double>(n), std::vector<uint32_t>(n), {}, parent};
  for (std::size_t i = 0; i < n; ++i) {
    const int32_t d = tables_.distance(h.config[i], goal_[i]);
    if (parent < 0) {
      h.priority[i] = static_cast<double>(d) / static_cast<double>(n);
    } else {
      const double p = nodes_[static_cast<std::size_t>(parent)].priority[i];
      h.priority[i] = d != 0 ? p + 1 : p - std::floor(p);
    }
  }
  std::iota(h.order.begin(), h.order.end(), 0);
  std::stable_sort(h.order.begin(), h.order.end(),
                   [&](uint32_t a, uint32_t b) { return h.priority[a] > h.priority[b]; });
  h.tree.emplace_back();
  explored_.emplace(hash_of(h.config), nodes_.size());
  nodes_.push_back(std::move(h));
  return nodes_.size() - 1;
}

// The low-level expansion: the next robot in order gets each of its cells, shuffled (seeded).
void Search::branch(HighNode& h, const std::vector<Constraint>& fixed) {
  if (fixed.size() >= h.order.size()) return;
  const uint32_t i = h.order[fixed.size()];
  const grid::Cell c = h.config[i];
  std::vector<grid::Cell> cells{c};
  for (const grid::Cell n : {grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                             grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
    if (grid_.free(n)) cells.push_back(n);
  }
  std::shuffle(cells.begin(), cells.end(), rng_);
  for (const grid::Cell to : cells) {
    auto more = fixed;
    more.push_back({i, to});
    low_bytes_ += more.capacity() * sizeof(Constraint) + 32;
    h.tree.push_back(std::move(more));
  }
}

// Algorithm 1's configuration generator: PIBT under the node's constraints.
bool Search::successor(const HighNode& h, const std::vector<Constraint>& fixed, Config& out) {
  step_.begin(h.config);
  bool ok = std::all_of(fixed.begin(), fixed.end(),
                        [&](const Constraint& c) { return step_.fix(c.robot, c.to); });
  for (std::size_t k = 0; ok && k < h.order.size(); ++k) ok = step_.plan(h.order[k], heur_, rng_);
  if (ok) out = step_.to();
  step_.end();
  return ok;
}

int64_t Search::find(const Config& c) const {
  const auto [first, last] = explored_.equal_range(hash_of(c));
  for (auto it = first; it != last; ++it) {
    if (nodes_[it->second].config == c) return static_cast<int64_t>(it->second);
  }
  return -1;
}

std::vector<std::vector<grid::Cell>> Search::paths(std::size_t last) const {
  std::vector<std::size_t> chain;
  for (auto k = static_cast<int64_t>(last); k >= 0;
       k = nodes_[static_cast<std::size_t>(k)].parent) {
    chain.push_back(static_cast<std::size_t>(k));
  }
  std::reverse(chain.begin(), chain.end());
  std::vector<std::vector<grid::Cell>> out(start_.size());
  for (const std::size_t k : chain) {
    for (std::size_t i = 0; i < out.size(); ++i) out[i].push_back(nodes_[k].config[i]);
  }
  return out;
}

// Algorithm 1 (LaCAM): depth-first over configurations; a configuration met again is searched
// from again (pushed back on the stack) with its next low-level node.
PlannerResult Search::run(LacamStats& stats) {
  PlannerResult out;
  const auto t0 = std::chrono::steady_clock::now();
  check();
  const std::size_t budget =
      o_.max_configurations > 0 ? o_.max_configurations * bytes_per_node() : std::size_t{1} << 30;
  std::vector<std::size_t> open{keep(start_, -1)};
  while (!open.empty()) {
    out.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (out.runtime_s > o_.time_limit_s || nodes_.size() * bytes_per_node() + low_bytes_ > budget) {
      out.error = (out.runtime_s > o_.time_limit_s
                       ? "time limit of " + std::to_string(o_.time_limit_s) + " s"
                       : "memory budget") +
                  " reached after " + std::to_string(nodes_.size()) + " configurations";
      break;
    }
    const std::size_t top = open.back();
    HighNode& h = nodes_[top];
    if (h.config == goal_) {
      out.plan = plan_from_timesteps(paths(top), "<built-in planner: lacam>");
      out.solved = true;
      break;
    }
    if (h.tree.empty()) {
      open.pop_back();
      continue;
    }
    const std::vector<Constraint> fixed = std::move(h.tree.front());
    h.tree.pop_front();
    low_bytes_ -= std::min(low_bytes_, fixed.capacity() * sizeof(Constraint) + 32);
    ++stats.expansions;
    branch(h, fixed);
    Config next;
    if (!successor(h, fixed, next)) continue;
    const int64_t seen = find(next);
    open.push_back(seen >= 0 ? static_cast<std::size_t>(seen)
                             : keep(std::move(next), static_cast<int64_t>(top)));
  }
  if (open.empty()) out.error = "no plan exists: every configuration reachable was searched";
  stats.configurations = nodes_.size();
  return out;
}

}  // namespace

PlannerResult plan_lacam(const grid::Grid& grid, const grid::Scenario& scen, const LacamOptions& o,
                         LacamStats* stats) {
  LacamStats local;
  return Search(grid, scen, o).run(stats != nullptr ? *stats : local);
}

}  // namespace smart::planning
