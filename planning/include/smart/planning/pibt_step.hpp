// Contract: one PIBT timestep (Okumura, Machida, Défago, Tsukamoto: "Priority inheritance with
// backtracking for iterative multi-agent path finding", Artificial Intelligence 310, 2022,
// Algorithm 2), shared by the lifelong window planner (pibt.hpp) and LaCAM's configuration
// generator (lacam.hpp; Okumura AAAI 2023, Algorithm 2's PIBT with constraints).
// begin() with every robot's cell; fix() robots whose next cell is decided already (LaCAM's
// constraints); then plan() robots in decreasing priority. A robot picks its own cell or a free
// neighbour, nearest its goal first by the heuristic (ties in an order shuffled by the caller's
// rng); a robot on the picked cell is asked to move first (priority inheritance) and, when it
// cannot, the asker tries its next candidate (backtracking). A step never gives two robots one
// next cell and never swaps two robots. end() forgets the step in O(robots), ready for begin().
// With swaps on (LaCAM2's "PIBT with swap": Okumura, "Improving LaCAM for Scalable Eventually
// Optimal Multi-Agent Pathfinding", IJCAI 2023, Section 4.2), a robot facing another robot in a
// one-wide corridor that must be passed tries its candidates in reverse, away from it, and pulls
// it into its own cell: over a few steps the two pass each other at the corridor's next fork,
// where plain PIBT steps would push each other back and forth. No cell is ever swapped directly.
// No clock, no I/O: deterministic for the same calls and rng.
#pragma once

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/goal_heuristic.hpp"

namespace smart::planning {

class PibtStep {
 public:
  explicit PibtStep(const grid::Grid& grid);

  // Turns swaps on for robots heading for `goals`; the heuristic given to plan() must then rank
  // any free cell (TableHeuristic does: exact distances), not only a robot's neighbours.
  void enable_swaps(std::vector<grid::Cell> goals) { goals_ = std::move(goals); }

  // Every robot's cell now: distinct free cells (the caller checked them).
  void begin(const std::vector<grid::Cell>& from);
  // `robot` goes to `to` (its cell or a free neighbour of it): false, and nothing fixed, when
  // another robot goes there already or the two would swap cells.
  bool fix(uint32_t robot, grid::Cell to);
  // Plans `robot` (aimed in `heuristic` already) unless its next cell is decided. False when no
  // cell was left for it: it was left on its own cell, which another robot was fixed to, so the
  // step is unusable (only fix() can cause this; without constraints PIBT always succeeds).
  bool plan(uint32_t robot, GoalHeuristic& heuristic, std::mt19937_64& rng);
  bool planned(uint32_t robot) const { return planned_[robot] != 0; }
  const std::vector<grid::Cell>& to() const { return to_; }
  void end();

 private:
  bool push(uint32_t robot, GoalHeuristic& heuristic, std::mt19937_64& rng);
  int64_t swap_partner(uint32_t robot, grid::Cell best, GoalHeuristic& h) const;
  bool swap_required(uint32_t pusher, uint32_t puller, grid::Cell v_pusher, grid::Cell v_puller,
                     GoalHeuristic& h) const;
  bool swap_possible(grid::Cell v_pusher, grid::Cell v_puller) const;
  int corridor_step(grid::Cell at, grid::Cell behind, grid::Cell& ahead) const;

  const grid::Grid& grid_;
  std::vector<grid::Cell> from_, to_;
  std::vector<uint8_t> planned_;
  std::vector<int64_t> now_, next_;  // by cell index: the robot there now / going there next
  std::vector<grid::Cell> goals_;    // per robot, when swaps are on (empty: off)
};

}  // namespace smart::planning
