#include "smart/planning/plan_lns.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "planning/plan_checks.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/lacam.hpp"

namespace smart::planning {
namespace {

using grid::Cell;
using Paths = std::vector<std::vector<Cell>>;

Paths timesteps(const grid::Plan& plan) {
  Paths out;
  for (const auto& p : plan.paths) {
    out.emplace_back();
    for (const auto& s : p.steps) out.back().push_back(s.cell);
  }
  return out;
}

std::size_t soc(const Paths& paths) {
  std::size_t sum = 0;
  for (const auto& p : paths) sum += p.size() - 1;
  return sum;
}

// LaCAM's plan of 250 robots on a random map, improved: still valid for its scenario (no
// conflict, every robot on its goal, an acyclic ADG), its sum of costs smaller by what the
// stats say, and each robot arriving no later than before.
TEST(PlanLns, LacamsPlanStaysValidAndNoRobotArrivesLater) {
  const auto g = generate_random_map(32, 32, 0.15, 4);
  const auto scen = generate_scenario(g, 250, 5, "random");
  auto r = plan_lacam(g, scen, {6});
  ASSERT_TRUE(r.solved) << r.error;
  auto paths = timesteps(r.plan);
  const auto before = paths;
  DistanceCache tables(g);
  const auto st = improve_plan(g, paths, tables, {.passes = 2});
  r.plan = plan_from_timesteps(paths, "lns");
  expect_valid_plan(g, scen, r, "LaCAM + LNS");
  EXPECT_GT(st.improved, 0u);
  EXPECT_EQ(static_cast<int64_t>(soc(before)) - static_cast<int64_t>(soc(paths)), st.saved);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    EXPECT_LE(paths[i].size(), before[i].size()) << "robot " << i;
  }
}

// Robot 0 waited two steps for nothing: it arrives two steps earlier. Robot 1 goes through
// robot 0's goal at t = 2: robot 0 may not park there before, so robot 1's path is kept and robot
// 0 is not sent in ahead of it.
TEST(PlanLns, ARobotArrivesEarlierButNeverParksWhereSomeonePassesLater) {
  const auto g = grid::parse_map("type octile\nheight 2\nwidth 4\nmap\n....\n....\n", "c");
  DistanceCache tables(g);
  Paths free_way{{{0, 0}, {0, 0}, {0, 0}, {1, 0}, {2, 0}}};
  auto st = improve_plan(g, free_way, tables);
  EXPECT_EQ(free_way[0], (std::vector<Cell>{{0, 0}, {1, 0}, {2, 0}}));
  EXPECT_EQ(st.saved, 2);
  // Robot 1 passes (1,0) at t = 2, on its way from (3,0) to (0,0) along the top row.
  Paths crossing{{{1, 1}, {1, 1}, {1, 1}, {1, 0}}, {{3, 0}, {2, 0}, {1, 0}, {0, 0}}};
  const auto kept = crossing;
  st = improve_plan(g, crossing, tables);
  EXPECT_EQ(crossing, kept);  // robot 0 arrives at t = 3, after robot 1 has left its goal
  EXPECT_EQ(st.improved, 0u);
}

TEST(PlanLns, RefusesAnEmptyPath) {
  const auto g = grid::parse_map("type octile\nheight 1\nwidth 3\nmap\n...\n", "c");
  DistanceCache tables(g);
  Paths paths{{{0, 0}}, {}};
  EXPECT_THROW(improve_plan(g, paths, tables), std::invalid_argument);
}

}  // namespace
}  // namespace smart::planning
