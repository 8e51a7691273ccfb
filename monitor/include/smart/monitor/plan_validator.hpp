// Contract: checks a plan against its map and (optionally) scenario and returns every problem
// found, each naming file, line, robot, cell and timestep:
// - steps outside the map or on obstacles, non-adjacent steps (only 4-neighbour moves and
//   waits), times that do not strictly increase;
// - starts and goals that differ from the scenario (with a hint when the other axis order
//   would match), more robots than the scenario has;
// - vertex conflicts, swap conflicts, and robots entering the goal cell of a robot that is
//   already parked there for good (robots stay at their goal after their last step).
// Occupancy semantics: a robot holds a cell over the half-open plan-time interval
// [arrival, departure), departure = time of its first step at another cell; the first cell is
// held from time 0 and the last one for ever. Following (entering as the other leaves) is fine.
#pragma once

#include <vector>

#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

std::vector<Problem> validate_plan(const Plan& plan, const Grid& grid,
                                   const Scenario* scen = nullptr);

}  // namespace smart::monitor
