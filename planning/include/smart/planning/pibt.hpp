// Contract: the built-in lifelong planner, PIBT (Okumura, Machida, Défago, Tsukamoto: "Priority
// inheritance with backtracking for iterative multi-agent path finding", Artificial
// Intelligence 310, 2022, Algorithms 1 and 2), written here from the paper. One call plans a
// window of `steps` timesteps for every robot from its start cell (the commit cut's end): each
// step, robots in decreasing priority pick the free neighbour (or their own cell) nearest their
// current goal; a robot that wants a cell another robot still stands on asks it to move first
// (priority inheritance), and when that robot cannot move the asker tries its next candidate
// (backtracking). Paths have no vertex and no swap conflicts; robots may follow one another and
// move round cycles (safe with the ADG's half-cell locations, SMART §IV-B). A robot with errands
// left heads for the first and, on reaching it inside the window, for the next; a robot with
// none holds its cell and yields when pushed.
// Priorities persist across windows as in the paper: each step a robot not at its goal gains 1;
// reaching a goal resets it to its tie-breaker in [0, 1), so a long-waiting robot eventually
// outranks everyone (reachability in biconnected graphs, the paper's Theorem 2).
// Candidates are ranked by a GoalHeuristic (goal_heuristic.hpp): exact distance tables shared
// per goal cell, or each robot's guide path on maps too large for them. Deterministic for a
// seed; no clock, no I/O. Cost per window: steps x robots x (4 neighbours, sorted) plus the
// heuristic's own (BFS tables, or A* for new goals).
#pragma once

#include <cstdint>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "smart/planning/pibt_step.hpp"

namespace smart::planning {

struct WindowRequest {
  std::vector<grid::Cell> start;               // per robot; distinct free cells
  std::vector<std::vector<grid::Cell>> goals;  // per robot: errands left, in order (may be empty)
  int steps = 10;
  std::vector<grid::Heading> heading = {};  // per robot at its start, if known (PIBT ignores it)
  double time_s = 0;  // when the cut was made (sim time), for planners that ask
};

struct WindowPlan {
  std::vector<std::vector<grid::Cell>> paths;  // per robot: steps + 1 cells, [0] = start
  std::size_t moves = 0;                       // robot-steps that change cell
};

class Pibt {
 public:
  Pibt(const grid::Grid& grid, GoalHeuristic& heuristic, uint64_t seed);

  // Throws std::invalid_argument for a request that does not fit (sizes, two robots on one
  // cell, a start on an obstacle, a goal no path reaches).
  WindowPlan plan(const WindowRequest& request);

 private:
  void check(const WindowRequest& request);

  const grid::Grid& grid_;
  GoalHeuristic& heur_;
  uint64_t seed_;
  std::vector<double> priority_;  // kept across windows
  std::vector<double> tie_;       // each robot's tie-breaker in [0, 1)
  uint64_t calls_ = 0;
  PibtStep step_;  // its cell tables are kept from window to window
};

}  // namespace smart::planning
