// Contract: a one-shot plan made better by large neighbourhood search, one robot at a time
// (MAPF-LNS: Li, Chen, Harabor, Stuckey, Koenig, "Anytime Multi-Agent Path Finding via Large
// Neighborhood Search", IJCAI 2021, §4, with neighbourhoods of one robot; written here from the
// paper). Each robot in turn, most delayed first (arrival minus its distance), is taken out of
// the plan and planned again by space-time A* against every other robot's path: vertices, swaps
// (following allowed, SMART §IV-B) and goals (a robot that has arrived stays, so nobody enters
// its goal after; it arrives only where nobody passes later). The new path is kept when the
// robot arrives earlier; the search looks only at paths that do (A* bounded by the old arrival),
// so a robot that cannot gain costs a few expansions. With `neighbourhood` > 1 (MAPF-LNS's
// agent-based neighbourhood, §4.3, without its random walk), the robot is replanned together
// with the robots in the way of its shortest path (at the path's cell at that time, or parked
// there), up to `neighbourhood` robots: their paths are taken out and planned again one after
// the other (the delayed robot first), each bounded so that the group's arrivals can still sum
// lower; kept when all are found, else the robot is replanned alone. Every step keeps the plan
// valid, so it never fails and never makes the plan's sum of costs larger. Paths are per timestep
// (waits included); deterministic; no clock, no I/O. Why: plans improved by LNS switch better than
// LaCAM's (docs/execution.md, "Plans of MAPF-LNS2 at 500 and 1000 robots").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/distance_cache.hpp"

namespace smart::planning {

struct PlanLnsOptions {
  int passes = 1;                       // rounds over every robot
  std::size_t max_expansions = 50'000;  // per robot replanned; past it its path is kept
  int neighbourhood = 1;                // robots replanned together (1-64)
};

struct PlanLnsStats {
  // Neighbourhoods planned again (a robot tried alone after its group counts once more), and
  // those kept.
  std::size_t replanned = 0, improved = 0;
  int64_t saved = 0;  // timesteps of arrival saved, all robots
  std::size_t expansions = 0;
};

// `paths[i]`: robot i's cells at t = 0, 1, ... up to its arrival at its goal (the last cell),
// a valid plan (validate_plan()). Improved in place. Throws std::invalid_argument for paths on
// maps of 16 M cells or more, an empty path, or a neighbourhood outside 1-64.
PlanLnsStats improve_plan(const grid::Grid& grid, std::vector<std::vector<grid::Cell>>& paths,
                          DistanceCache& tables, const PlanLnsOptions& options = {});

}  // namespace smart::planning
