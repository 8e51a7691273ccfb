#include "smart/planning/pibt.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

namespace smart::planning {

namespace {
constexpr int64_t kNoOccupant = -1;
}  // namespace

Pibt::Pibt(const grid::Grid& grid, GoalHeuristic& heuristic, uint64_t seed)
    : grid_(grid), heur_(heuristic), seed_(seed), step_(grid) {}

void Pibt::check(const WindowRequest& r) {
  if (r.goals.size() != r.start.size()) {
    throw std::invalid_argument("PIBT: " + std::to_string(r.start.size()) + " starts but " +
                                std::to_string(r.goals.size()) + " goal lists");
  }
  if (r.steps < 1) throw std::invalid_argument("PIBT: a window needs at least one step");
  std::vector<int64_t> at(static_cast<std::size_t>(grid_.width()) * grid_.height(), kNoOccupant);
  for (std::size_t i = 0; i < r.start.size(); ++i) {
    const auto c = r.start[i];
    if (!grid_.free(c)) {
      throw std::invalid_argument("PIBT: robot " + std::to_string(i) + " starts on " +
                                  grid::to_string(c) + ", not a free cell");
    }
    if (at[grid_.index(c)] != kNoOccupant) {
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
  std::mt19937_64 rng(seed_ + 7919 * ++calls_);
  std::vector<grid::Cell> from = r.start;
  std::vector<std::size_t> next_goal(robots, 0);
  WindowPlan out;
  out.paths.assign(robots, {});
  for (std::size_t i = 0; i < robots; ++i) out.paths[i].push_back(r.start[i]);
  std::vector<uint32_t> order(robots);
  for (int t = 0; t < r.steps; ++t) {
    step_.begin(from);
    for (std::size_t i = 0; i < robots; ++i) {
      // Goals reached (at the step's start) advance to the next errand.
      while (next_goal[i] < r.goals[i].size() && r.goals[i][next_goal[i]] == from[i]) {
        ++next_goal[i];
        priority_[i] = tie_[i];
        if (next_goal[i] < r.goals[i].size() &&
            !heur_.aim(static_cast<uint32_t>(i), from[i], r.goals[i][next_goal[i]])) {
          next_goal[i] = r.goals[i].size();  // out of reach: hold here (see check())
        }
      }
      const bool has_goal = next_goal[i] < r.goals[i].size();
      heur_.aim(static_cast<uint32_t>(i), from[i], has_goal ? r.goals[i][next_goal[i]] : from[i]);
      if (has_goal) priority_[i] += 1;
    }
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return priority_[a] > priority_[b]; });
    for (const uint32_t i : order) step_.plan(i, heur_, rng);  // cannot fail: no fix()
    for (std::size_t i = 0; i < robots; ++i) {
      if (step_.to()[i] != from[i]) ++out.moves;
      out.paths[i].push_back(step_.to()[i]);
    }
    from = step_.to();
    step_.end();
  }
  return out;
}

}  // namespace smart::planning
