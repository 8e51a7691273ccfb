#include "smart/planning/guide_paths.hpp"

#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

using grid::Cell;

TEST(GuidePaths, PathsAreShortestAndTheLandmarkBoundNeverOverestimates) {
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    const auto g = generate_random_map(40, 30, 0.3, seed);
    GuidePaths paths(g, 4);
    const auto cells = largest_region_cells(g);
    for (std::size_t k = 0; k < 40; ++k) {
      const Cell a = cells[(k * 7919) % cells.size()], b = cells[(k * 104729 + 13) % cells.size()];
      const auto d = bfs_distances(g, a)[g.index(b)];
      const auto p = paths.shortest_path(a, b);
      ASSERT_EQ(static_cast<int32_t>(p.size()) - 1, d) << "seed " << seed << " pair " << k;
      EXPECT_EQ(p.front(), a);
      EXPECT_EQ(p.back(), b);
      for (std::size_t i = 1; i < p.size(); ++i) {
        ASSERT_TRUE(g.free(p[i]));
        ASSERT_EQ(std::abs(p[i].x - p[i - 1].x) + std::abs(p[i].y - p[i - 1].y), 1);
      }
      EXPECT_LE(paths.lower_bound(a, b), d);
      EXPECT_GE(paths.lower_bound(a, b), std::abs(a.x - b.x) + std::abs(a.y - b.y));
    }
  }
}

TEST(GuidePaths, LandmarksKeepTheSearchOutOfACup) {
  // A robot inside a cup open to the north heads for a cell below it: Manhattan distance lures
  // A* into the cup's whole floor first; the landmark bound knows the way round.
  std::string text = "type octile\nheight 31\nwidth 31\nmap\n";
  for (int y = 0; y < 31; ++y) {
    for (int x = 0; x < 31; ++x) {
      const bool cup = (y == 20 && x >= 5 && x <= 25) || ((x == 5 || x == 25) && y >= 5 && y <= 20);
      text += cup ? '@' : '.';
    }
    text += '\n';
  }
  const auto g = grid::parse_map(text, "cup");
  GuidePaths with(g, 8), without(g, 0);
  const auto a = with.shortest_path({15, 10}, {15, 28}),
             b = without.shortest_path({15, 10}, {15, 28});
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(static_cast<int32_t>(a.size()) - 1, bfs_distances(g, {15, 10})[g.index({15, 28})]);
  // 229 against 407 when written: at least a third fewer.
  EXPECT_LT(with.expanded() * 3, without.expanded() * 2)
      << with.expanded() << " vs " << without.expanded() << " expansions";
}

TEST(GuidePaths, RanksFollowThePathAndBringAPushedRobotBack) {
  const auto g = generate_empty_map(6, 3);
  GuidePaths paths(g, 2);
  ASSERT_TRUE(paths.aim(0, {0, 1}, {5, 1}));  // 5 cells to go
  const auto next = paths.shortest_path({0, 1}, {5, 1})[1];
  EXPECT_EQ(paths.rank(0, {0, 1}), 5);
  EXPECT_EQ(paths.rank(0, next), 4);
  for (const Cell c : {Cell{0, 0}, Cell{0, 2}, Cell{1, 0}}) {
    if (c != next) {
      EXPECT_EQ(paths.rank(0, c), 6);
    }
  }
  // Two steps along: the same path, two cells fewer.
  const auto p = paths.shortest_path({0, 1}, {5, 1});
  ASSERT_TRUE(paths.aim(0, p[2], {5, 1}));
  EXPECT_EQ(paths.rank(0, p[2]), 3);
  EXPECT_EQ(paths.rank(0, p[3]), 2);
  const auto searches = paths.searches();
  // Pushed a cell off the path: the way back onto it ranks best, without a new search.
  const Cell off{p[2].x, p[2].y == 0 ? 1 : p[2].y - 1};
  ASSERT_TRUE(g.free(off));
  ASSERT_TRUE(paths.aim(0, off, {5, 1}));
  EXPECT_EQ(paths.searches(), searches);
  EXPECT_LT(paths.rank(0, p[2]), paths.rank(0, off));
}

