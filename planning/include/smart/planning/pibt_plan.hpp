// Contract: a one-shot MAPF plan by PIBT alone (Okumura et al., AI 2022; the configuration
// generator of LaCAM, Okumura AAAI 2023, without LaCAM's search over configurations): pibt.hpp's
// planner is called window after window from where the robots stand, every robot aiming at its
// scenario goal, until every robot stands on its goal at the end of a window (PIBT reaches all
// goals on biconnected maps, the paper's Theorem 2; elsewhere it may not, and then max_steps
// ends the attempt with an error). Plans are long and full of waits and pushes, unlike
// prioritized planning's (planner.hpp): the kind of plan a delay-tolerant executor is for.
// Paths per timestep (times 0, 1, 2, ...), with vertex- and swap-free steps where robots may
// follow one another and move round cycles (safe with half-cell locations, SMART §IV-B).
// Deterministic for a seed; the result passes validate_plan() when solved. No clock, no I/O.
#pragma once

#include <cstdint>

#include "smart/grid/grid.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/planning/planner.hpp"

namespace smart::planning {

struct PibtPlanOptions {
  uint64_t seed = 1;
  int window_steps = 16;  // PIBT steps per call (priorities persist across calls)
  int64_t max_steps = 0;  // give up past this many timesteps; 0: 50 x (width + height)
};

// Throws std::invalid_argument for a scenario that does not fit the map (pibt.hpp's checks).
PlannerResult plan_pibt(const grid::Grid& grid, const grid::Scenario& scen,
                        const PibtPlanOptions& o);

}  // namespace smart::planning
