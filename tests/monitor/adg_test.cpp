#include "smart/monitor/adg.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "smart/planning/random_plan.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using test::grid_of;
using test::plan_of;
using ::testing::HasSubstr;
using Edge = std::pair<uint32_t, uint32_t>;

std::set<Edge> type2_edges(const Adg& adg) {
  std::set<Edge> edges;
  for (uint32_t u = 0; u < adg.nodes(); ++u) {
    for (uint32_t i = adg.out_begin[u]; i < adg.out_begin[u + 1]; ++i)
      edges.insert({u, adg.out[i]});
  }
  return edges;
}

struct Built {
  ActionPlan actions;
  Adg adg;
  std::vector<Problem> problems;
};

Built build(const Grid& grid, const Plan& plan, Footprint footprint = Footprint::kHalfCells) {
  Built b;
  b.actions = build_actions(plan, Heading::kEast);
  b.adg = build_adg(b.actions, grid, plan.source, b.problems, footprint);
  return b;
}

const Grid kAdgRoom = grid_of({".....", ".....", "....."});

TEST(Adg, FollowingRobotWaitsForEachLocationToBeLeft) {
  // Robot 0: (1,0)->(2,0)->(3,0); robot 1 follows one step behind, both heading east.
  const auto b = build(kAdgRoom, plan_of({{{1, 0}, {2, 0}, {3, 0}}, {{0, 0}, {1, 0}, {2, 0}}}));
  ASSERT_TRUE(b.problems.empty());
  ASSERT_EQ(b.actions.count(0), 4u);
  ASSERT_EQ(b.actions.count(1), 4u);
  // Node ids: robot 0 = 0..3, robot 1 = 4..7. Leaving (1,0), the midpoint and (2,0) gate robot
  // 1's entering of each.
  EXPECT_EQ(type2_edges(b.adg), (std::set<Edge>{{0, 5}, {1, 6}, {2, 7}}));
  EXPECT_EQ(b.adg.in_begin[5 + 1] - b.adg.in_begin[5], 1u);
  EXPECT_EQ(b.adg.stats.type1, 6u);
  EXPECT_EQ(b.adg.stats.type2, 3u);
  EXPECT_TRUE(check_acyclic(b.adg, b.actions, "p").empty());
}

TEST(Adg, CrossingRobotEntersAfterTheFirstHasLeft) {
  // Robot 0 crosses (1,1) eastwards at t=1..2; robot 1 comes down through it at t=2..3.
  const auto b =
      build(kAdgRoom, plan_of({{{0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 0}, {1, 1}, {1, 2}}}));
  ASSERT_TRUE(b.problems.empty());
  ASSERT_EQ(b.actions.count(1), 5u);  // rotate south, then four half-moves
  EXPECT_EQ(b.actions.at(1, 0).type, ActionType::kRotate);
  // Robot 0 leaves (1,1) with its action 2; robot 1 enters (1,1) with its action 2 (node 4+2).
  EXPECT_EQ(type2_edges(b.adg), (std::set<Edge>{{2, 6}}));
}