TEST(GuidePaths, ARobotPushedFurtherFindsItsWayBackWithoutANewSearch) {
  const auto g = generate_empty_map(20, 9);
  GuidePaths paths(g, 2);
  ASSERT_TRUE(paths.aim(0, {0, 4}, {19, 4}));
  const auto p = paths.shortest_path({0, 4}, {19, 4});
  ASSERT_TRUE(paths.aim(0, p[6], {19, 4}));
  const auto searches = paths.searches();
  const Cell pushed{p[6].x, p[6].y <= 4 ? p[6].y + 3 : p[6].y - 3};  // three cells aside
  ASSERT_TRUE(paths.aim(0, pushed, {19, 4}));
  EXPECT_EQ(paths.searches(), searches);
  EXPECT_EQ(paths.repairs(), 1u);
  // From there, one step toward the path ranks best; its cells left count down to the goal.
  const auto left = paths.rank(0, pushed);
  EXPECT_GE(left, 19 - pushed.x + 3);
  int better = 0;
  for (const Cell c : {Cell{pushed.x + 1, pushed.y}, Cell{pushed.x - 1, pushed.y},
                       Cell{pushed.x, pushed.y + 1}, Cell{pushed.x, pushed.y - 1}}) {
    if (g.free(c) && paths.rank(0, c) == left - 1) ++better;
  }
  EXPECT_EQ(better, 1);
}

TEST(GuidePaths, SearchesBeyondTheWindowsBudgetWaitWithTheLandmarkBound) {
  const auto g = generate_empty_map(8, 8);
  GuidePaths paths(g, 2, 1);  // one A* per window
  paths.new_window({}, {});
  ASSERT_TRUE(paths.aim(0, {0, 0}, {7, 0}));
  ASSERT_TRUE(paths.aim(1, {0, 7}, {7, 7}));  // no search left: waits
  EXPECT_EQ(paths.searches(), 1u);
  EXPECT_EQ(paths.rank(1, {0, 7}), 7);  // the bound: 7 cells east
  EXPECT_EQ(paths.rank(1, {1, 7}), 6);
  paths.new_window({}, {});
  ASSERT_TRUE(paths.aim(0, {1, 0}, {7, 0}));  // on its path: no search
  ASSERT_TRUE(paths.aim(1, {1, 7}, {7, 7}));
  EXPECT_EQ(paths.searches(), 2u);
  EXPECT_EQ(paths.rank(1, {1, 7}), 6);
}

// A window's first searches run on threads; which robots search is decided in robot order.
TEST(GuidePaths, TheWindowsSearchesAreTheSameOnOneThreadOrTwo) {
  const auto g = generate_random_map(60, 40, 0.25, 8);
  const auto cells = largest_region_cells(g);
  std::vector<Cell> at, goal;
  for (std::size_t r = 0; r < 50; ++r) {
    at.push_back(cells[(r * 131) % cells.size()]);
    goal.push_back(cells[(r * 977 + 5) % cells.size()]);
  }
  GuidePaths one(g, 4, 30, 1), two(g, 4, 30, 2);
  one.new_window(at, goal);
  two.new_window(at, goal);
  EXPECT_EQ(one.searches(), 30u);
  EXPECT_EQ(two.searches(), 30u);
  for (uint32_t r = 0; r < 50; ++r) {
    ASSERT_TRUE(one.aim(r, at[r], goal[r]));
    ASSERT_TRUE(two.aim(r, at[r], goal[r]));
    EXPECT_EQ(one.rank(r, at[r]), two.rank(r, at[r])) << "robot " << r;
  }
  EXPECT_EQ(one.searches(), 30u);  // robots 30.. wait for the next window
  EXPECT_EQ(one.rank(40, at[40]), one.lower_bound(at[40], goal[40]));
  EXPECT_EQ(one.rank(5, at[5]), bfs_distances(g, at[5])[g.index(goal[5])]);
}

TEST(GuidePaths, AnUnreachableGoalIsSaid) {
  const auto g = grid::parse_map("type octile\nheight 1\nwidth 5\nmap\n..@..\n", "split");
  GuidePaths paths(g);
  EXPECT_FALSE(paths.aim(0, {0, 0}, {4, 0}));
  EXPECT_TRUE(paths.shortest_path({0, 0}, {4, 0}).empty());
  EXPECT_TRUE(paths.aim(0, {0, 0}, {1, 0}));
  EXPECT_TRUE(paths.aim(1, {3, 0}, {3, 0}));  // already there
  EXPECT_EQ(paths.rank(1, {3, 0}), 0);
}

}  // namespace
}  // namespace smart::planning
