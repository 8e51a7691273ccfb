#include "smart/monitor/plan_validator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/plan_reader.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using test::grid_of;
using test::plan_of;
using ::testing::HasSubstr;

std::string all(const std::vector<Problem>& problems) {
  std::string s;
  for (const auto& p : problems) s += p.to_string() + "\n";
  return s;
}

const Grid kGrid = grid_of({
    ".....",
    ".@...",
    ".....",
});

TEST(PlanValidator, FollowingAndStandingStillAreValid) {
  // Robot 1 enters each cell as robot 0 leaves it; robot 2 never moves.
  const auto plan = plan_of({{{1, 0}, {2, 0}, {3, 0}}, {{0, 0}, {1, 0}, {2, 0}}, {{4, 2}}});
  const auto scen = test::scen_of(plan, kGrid);
  EXPECT_EQ(all(validate_plan(plan, kGrid, &scen)), "");
}

TEST(PlanValidator, RotationCycleIsValid) {
  const auto plan =
      plan_of({{{2, 0}, {3, 0}}, {{3, 0}, {3, 1}}, {{3, 1}, {2, 1}}, {{2, 1}, {2, 0}}});
  EXPECT_EQ(all(validate_plan(plan, kGrid)), "");
}

TEST(PlanValidator, OutsideObstacleAndJump) {
  const auto plan = plan_of({{{0, 0}, {0, 1}, {1, 1}}, {{4, 0}, {5, 0}}, {{0, 2}, {2, 2}}});
  const auto e = all(validate_plan(plan, kGrid));
  EXPECT_THAT(e, HasSubstr("robot 0: step 2 at t=2 moves into the obstacle at (x=1,y=1)"));
  EXPECT_THAT(e, HasSubstr("robot 1: step 1 at t=1 is (x=5,y=0), outside the 5x3 map"));
  EXPECT_THAT(e, HasSubstr("robot 2: step 1 jumps from (x=0,y=2) to (x=2,y=2) at t=1"));
}

TEST(PlanValidator, TimesMustIncrease) {
  auto plan = plan_of({{{0, 0}, {1, 0}, {2, 0}}});
  plan.paths[0].steps[2].time = 1.0;
  EXPECT_THAT(all(validate_plan(plan, kGrid)),
              HasSubstr("step 2 has t=1, not after the previous step's t=1"));
}

TEST(PlanValidator, VertexConflictNamesBothRobotsCellAndTime) {
  const auto plan = plan_of({{{0, 0}, {1, 0}, {2, 0}}, {{2, 2}, {2, 1}, {2, 0}}});
  EXPECT_THAT(
      all(validate_plan(plan, kGrid)),
      HasSubstr("fixture.txt:2: robot 1: vertex conflict with robot 0 at (x=2,y=0) at t=2"));
}

TEST(PlanValidator, SwapConflict) {
  const auto plan = plan_of({{{0, 0}, {1, 0}}, {{1, 0}, {0, 0}}});
  EXPECT_THAT(all(validate_plan(plan, kGrid)),
              HasSubstr("swap conflict with robot 0: it moves (x=1,y=0)->(x=0,y=0)"));
}

TEST(PlanValidator, PassingARobotParkedAtItsGoal) {
  // Robot 0 reaches (2,0) at t=1 and stays; robot 1 comes through at t=3.
  const auto plan = plan_of({{{1, 0}, {2, 0}}, {{0, 0}, {0, 0}, {1, 0}, {2, 0}, {3, 0}}});
  EXPECT_THAT(all(validate_plan(plan, kGrid)),
              HasSubstr("robot 1: enters (x=2,y=0) at t=3 where robot 0 is parked at its goal "
                        "since t=1"));
}

TEST(PlanValidator, ScenarioMismatchesAndAxisHint) {
  const auto plan = plan_of({{{0, 1}, {0, 2}}, {{2, 0}, {3, 0}}});
  Scenario scen;
  scen.source = "s.scen";
  scen.agents = {{{1, 0}, {2, 0}, 2}, {{0, 2}, {0, 3}, 3}};
  const auto problems = validate_plan(plan, kGrid, &scen);
  const auto e = all(problems);
  EXPECT_THAT(problems[0].message, HasSubstr("pass --axis rowcol"));
  EXPECT_THAT(e, HasSubstr("robot 0: starts at (x=0,y=1) but the scenario (line 2) starts it at "
                           "(x=1,y=0)"));
  EXPECT_THAT(e, HasSubstr("robot 1: ends at (x=3,y=0) but the scenario (line 3) has its goal"));
  scen.agents.pop_back();
  EXPECT_THAT(all(validate_plan(plan, kGrid, &scen)),
              HasSubstr("the plan has 2 robots but the scenario s.scen only 1"));
}

TEST(PlanValidator, ContinuousTimeOverlapIsAConflict) {
  auto plan = plan_of({{{0, 0}, {1, 0}}, {{2, 0}, {1, 0}}});
  plan.paths[0].steps[1].time = 0.5;  // robot 0 holds (1,0) from 0.5 on, robot 1 arrives at 1
  EXPECT_THAT(all(validate_plan(plan, kGrid)), HasSubstr("(x=1,y=0)"));
}

TEST(PlanValidator, EveryExamplePlanIsValidAndTheWrongAxisIsCaught) {
  const auto dir = test::benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(dir)) << smart::test::no_benchmarks(dir);
  const auto grid = parse_map(read_text_file(dir / "maps/random-32-32-20.map", "map"), "map");
  const auto scen =
      parse_scen(read_text_file(dir / "scens/random-32-32-20-random-1.scen", "scen"), "scen", 50);
  const auto text = read_text_file(dir / "smart-examples/example_paths_yx.txt", "plan");
  const auto ok = parse_plan(text, "yx", {PlanFormat::kAuto, AxisOrder::kRowCol});
  EXPECT_EQ(all(validate_plan(ok, grid, &scen)), "");
  const auto wrong = parse_plan(text, "yx", {PlanFormat::kAuto, AxisOrder::kXY});
  const auto problems = validate_plan(wrong, grid, &scen);
  ASSERT_FALSE(problems.empty());
  EXPECT_THAT(problems[0].message, HasSubstr("pass --axis rowcol"));
}

}  // namespace
}  // namespace smart::monitor