TEST(Adg, RotationCycleOfFourRobotsIsAcyclicThanksToMidpoints) {
  const Cell c[4] = {{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  Plan plan = plan_of({{c[0], c[1]}, {c[1], c[2]}, {c[2], c[3]}, {c[3], c[0]}});
  const auto b = build(kAdgRoom, plan);
  ASSERT_TRUE(b.problems.empty());
  EXPECT_EQ(b.adg.stats.type2, 4u);
  EXPECT_TRUE(check_acyclic(b.adg, b.actions, "p").empty());
  // Every robot's first half-move (out of its cell) has no Type-2 predecessor.
  for (uint32_t r = 0; r < 4; ++r) {
    uint32_t first_move = b.actions.offset[r];
    while (b.actions.actions[first_move].type != ActionType::kMove) ++first_move;
    EXPECT_EQ(b.adg.in_begin[first_move + 1] - b.adg.in_begin[first_move], 0u) << r;
  }
}

TEST(Adg, ReducedEdgesVersusAllPairsOnAThreeRobotTrain) {
  const auto b = build(
      kAdgRoom,
      plan_of({{{2, 0}, {3, 0}, {4, 0}}, {{1, 0}, {2, 0}, {3, 0}}, {{0, 0}, {1, 0}, {2, 0}}}));
  ASSERT_TRUE(b.problems.empty());
  EXPECT_EQ(b.adg.stats.type2, 6u);
  EXPECT_EQ(b.adg.stats.type2_all_pairs, 7u);  // (2,0) is visited by all three robots
  EXPECT_EQ(b.adg.stats.locations, 9u);
  EXPECT_EQ(b.adg.stats.moves, 12u);
}

TEST(Adg, SwapPlanGivesACycleNamingBothRobots) {
  const auto b = build(kAdgRoom, plan_of({{{0, 2}, {1, 2}}, {{1, 2}, {0, 2}}}));
  const auto cycle = check_acyclic(b.adg, b.actions, "swap.txt");
  ASSERT_EQ(cycle.size(), 1u);
  EXPECT_THAT(cycle[0].to_string(), HasSubstr("swap.txt: the action dependency graph has a cycle"));
  EXPECT_THAT(cycle[0].message, HasSubstr("robot 0"));
  EXPECT_THAT(cycle[0].message, HasSubstr("robot 1"));
  EXPECT_THAT(cycle[0].message, HasSubstr("(x=0.5,y=2)"));
}

TEST(Adg, VisitorAfterARobotParkedForGoodIsReported) {
  const auto b =
      build(kAdgRoom, plan_of({{{1, 0}, {2, 0}}, {{0, 0}, {0, 0}, {1, 0}, {2, 0}, {3, 0}}}));
  ASSERT_FALSE(b.problems.empty());
  EXPECT_THAT(b.problems[0].to_string(),
              HasSubstr("robot 1: enters (x=2,y=0) at t=3 after robot 0 parked there for good"));
}

TEST(Adg, RobotsThatNeverMoveAddNoEdges) {
  const auto b = build(kAdgRoom, plan_of({{{0, 0}}, {{4, 2}, {4, 2}}}));
  EXPECT_TRUE(b.problems.empty());
  EXPECT_EQ(b.adg.nodes(), 0u);
  EXPECT_TRUE(check_acyclic(b.adg, b.actions, "p").empty());
}

TEST(Adg, FootprintFollowsTheRobotsWidthAgainstTheCell) {
  EXPECT_EQ(footprint_for(0.09, 0.4), Footprint::kHalfCells);
  EXPECT_EQ(footprint_for(0.075, 0.3), Footprint::kHalfCells);  // exactly a quarter cell
  EXPECT_EQ(footprint_for(0.09, 0.3), Footprint::kCells);       // JetBots on the paper's lab grid
  EXPECT_EQ(footprint_for(0.149, 0.3), Footprint::kCells);
  EXPECT_EQ(footprint_for(0.15, 0.3), std::nullopt);  // neighbours would touch
}

// Regression: JetBots (radius 0.09 m) on 0.3 m cells collided, as a follower on an edge
// midpoint was half a cell (0.15 m) from the robot ahead still on the next cell's centre.
TEST(Adg, WideFollowerCrossesAnEdgeOnlyOnceTheRobotAheadReachedTheNextCell) {
  const auto b = build(kAdgRoom, plan_of({{{1, 0}, {2, 0}, {3, 0}}, {{0, 0}, {1, 0}, {2, 0}}}),
                       Footprint::kCells);
  ASSERT_TRUE(b.problems.empty());
  // Robot 0 = nodes 0..3 ((1,0)->mid, mid->(2,0), (2,0)->mid, mid->(3,0)), robot 1 = 4..7.
  // Robot 1 moves onto the edge into (1,0) (node 4) once robot 0 is on (2,0)'s centre (node 1),
  // and onto the edge into (2,0) (node 6) once robot 0 is on (3,0) (node 3).
  EXPECT_EQ(type2_edges(b.adg), (std::set<Edge>{{1, 4}, {3, 6}}));
  EXPECT_EQ(b.adg.footprint, Footprint::kCells);
  EXPECT_TRUE(check_acyclic(b.adg, b.actions, "p").empty());
}

TEST(Adg, WideRobotCrossingWaitsUntilTheFirstHasLeftTheCellsEdge) {
  const auto b =
      build(kAdgRoom, plan_of({{{0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 0}, {1, 1}, {1, 2}}}),
            Footprint::kCells);
  ASSERT_TRUE(b.problems.empty());
  // Robot 0 leaves the edge (1,1)-(2,1) with its action 3; robot 1 (rotation = node 4) then
  // steps onto the edge (1,0)-(1,1) (node 5).
  EXPECT_EQ(type2_edges(b.adg), (std::set<Edge>{{3, 5}}));
}

TEST(Adg, WideRobotsCannotFollowEachOtherRoundALoop) {
  const Cell c[4] = {{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  const auto b = build(kAdgRoom, plan_of({{c[0], c[1]}, {c[1], c[2]}, {c[2], c[3]}, {c[3], c[0]}}),
                       Footprint::kCells);
  ASSERT_TRUE(b.problems.empty());
  const auto cycle = check_acyclic(b.adg, b.actions, "p");
  ASSERT_EQ(cycle.size(), 1u);
  EXPECT_THAT(cycle[0].message, HasSubstr("cannot follow each other round a loop"));
  EXPECT_THAT(cycle[0].message, HasSubstr("--cell-m"));
}

TEST(Adg, WideRobotsParkedForGoodAndSharedStartsAreStillReported) {
  const auto parked =
      build(kAdgRoom, plan_of({{{2, 0}}, {{0, 0}, {1, 0}, {2, 0}}}), Footprint::kCells);
  ASSERT_EQ(parked.problems.size(), 1u);
  EXPECT_THAT(parked.problems[0].message, HasSubstr("parked there for good"));
  const auto shared = build(kAdgRoom, plan_of({{{1, 1}, {2, 1}}, {{1, 1}}}), Footprint::kCells);
  ASSERT_EQ(shared.problems.size(), 1u);
  EXPECT_THAT(shared.problems[0].message, HasSubstr("also starts"));
}

// adg_of_orders over the plan's own passing orders is build_adg's graph (the viewer draws a
// switchable run's edges from it, serve/robot_detail).
TEST(Adg, TheEdgesOfThePlansPassingOrdersAreBuildAdgs) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const auto grid = planning::generate_random_grid(10, 8, 0.15, seed);
    const auto inst = planning::generate_random_plan(grid, {12, 20, seed, 0.7, 0.3});
    const auto actions = build_actions(inst.plan, Heading::kEast);
    for (const auto fp : {Footprint::kHalfCells, Footprint::kCells}) {
      std::vector<Problem> problems;
      const auto adg = build_adg(actions, grid, "random", problems, fp);
      if (!problems.empty()) continue;
      const auto same = adg_of_orders(passing_orders(actions, grid, fp), actions, fp);
      EXPECT_EQ(same.out_begin, adg.out_begin) << "seed " << seed;
      EXPECT_EQ(same.out, adg.out) << "seed " << seed;
      EXPECT_EQ(same.in, adg.in) << "seed " << seed;
    }
  }
}

// A switch names robots that are not adjacent there: skipped and counted.
TEST(Adg, ASwitchMatchingNoPairIsCounted) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(
      plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}}),
      Heading::kEast);
  auto orders = passing_orders(actions, grid);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  // Regression: the largest location (what a row naming no location gets) wrapped to 0 in the
  // bounds check and read far past the orders.
  EXPECT_EQ(apply_switches(orders, {{1.0, cell, 0, 1}, {1.0, 99999, 1, 0}, {1.0, kNoAction, 1, 0}}),
            3u);
  EXPECT_EQ(apply_switches(orders, {{1.0, cell, 1, 0}}), 0u);
  EXPECT_EQ(orders.stays[orders.begin[cell]].robot, 1u);
}

}  // namespace
}  // namespace smart::monitor
