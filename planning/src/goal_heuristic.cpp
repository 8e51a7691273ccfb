#include "smart/planning/goal_heuristic.hpp"

namespace smart::planning {

HeuristicKind choose_heuristic(HeuristicKind kind, const grid::Grid& grid, std::size_t robots,
                               std::size_t budget_bytes) {
  if (kind != HeuristicKind::kAuto) return kind;
  return robots * DistanceCache::table_bytes(grid) <= budget_bytes ? HeuristicKind::kTables
                                                                   : HeuristicKind::kPaths;
}

bool TableHeuristic::aim(uint32_t robot, grid::Cell at, grid::Cell goal) {
  if (robot >= goal_.size()) {
    goal_.resize(robot + 1);
    holding_.resize(robot + 1);
    table_.resize(robot + 1);
  }
  goal_[robot] = goal;
  holding_[robot] = at == goal;
  if (at == goal) {
    table_[robot].reset();  // the goal's table is no longer this robot's to keep
    return true;
  }
  table_[robot] = tables_.to(goal);
  return (*table_[robot])[tables_.grid().index(at)] >= 0;
}

// A robot aimed at its own cell (no goal: it holds where it is) ranks it 0 and each free
// neighbour 1, its table's values there: a BFS a cell it is pushed to took a third of the
// monitor's CPU in lifelong runs, and evicted the tables of goals in use (docs/performance.md,
// "Wait causes read from records, and robots without a goal ranked without a table").
int64_t TableHeuristic::rank(uint32_t robot, grid::Cell c) {
  if (holding_[robot]) return c == goal_[robot] ? 0 : 1;
  return (*table_[robot])[tables_.grid().index(c)];
}

std::size_t TableHeuristic::memory_bytes() const {
  return tables_.tables() * DistanceCache::table_bytes(tables_.grid());
}

}  // namespace smart::planning
