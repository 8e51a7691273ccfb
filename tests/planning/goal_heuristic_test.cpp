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

TEST(ChooseHeuristic, TablesWhileOnePerRobotFitsTheBudget) {
  const auto g = generate_empty_map(100, 100);  // 40 000 bytes a table
  EXPECT_EQ(choose_heuristic(HeuristicKind::kAuto, g, 25, 1000000), HeuristicKind::kTables);
  EXPECT_EQ(choose_heuristic(HeuristicKind::kAuto, g, 26, 1000000), HeuristicKind::kPaths);
  EXPECT_EQ(choose_heuristic(HeuristicKind::kTables, g, 1000, 1), HeuristicKind::kTables);
  EXPECT_EQ(choose_heuristic(HeuristicKind::kPaths, g, 1, 1u << 30), HeuristicKind::kPaths);
}

}  // namespace
}  // namespace smart::planning
