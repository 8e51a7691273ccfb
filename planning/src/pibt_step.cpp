#include "smart/planning/pibt_step.hpp"

#include <algorithm>
#include <array>

namespace smart::planning {

namespace {
constexpr int64_t kNobody = -1;
}  // namespace

PibtStep::PibtStep(const grid::Grid& grid)
    : grid_(grid),
      now_(static_cast<std::size_t>(grid.width()) * grid.height(), kNobody),
      next_(now_.size(), kNobody) {}

void PibtStep::begin(const std::vector<grid::Cell>& from) {
  from_ = from;
  to_ = from;
  planned_.assign(from.size(), 0);
  for (std::size_t i = 0; i < from.size(); ++i) {
    now_[grid_.index(from[i])] = static_cast<int64_t>(i);
  }
}

void PibtStep::end() {
  for (std::size_t i = 0; i < from_.size(); ++i) {
    now_[grid_.index(from_[i])] = kNobody;
    next_[grid_.index(to_[i])] = kNobody;
  }
}

bool PibtStep::fix(uint32_t robot, grid::Cell to) {
  const auto v = grid_.index(to);
  if (next_[v] != kNobody) return false;  // vertex conflict
  const int64_t there = now_[v];
  if (there != kNobody && there != robot && planned_[static_cast<std::size_t>(there)] &&
      to_[static_cast<std::size_t>(there)] == from_[robot]) {
    return false;  // swap
  }
  next_[v] = robot;
  to_[robot] = to;
  planned_[robot] = 1;
  return true;
}

bool PibtStep::plan(uint32_t robot, GoalHeuristic& heuristic, std::mt19937_64& rng) {
  return planned_[robot] != 0 || push(robot, heuristic, rng);
}

// Algorithm 2 (PIBT): plan `robot`'s next cell, for itself or for the robot that asked it to
// move (that robot is bound for this robot's cell: the swap check below keeps it out).
bool PibtStep::push(uint32_t robot, GoalHeuristic& heuristic, std::mt19937_64& rng) {
  const grid::Cell here = from_[robot];
  std::array<grid::Cell, 5> c{here, grid::Cell{here.x + 1, here.y}, grid::Cell{here.x - 1, here.y},
                              grid::Cell{here.x, here.y + 1}, grid::Cell{here.x, here.y - 1}};
  std::size_t n = 1;
  for (std::size_t k = 1; k < 5; ++k) {
    if (grid_.free(c[k])) c[n++] = c[k];
  }
  // Random tie order first, then a stable sort by distance (ties broken at random, seeded).
  for (std::size_t k = n - 1; k > 0; --k) std::swap(c[k], c[rng() % (k + 1)]);
  std::array<int64_t, 5> rank{};
  for (std::size_t k = 0; k < n; ++k) rank[k] = heuristic.rank(robot, c[k]);
  std::array<std::size_t, 5> by{0, 1, 2, 3, 4};
  std::stable_sort(by.begin(), by.begin() + static_cast<long>(n),
                   [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
  const auto shuffled = c;
  for (std::size_t k = 0; k < n; ++k) c[k] = shuffled[by[k]];
  for (std::size_t k = 0; k < n; ++k) {
    const auto v = grid_.index(c[k]);
    if (next_[v] != kNobody) continue;  // vertex
    const int64_t other = now_[v];
    const bool other_planned =
        other != kNobody && other != robot && planned_[static_cast<std::size_t>(other)];
    // A swap: the robot there goes to this robot's cell. Without constraints only the asker
    // can (any other robot bound there would have asked this one first).
    if (other_planned && to_[static_cast<std::size_t>(other)] == here) continue;
    next_[v] = robot;
    to_[robot] = c[k];
    planned_[robot] = 1;
    if (other == kNobody || other == robot || other_planned) return true;
    if (!push(static_cast<uint32_t>(other), heuristic, rng)) {
      continue;  // the robot there cannot move: try the next candidate
    }
    return true;
  }
  next_[grid_.index(here)] = robot;  // nothing worked: stay
  to_[robot] = here;
  planned_[robot] = 1;
  return false;
}

}  // namespace smart::planning
