// The two-robot "following" plan of monitor tests: tiny, with Type-2 waits at every step.
#pragma once

#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::test {

// Robot 0 drives (1,0) -> (3,0); robot 1 follows it from (0,0) to (2,0): robot 1's second
// half-move waits for robot 0's first (Type-2), its third for robot 0's second, and so on.
struct Following {
  grid::Grid grid = grid_of({".....", "....."});
  grid::ActionPlan actions =
      monitor::build_actions(plan_of({{{1, 0}, {2, 0}, {3, 0}}, {{0, 0}, {1, 0}, {2, 0}}}));
  std::vector<grid::Problem> problems;
  monitor::Adg adg = monitor::build_adg(actions, grid, "p", problems);
};

}  // namespace smart::test
