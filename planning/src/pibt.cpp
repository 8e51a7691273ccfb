#include "smart/planning/pibt.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

namespace smart::planning {

namespace {
constexpr int64_t kNobody = -1;
}  // namespace

// One timestep's bookkeeping (the paper's occupied_now / occupied_next).
struct Pibt::Step {
  std::vector<grid::Cell> from, to;
  std::vector<uint8_t> planned;
  std::vector<int64_t> now, next;  // by cell index: robot there now / reserved next
  std::vector<grid::Cell> goal;    // per robot, this step's goal
  std::mt19937_64 rng;
};

Pibt::Pibt(const grid::Grid& grid, GoalHeuristic& heuristic, uint64_t seed)
    : grid_(grid), heur_(heuristic), seed_(seed) {}

void Pibt::check(const WindowRequest& r) {
  if (r.goals.size() != r.start.size()) {
    throw std::invalid_argument("PIBT: " + std::to_string(r.start.size()) + " starts but " +
                                std::to_string(r.goals.size()) + " goal lists");
  }
  if (r.steps < 1) throw std::invalid_argument("PIBT: a window needs at least one step");
  std::vector<int64_t> at(static_cast<std::size_t>(grid_.width()) * grid_.height(), kNobody);
  for (std::size_t i = 0; i < r.start.size(); ++i) {
    const auto c = r.start[i];
    if (!grid_.free(c)) {
      throw std::invalid_argument("PIBT: robot " + std::to_string(i) + " starts on " +
                                  grid::to_string(c) + ", not a free cell");
    }
    if (at[grid_.index(c)] != kNobody) {
      throw std::invalid_argument("PIBT: robots " + std::to_string(at[grid_.index(c)]) + " and " +
                                  std::to_string(i) + " both start on " + grid::to_string(c));
    }
    at[grid_.index(c)] = static_cast<int64_t>(i);
    // The first goal only: a table per later errand would cost a BFS each (thousands on large
    // maps) for goals a window rarely reaches; a later errand out of reach is held, not chased.
    if (!r.goals[i].empty()) {
      const auto goal = r.goals[i].front();
      if (!grid_.free(goal) || !heur_.aim(static_cast<uint32_t>(i), c, goal)) {
        throw std::invalid_argument("PIBT: robot " + std::to_string(i) + " at " +
                                    grid::to_string(c) + " cannot reach its goal " +
                                    grid::to_string(goal));
      }
    }
  }
}

// Algorithm 2 (PIBT): plan `robot`'s next cell; `asker` is the robot that inherited to it.
bool Pibt::push(Step& s, uint32_t robot, int64_t asker) {
  const grid::Cell here = s.from[robot];
  std::array<grid::Cell, 5> c{here, grid::Cell{here.x + 1, here.y}, grid::Cell{here.x - 1, here.y},
                              grid::Cell{here.x, here.y + 1}, grid::Cell{here.x, here.y - 1}};
  std::size_t n = 1;
  for (std::size_t k = 1; k < 5; ++k) {
    if (grid_.free(c[k])) c[n++] = c[k];
  }
  // Random tie order first, then a stable sort by distance (ties broken at random, seeded).
  for (std::size_t k = n - 1; k > 0; --k) std::swap(c[k], c[s.rng() % (k + 1)]);
  std::array<int64_t, 5> rank{};
  for (std::size_t k = 0; k < n; ++k) rank[k] = heur_.rank(robot, c[k]);
  std::array<std::size_t, 5> by{0, 1, 2, 3, 4};
  std::stable_sort(by.begin(), by.begin() + static_cast<long>(n),
                   [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
  const auto shuffled = c;
  for (std::size_t k = 0; k < n; ++k) c[k] = shuffled[by[k]];
  for (std::size_t k = 0; k < n; ++k) {
    const auto v = grid_.index(c[k]);
    if (s.next[v] != kNobody) continue;                                                 // vertex
    if (asker != kNobody && c[k] == s.from[static_cast<std::size_t>(asker)]) continue;  // swap
    s.next[v] = robot;
    s.to[robot] = c[k];
    s.planned[robot] = 1;
    const int64_t other = s.now[v];
    if (other == kNobody || other == robot) return true;
    if (!s.planned[static_cast<std::size_t>(other)] &&
        !push(s, static_cast<uint32_t>(other), robot)) {
      continue;  // the robot there cannot move: try the next candidate
    }
    return true;
  }
  s.next[grid_.index(here)] = robot;  // nothing worked: stay
  s.to[robot] = here;
  s.planned[robot] = 1;
  return false;
}

WindowPlan Pibt::plan(const WindowRequest& r) {
  if (r.goals.size() == r.start.size()) {
    std::vector<grid::Cell> first(r.start.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
      first[i] = r.goals[i].empty() ? r.start[i] : r.goals[i].front();
    }
    heur_.new_window(r.start, first);
  }
  check(r);
  const std::size_t robots = r.start.size();
  if (priority_.size() != robots) {
    std::mt19937_64 rng(seed_);
    tie_.resize(robots);
    for (auto& t : tie_) t = static_cast<double>(rng() >> 11) / 9007199254740992.0;  // [0, 1)
    priority_ = tie_;
  }
  const std::size_t cells = static_cast<std::size_t>(grid_.width()) * grid_.height();
  Step s{r.start,
         r.start,
         {},
         std::vector<int64_t>(cells, kNobody),
         std::vector<int64_t>(cells, kNobody),
         {},
         std::mt19937_64(seed_ + 7919 * ++calls_)};
  std::vector<std::size_t> next_goal(robots, 0);
  WindowPlan out;
  out.paths.assign(robots, {});
  for (std::size_t i = 0; i < robots; ++i) out.paths[i].push_back(r.start[i]);
  std::vector<uint32_t> order(robots);
  for (int t = 0; t < r.steps; ++t) {
    s.goal.resize(robots);
    for (std::size_t i = 0; i < robots; ++i) {
      // Goals reached (at the step's start) advance to the next errand.
      while (next_goal[i] < r.goals[i].size() && r.goals[i][next_goal[i]] == s.from[i]) {
        ++next_goal[i];
        priority_[i] = tie_[i];
        if (next_goal[i] < r.goals[i].size() &&
            !heur_.aim(static_cast<uint32_t>(i), s.from[i], r.goals[i][next_goal[i]])) {
          next_goal[i] = r.goals[i].size();  // out of reach: hold here (see check())
        }
      }
      const bool has_goal = next_goal[i] < r.goals[i].size();
      s.goal[i] = has_goal ? r.goals[i][next_goal[i]] : s.from[i];
      heur_.aim(static_cast<uint32_t>(i), s.from[i], s.goal[i]);
      if (has_goal) priority_[i] += 1;
      s.now[grid_.index(s.from[i])] = static_cast<int64_t>(i);
    }
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return priority_[a] > priority_[b]; });
    s.planned.assign(robots, 0);
    for (const uint32_t i : order) {
      if (!s.planned[i]) push(s, i, kNobody);
    }
    for (std::size_t i = 0; i < robots; ++i) {
      s.now[grid_.index(s.from[i])] = kNobody;
      s.next[grid_.index(s.to[i])] = kNobody;
      if (s.to[i] != s.from[i]) ++out.moves;
      out.paths[i].push_back(s.to[i]);
    }
    s.from = s.to;
  }
  return out;
}

}  // namespace smart::planning
