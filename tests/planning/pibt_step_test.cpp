// One PIBT step (pibt_step.hpp): priority inheritance and backtracking, and LaCAM's constraints
// (fix): never two robots on one cell, never a swap, and a robot left without a cell reported.
#include "smart/planning/pibt_step.hpp"

#include <gtest/gtest.h>

#include "smart/planning/distance_cache.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::planning {
namespace {

using grid::Cell;

struct Fixture {
  explicit Fixture(const std::vector<std::string>& rows, const std::vector<Cell>& from,
                   const std::vector<Cell>& goal)
      : g(test::grid_of(rows)), tables(g), heur(tables), step(g) {
    for (uint32_t i = 0; i < goal.size(); ++i) heur.aim(i, from[i], goal[i]);
    step.begin(from);
  }
  grid::Grid g;
  DistanceCache tables;
  TableHeuristic heur;
  PibtStep step;
  std::mt19937_64 rng{1};
};

TEST(PibtStep, ARobotOnTheWayIsAskedToMoveFirstAndDoes) {
  // Robot 0 heads right along a corridor; robot 1 stands in front of it and wants to stay.
  Fixture f({"...."}, {{0, 0}, {1, 0}}, {{3, 0}, {1, 0}});
  EXPECT_TRUE(f.step.plan(0, f.heur, f.rng));
  EXPECT_EQ(f.step.to()[0], (Cell{1, 0}));
  EXPECT_EQ(f.step.to()[1], (Cell{2, 0})) << "pushed on, not back into robot 0 (a swap)";
  EXPECT_TRUE(f.step.planned(1));
}

TEST(PibtStep, WhenTheRobotAheadCannotMoveTheAskerTriesItsNextCell) {
  // Robot 1 is at the corridor's dead end: robot 0 backtracks and stays.
  Fixture f({".."}, {{0, 0}, {1, 0}}, {{1, 0}, {1, 0}});
  EXPECT_TRUE(f.step.plan(0, f.heur, f.rng));
  EXPECT_EQ(f.step.to()[0], (Cell{0, 0}));
  EXPECT_EQ(f.step.to()[1], (Cell{1, 0}));
}

TEST(PibtStep, FixRefusesACellTakenAndASwap) {
  Fixture f({"...."}, {{0, 0}, {1, 0}, {3, 0}}, {{3, 0}, {0, 0}, {3, 0}});
  EXPECT_TRUE(f.step.fix(0, {1, 0}));
  EXPECT_FALSE(f.step.fix(1, {0, 0})) << "robots 0 and 1 would swap";
  EXPECT_FALSE(f.step.fix(2, {1, 0})) << "robot 0 goes there";
  EXPECT_FALSE(f.step.planned(2));
  EXPECT_TRUE(f.step.fix(2, {3, 0}));
}

TEST(PibtStep, ARobotWhoseCellAFixedRobotTakesMovesOnOrReportsThatItCannot) {
  // Robot 0 is fixed onto robot 1's cell: robot 1 must leave, away from robot 0.
  Fixture open({"..."}, {{0, 0}, {1, 0}}, {{1, 0}, {1, 0}});
  ASSERT_TRUE(open.step.fix(0, {1, 0}));
  EXPECT_TRUE(open.step.plan(1, open.heur, open.rng));
  EXPECT_EQ(open.step.to()[1], (Cell{2, 0}));
  // No cell left for robot 1: it may not swap into robot 0's cell.
  Fixture boxed({".."}, {{0, 0}, {1, 0}}, {{1, 0}, {1, 0}});
  ASSERT_TRUE(boxed.step.fix(0, {1, 0}));
  EXPECT_FALSE(boxed.step.plan(1, boxed.heur, boxed.rng));
}

TEST(PibtStep, WithSwapsARobotPullsTheOneOnItsGoalOutOfADeadEnd) {
  // Robot 1 stands in the dead end (0, 0) that is robot 0's goal, and must get past robot 0 to
  // (4, 0); the corridor forks at (3, 0). Plain PIBT steps leave both where they are; with swaps
  // robot 0 steps back and pulls robot 1 after it, towards the fork.
  const std::vector<std::string> rows{".....", "@@@.@"};
  const std::vector<Cell> from{{1, 0}, {0, 0}}, goal{{0, 0}, {4, 0}};
  Fixture plain(rows, from, goal);
  EXPECT_TRUE(plain.step.plan(0, plain.heur, plain.rng));
  EXPECT_EQ(plain.step.to(), from);
  Fixture swapping(rows, from, goal);
  swapping.step.enable_swaps(goal);
  EXPECT_TRUE(swapping.step.plan(0, swapping.heur, swapping.rng));
  EXPECT_EQ(swapping.step.to()[0], (Cell{2, 0}));
  EXPECT_EQ(swapping.step.to()[1], (Cell{1, 0})) << "pulled into robot 0's cell";
  EXPECT_TRUE(swapping.step.planned(1));
}

TEST(PibtStep, NoSwapWhereTheCorridorEndsBeforeAFork) {
  // As above, but nothing forks: pulling would only push both into the other dead end.
  const std::vector<std::string> rows{"....."};
  const std::vector<Cell> from{{1, 0}, {0, 0}}, goal{{0, 0}, {4, 0}};
  Fixture f(rows, from, goal);
  f.step.enable_swaps(goal);
  EXPECT_TRUE(f.step.plan(0, f.heur, f.rng));
  EXPECT_EQ(f.step.to(), from);
}

TEST(PibtStep, EndForgetsTheStepSoTheNextBeginsClean) {
  Fixture f({"..."}, {{0, 0}, {2, 0}}, {{1, 0}, {2, 0}});
  ASSERT_TRUE(f.step.plan(0, f.heur, f.rng));
  ASSERT_TRUE(f.step.plan(1, f.heur, f.rng));
  f.step.end();
  f.step.begin({{1, 0}, {2, 0}});
  EXPECT_FALSE(f.step.planned(0));
  EXPECT_TRUE(f.step.fix(1, {2, 0})) << "no reservation left from the last step";
  EXPECT_TRUE(f.step.plan(0, f.heur, f.rng));
  EXPECT_EQ(f.step.to()[0], (Cell{1, 0}));
}

}  // namespace
}  // namespace smart::planning
