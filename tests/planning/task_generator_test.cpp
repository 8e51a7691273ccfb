#include "smart/planning/task_generator.hpp"

#include <gtest/gtest.h>

#include <set>

#include "smart/grid/map_reader.hpp"
#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

using grid::Cell;

TEST(TaskGenerator, StartsAreDistinctReachableAndSeeded) {
  // The right half is walled off: nothing may start there.
  const auto g =
      grid::parse_map("type octile\nheight 3\nwidth 7\nmap\n....@..\n....@..\n....@..\n", "m");
  const auto s = random_starts(g, 12, 4);
  EXPECT_EQ(std::set<Cell>(s.begin(), s.end()).size(), 12u);
  for (const Cell c : s) EXPECT_LT(c.x, 4);
  EXPECT_EQ(s, random_starts(g, 12, 4));
  EXPECT_NE(s, random_starts(g, 12, 5));
  EXPECT_THROW(random_starts(g, 13, 4), std::invalid_argument);
}

TEST(TaskGenerator, RandomErrandsStayInTheRegionAndNeverRepeatACell) {
  const auto g = grid::parse_map("type octile\nheight 2\nwidth 5\nmap\n..@..\n..@..\n", "m");
  const auto tasks = generate_tasks(g, {}, 50, 3, 1);
  ASSERT_EQ(tasks.size(), 50u);
  const auto region = largest_region_cells(g);
  const std::set<Cell> in(region.begin(), region.end());
  for (const auto& t : tasks) {
    ASSERT_EQ(t.errands.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_TRUE(in.count(t.errands[k]));
      if (k > 0) {
        EXPECT_NE(t.errands[k], t.errands[k - 1]);
      }
    }
  }
}

TEST(TaskGenerator, MarkedMapsAlternateEndpointAndWorkstation) {
  const auto g = generate_empty_map(6, 6);
  grid::MapMarks marks{{{0, 0}, {0, 5}}, {{3, 2}, {3, 3}, {4, 2}}};
  const auto tasks = generate_tasks(g, marks, 20, 4, 2);
  const std::set<Cell> ws(marks.workstations.begin(), marks.workstations.end());
  const std::set<Cell> ep(marks.endpoints.begin(), marks.endpoints.end());
  for (const auto& t : tasks) {
    for (std::size_t k = 0; k < t.errands.size(); ++k) {
      EXPECT_TRUE((k % 2 == 0 ? ep : ws).count(t.errands[k])) << "task " << t.id << " errand " << k;
    }
  }
}

}  // namespace
}  // namespace smart::planning
