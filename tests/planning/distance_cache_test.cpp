#include "smart/planning/distance_cache.hpp"

#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

TEST(DistanceCache, OneTablePerGoalSharedAndEqualToBfs) {
  const auto g = generate_random_map(20, 20, 0.2, 3);
  DistanceCache cache(g);
  const auto cells = largest_region_cells(g);
  const auto goal = cells[cells.size() / 2];
  const auto a = cache.to(goal);
  const auto b = cache.to(goal);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(cache.computed(), 1u);
  EXPECT_EQ(*a, bfs_distances(g, goal));
  EXPECT_EQ(cache.distance(goal, goal), 0);
}

TEST(DistanceCache, EvictsTheLeastRecentlyUsedWithinTheBudget) {
  const auto g = generate_empty_map(10, 10);     // 400 bytes a table
  DistanceCache cache(g, 4 * 400);               // four tables
  for (int x = 0; x < 5; ++x) cache.to({x, 0});  // the fifth evicts (0,0)
  EXPECT_EQ(cache.tables(), 4u);
  const auto kept = cache.to({1, 0});  // still there: no new BFS
  EXPECT_EQ(cache.computed(), 5u);
  cache.to({0, 0});  // evicted: computed again
  EXPECT_EQ(cache.computed(), 6u);
  EXPECT_EQ((*kept)[g.index({1, 0})], 0);  // a held table outlives eviction
}

TEST(DistanceCache, ATableCountBoundsItBelowTheBudget) {
  const auto g = generate_empty_map(10, 10);
  DistanceCache cache(g, 1 << 20, 6);  // room for 2621 tables, but at most six
  for (int x = 0; x < 10; ++x) cache.to({x, 3});
  EXPECT_EQ(cache.tables(), 6u);
}

}  // namespace
}  // namespace smart::planning
