#include "smart/planning/goal_heuristic.hpp"

#include <gtest/gtest.h>

#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

TEST(TableHeuristic, RanksAreTheGoalsBfsDistances) {
  const auto g = generate_random_map(20, 20, 0.2, 3);
  DistanceCache cache(g);
  TableHeuristic h(cache);
  const auto cells = largest_region_cells(g);
  const grid::Cell goal = cells.back();
  const auto d = bfs_distances(g, goal);
  ASSERT_TRUE(h.aim(4, cells.front(), goal));
  for (std::size_t k = 0; k < cells.size(); k += 17) {
    EXPECT_EQ(h.rank(4, cells[k]), d[g.index(cells[k])]);
  }
  EXPECT_EQ(h.tables(), 1u);
  EXPECT_EQ(h.memory_bytes(), 400 * sizeof(int32_t));
}

// Robots without a goal are aimed at their own cell each step (pibt.cpp); PIBT pushes them
// about, and a BFS table a cell they were pushed to took a third of the monitor's CPU in a
// 1000-robot lifelong run (2026-12-08). The ranks are those of the cell's table, without one.
TEST(TableHeuristic, ARobotAimedAtItsOwnCellRanksAsItsTableWithoutOne) {
  const auto g = generate_random_map(20, 20, 0.2, 3);
  DistanceCache cache(g);
  TableHeuristic h(cache);
  const auto cells = largest_region_cells(g);
  for (std::size_t k = 0; k < cells.size(); k += 7) {
    const grid::Cell at = cells[k];
    const auto d = bfs_distances(g, at);
    ASSERT_TRUE(h.aim(2, at, at));
    EXPECT_EQ(h.rank(2, at), 0);
    for (const grid::Cell n : {grid::Cell{at.x + 1, at.y}, grid::Cell{at.x - 1, at.y},
                               grid::Cell{at.x, at.y + 1}, grid::Cell{at.x, at.y - 1}}) {
      if (g.free(n)) {
        EXPECT_EQ(h.rank(2, n), d[g.index(n)]) << grid::to_string(n);
      }
    }
  }
  EXPECT_EQ(cache.computed(), 0u) << "no table for a robot that holds its cell";
  // Aimed at a goal again, it ranks by the goal's table.
  ASSERT_TRUE(h.aim(2, cells.front(), cells.back()));
  EXPECT_EQ(h.rank(2, cells.front()), bfs_distances(g, cells.back())[g.index(cells.front())]);
  EXPECT_EQ(cache.computed(), 1u);
}

TEST(ChooseHeuristic, TablesWhileOnePerRobotFitsTheBudget) {
  const auto g = generate_empty_map(100, 100);  // 40 000 bytes a table
  EXPECT_EQ(choose_heuristic(HeuristicKind::kAuto, g, 25, 1000000), HeuristicKind::kTables);
  EXPECT_EQ(choose_heuristic(HeuristicKind::kAuto, g, 26, 1000000), HeuristicKind::kPaths);
  EXPECT_EQ(choose_heuristic(HeuristicKind::kTables, g, 1000, 1), HeuristicKind::kTables);
  EXPECT_EQ(choose_heuristic(HeuristicKind::kPaths, g, 1, 1u << 30), HeuristicKind::kPaths);
}

}  // namespace
}  // namespace smart::planning
