// Contract: one-shot MAPF plans by LaCAM (Okumura: "LaCAM: Search-Based Algorithm for Quick
// Multi-Agent Pathfinding", AAAI 2023, Algorithms 1 and 2), written here from the paper: a
// depth-first search over configurations (every robot's cell at once) whose successor is made
// by one PIBT step (pibt_step.hpp). A configuration met again is not expanded anew; the search
// returns to it and asks PIBT again under constraints it builds lazily, one robot's next cell at
// a time in priority order (the low-level search), so every successor is tried in the end:
// complete for solvable instances given time (the paper's Theorem 1), where PIBT alone
// (pibt_plan.hpp) can cycle for ever. Priorities as the paper's PIBT: a robot away from its goal
// gains 1 per step, one on its goal drops to its fraction; at the start, distance / robots.
// Its PIBT steps swap by pulling (LaCAM2, pibt_step.hpp), which one-wide corridors need: without
// it, 200 robots on MovingAI's warehouse map fill 1 GiB unsolved; with it 1000 take 0.24 s.
// The plan is the chain of configurations from the start to the goal: feasible, not short
// (LaCAM*'s refinement is not done). Paths per timestep, vertex- and swap-free, robots may
// follow one another and move round cycles (safe with half-cell locations, SMART §IV-B).
// Deterministic for a seed unless the time limit cuts the search short; max_configurations
// bounds its memory (each kept configuration costs about 16 bytes per robot). No I/O.
#pragma once

#include <cstddef>
#include <cstdint>

#include "smart/grid/grid.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/planning/planner.hpp"

namespace smart::planning {

struct LacamOptions {
  uint64_t seed = 1;
  double time_limit_s = 120;
  std::size_t max_configurations = 0;  // 0: as many as 1 GiB holds
  bool swap = true;  // PIBT with swap (LaCAM2, pibt_step.hpp): false for the AAAI 2023 original
};

struct LacamStats {
  std::size_t configurations = 0;  // distinct configurations kept
  std::size_t expansions = 0;      // low-level nodes tried
};

// Throws std::invalid_argument for a scenario that does not fit the map (a start or goal
// blocked or out of reach, two robots on one start or one goal).
PlannerResult plan_lacam(const grid::Grid& grid, const grid::Scenario& scen, const LacamOptions& o,
                         LacamStats* stats = nullptr);

}  // namespace smart::planning
