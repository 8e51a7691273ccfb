// Contract: a built-in MAPF planner for demos and tests: prioritized planning (Silver 2005;
// Erdmann & Lozano-Pérez 1987) with space-time A* against a reservation table of vertices,
// edges (no swaps) and goals (a robot parked at its goal blocks its cell for good, and a robot
// only parks where nobody passes later). Every robot's start is reserved at t = 0 so earlier
// robots do not run through later robots' starts. Robots are planned longest-distance first;
// a robot that finds no path goes first in the next attempt (every fifth attempt the rest of
// the order is also shuffled, seeded). Deterministic for a seed
// unless the time limit cuts it short. Paths are per timestep (waits included), times 0,1,2...
// The result passes validate_plan() when solved.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/grid/plan.hpp"
#include "smart/grid/scen_reader.hpp"

namespace smart::planning {

struct PlannerOptions {
  uint64_t seed = 1;
  int restarts = 50;
  double time_limit_s = 120;
};

struct PlannerResult {
  bool solved = false;
  grid::Plan plan;
  int restarts_used = 0;
  double runtime_s = 0;
  std::string error;  // why not solved
};

PlannerResult plan_prioritized(const grid::Grid& grid, const grid::Scenario& scen,
                               const PlannerOptions& o);

// A plan from per-timestep paths (paths[robot][t], every path as long): a robot's trailing waits
// on its last cell are dropped. `source` names the planner in errors.
grid::Plan plan_from_timesteps(const std::vector<std::vector<grid::Cell>>& paths,
                               const std::string& source);
// The inverse for a plan of plan_from_timesteps (a step per timestep from 0): each robot's cells,
// up to its arrival (plan_lns.hpp's paths).
std::vector<std::vector<grid::Cell>> timesteps_of(const grid::Plan& plan);

// SMART timed plan text: "# axis: xy", then "Agent i:(x,y,t)->...", x = column (the reader takes
// the axis from that line; a reader that wants only Agent lines may need it removed).
std::string to_smart_plan_text(const grid::Plan& plan);

}  // namespace smart::planning
