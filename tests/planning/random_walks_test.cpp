#include "smart/planning/random_walks.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <stdexcept>
#include <utility>

#include "smart/grid/map_reader.hpp"

namespace smart::planning {
namespace {

// 5 x 3 with two walls: 13 free cells.
grid::Grid tiny() {
  return grid::parse_map("type octile\nheight 3\nwidth 5\nmap\n..@..\n.....\n..@..\n", "tiny.map");
}

TEST(RandomWalks, StartOnDistinctFreeCellsAndMoveOneFreeNeighbourAtATime) {
  const auto g = tiny();
  const auto w = generate_random_walks(g, 10, 40, 7);
  ASSERT_EQ(w.starts.size(), 10u);
  ASSERT_EQ(w.plan.paths.size(), 10u);
  std::set<std::pair<int32_t, int32_t>> starts;
  for (std::size_t r = 0; r < 10; ++r) {
    const auto& p = w.plan.paths[r];
    EXPECT_EQ(p.robot, static_cast<int>(r));
    ASSERT_EQ(p.steps.size(), 40u);
    EXPECT_EQ(p.steps.front().cell, w.starts[r]);
    starts.insert({w.starts[r].x, w.starts[r].y});
    for (std::size_t k = 0; k < p.steps.size(); ++k) {
      EXPECT_TRUE(g.free(p.steps[k].cell)) << "robot " << r << " step " << k;
      EXPECT_EQ(p.steps[k].time, double(k));
      if (k == 0) continue;
      const auto a = p.steps[k - 1].cell, b = p.steps[k].cell;
      EXPECT_LE(std::abs(a.x - b.x) + std::abs(a.y - b.y), 1) << "robot " << r << " step " << k;
    }
  }
  EXPECT_EQ(starts.size(), 10u);
}

TEST(RandomWalks, TheSameSeedGivesTheSameWalksAndAnotherSeedOthers) {
  const auto g = tiny();
  const auto a = generate_random_walks(g, 5, 30, 3), b = generate_random_walks(g, 5, 30, 3);
  const auto c = generate_random_walks(g, 5, 30, 4);
  bool differs = false;
  for (std::size_t r = 0; r < 5; ++r) {
    for (std::size_t k = 0; k < 30; ++k) {
      EXPECT_EQ(a.plan.paths[r].steps[k].cell, b.plan.paths[r].steps[k].cell);
      differs |= a.plan.paths[r].steps[k].cell != c.plan.paths[r].steps[k].cell;
    }
  }
  EXPECT_TRUE(differs);
}

TEST(RandomWalks, MoreRobotsThanFreeCellsIsAnErrorNamingBothCounts) {
  try {
    generate_random_walks(tiny(), 14, 5, 1);
    FAIL() << "14 robots on 13 free cells were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "14 robots do not fit on 13 free cells");
  }
}

}  // namespace
}  // namespace smart::planning
