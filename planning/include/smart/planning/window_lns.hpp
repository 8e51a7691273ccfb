// Contract: a lifelong window made better by large neighbourhood search, one robot at a time.
// PIBT (pibt.hpp) plans a window greedily, a step at a time: robots detour and wait behind each
// other where a path planned ahead would not. improve() takes such a window (conflict-free) and,
// for each robot in turn, takes its path out and plans it again by space-time A* against every
// other robot's path (vertices and swaps; following allowed, SMART §IV-B), keeping the new path
// when it ends the window nearer the robot's errands: MAPF-LNS's replanning of a neighbourhood
// (Li, Chen, Harabor, Stuckey, Koenig: "Anytime Multi-Agent Path Finding via Large Neighborhood
// Search", IJCAI 2021, §4) with neighbourhoods of one robot, written here from the paper. Each
// step keeps the window conflict-free, so it stops whenever it must: it never makes a window
// worse, and never fails.
// A robot's cost is where it ends the window: timesteps plus the exact distance left through
// its errands (the first, and the second when the first is within the window's reach), the
// objective of a windowed planner (RHCR: Li, Tinka, Kiesel, Durham, Kumar, Koenig, AAAI 2021,
// §4); a robot past them costs 0 where it stands at the end, and one with none is left as PIBT
// planned it. Robots go longest distance left first.
// Deterministic; no clock, no I/O. Needs a distance table per goal cell (distance_cache.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/distance_cache.hpp"
#include "smart/planning/pibt.hpp"
#include "smart/planning/space_time_reservations.hpp"

namespace smart::planning {

struct WindowLnsOptions {
  int passes = 1;                     // rounds over every robot
  std::size_t max_expansions = 4096;  // per robot replanned; past it its path is kept
};

struct WindowLnsStats {
  uint64_t windows = 0;     // improve() calls
  uint64_t replanned = 0;   // robots planned again
  uint64_t improved = 0;    // of them, those given a better path
  int64_t saved = 0;        // the cost (steps) the better paths saved, all windows
  uint64_t expansions = 0;  // A* nodes expanded, all calls
};

class WindowLns {
 public:
  WindowLns(const grid::Grid& grid, DistanceCache& tables, WindowLnsOptions options = {});

  // `plan` must be a conflict-free window for `request` (every path steps + 1 cells from the
  // robot's start). Throws std::invalid_argument when it is not shaped so (sizes, starts).
  void improve(const WindowRequest& request, WindowPlan& plan);
  const WindowLnsStats& stats() const { return stats_; }

 private:
  struct Search;
  struct Goals;
  void check(const WindowRequest& request, const WindowPlan& plan) const;
  Goals goals_of(const WindowRequest& request, uint32_t robot);
  int32_t cost(const Goals& goals, const std::vector<grid::Cell>& path) const;
  bool replan(const Goals& goals, int steps, const SpaceTimeReservations& reservations,
              Search& search, std::vector<grid::Cell>& path);

  const grid::Grid& grid_;
  DistanceCache& tables_;
  WindowLnsOptions options_;
  WindowLnsStats stats_;
};

}  // namespace smart::planning
