#include "smart/planning/pibt_step.hpp"

#include <algorithm>
#include <array>

namespace smart::planning {

namespace {
constexpr int64_t kNobody = -1;

std::array<grid::Cell, 4> around(grid::Cell c) {
  return {grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y}, grid::Cell{c.x, c.y + 1},
          grid::Cell{c.x, c.y - 1}};
}
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
  // Swap (LaCAM2): move away from the robot to be passed, and pull it into this cell.
  const int64_t swapper = goals_.empty() ? kNobody : swap_partner(robot, c[0], heuristic);
  if (swapper != kNobody) std::reverse(c.begin(), c.begin() + static_cast<long>(n));
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
    if (other != kNobody && other != robot && !other_planned &&
        !push(static_cast<uint32_t>(other), heuristic, rng)) {
      continue;  // the robot there cannot move: try the next candidate
    }
    const auto s = static_cast<std::size_t>(swapper);
    if (swapper != kNobody && !planned_[s] && next_[grid_.index(here)] == kNobody) {
      next_[grid_.index(here)] = swapper;  // pulled along
      to_[s] = here;
      planned_[s] = 1;
    }
    return true;
  }
  next_[grid_.index(here)] = robot;  // nothing worked: stay
  to_[robot] = here;
  planned_[robot] = 1;
  return false;
}

// The free cells around `at` a robot could step aside into, not counting `behind` nor a dead end
// where a robot stands on its goal; `ahead` is one of them (the last).
int PibtStep::corridor_step(grid::Cell at, grid::Cell behind, grid::Cell& ahead) const {
  int n = 0;
  for (const grid::Cell u : around(at)) {
    if (!grid_.free(u) || u == behind) continue;
    const int64_t r = now_[grid_.index(u)];
    int degree = 0;
    for (const grid::Cell w : around(u)) degree += grid_.free(w) ? 1 : 0;
    if (degree == 1 && r != kNobody && goals_[static_cast<std::size_t>(r)] == u) continue;
    ++n;
    ahead = u;
  }
  return n;
}

// The robot `robot` should pull through a corridor: the one on its best cell when they must
// pass each other and can, or one behind it that must pass it (LaCAM2's "clear" case).
int64_t PibtStep::swap_partner(uint32_t robot, grid::Cell best, GoalHeuristic& h) const {
  const grid::Cell here = from_[robot];
  if (best == here) return kNobody;
  const int64_t j = now_[grid_.index(best)];
  if (j != kNobody && !planned_[static_cast<std::size_t>(j)] &&
      swap_required(robot, static_cast<uint32_t>(j), here, best, h) && swap_possible(best, here)) {
    return j;
  }
  for (const grid::Cell u : around(here)) {
    if (!grid_.free(u)) continue;
    const int64_t k = now_[grid_.index(u)];
    if (k != kNobody && best != u &&
        swap_required(static_cast<uint32_t>(k), robot, here, best, h) &&
        swap_possible(best, here)) {
      return k;
    }
  }
  return kNobody;
}

// Whether `pusher` (on v_pusher) and `puller` (on v_puller) must pass each other: walking the
// corridor ahead of the puller while it leads the pusher nearer its goal meets no fork, and the
// puller wants to go where the pusher is.
bool PibtStep::swap_required(uint32_t pusher, uint32_t puller, grid::Cell v_pusher,
                             grid::Cell v_puller, GoalHeuristic& h) const {
  for (std::size_t guard = 0; guard < now_.size(); ++guard) {
    if (h.rank(pusher, v_puller) >= h.rank(pusher, v_pusher)) break;
    grid::Cell ahead{};
    const int n = corridor_step(v_puller, v_pusher, ahead);
    if (n >= 2) return false;  // a fork: they can pass there without pulling
    if (n <= 0) break;
    v_pusher = v_puller;
    v_puller = ahead;
  }
  return h.rank(puller, v_pusher) < h.rank(puller, v_puller) &&
         (h.rank(pusher, v_pusher) == 0 || h.rank(pusher, v_puller) < h.rank(pusher, v_pusher));
}

// Whether pulling can succeed: walking away from the pusher reaches a fork before a dead end.
bool PibtStep::swap_possible(grid::Cell v_pusher, grid::Cell v_puller) const {
  const grid::Cell origin = v_pusher;
  for (std::size_t guard = 0; guard < now_.size() && v_puller != origin; ++guard) {
    grid::Cell ahead{};
    const int n = corridor_step(v_puller, v_pusher, ahead);
    if (n >= 2) return true;
    if (n <= 0) return false;
    v_pusher = v_puller;
    v_puller = ahead;
  }
  return false;
}

}  // namespace smart::planning
