// What the viewer shows of one robot, on a two-robot corridor with one Type-2 edge.
#include "smart/serve/robot_detail.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "smart/monitor/plan_validator.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::serve {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

// Robot 0 drives (1,0) -> (2,0); robot 1 follows into (1,0) a step later, so robot 1's second
// half-move (into (1,0)) waits for robot 0's first (out of (1,0)'s centre).
monitor::Instance corridor() {
  monitor::Instance in;
  in.grid = test::grid_of({"...."});
  in.plan = test::plan_of({{{1, 0}, {2, 0}, {2, 0}}, {{0, 0}, {0, 0}, {1, 0}}});
  in.scen = test::scen_of(in.plan, in.grid);
  in.actions = monitor::build_actions(in.plan, monitor::Heading::kEast);
  std::vector<monitor::Problem> problems;
  in.adg = monitor::build_adg(in.actions, in.grid, "fixture", problems);
  return in;
}

constexpr const char* kActionsCsv =
    "robot,action,type,finish_time_s\n0,0,move,1\n0,1,move,2\n1,0,move,0.5\n1,1,move,\n";

TEST(RobotDetail, PathAndPartnersComeFromThePlanAndTheAdg) {
  const auto in = corridor();
  const auto d = robot_detail(in, 1, 0.5);
  EXPECT_EQ(d["actions"], 2);
  EXPECT_EQ(d["path"], json::parse("[[0.0, 0.0], [0.5, 0.0]]"));
  EXPECT_EQ(d["waits_for"], json::parse(R"([{"robot": 0, "edges": 1}])"));
  EXPECT_TRUE(d["waited_by"].empty());
  EXPECT_TRUE(d["steps"][1]["finish_s"].is_null());  // no actions.csv: no times
}

// Issue 26: no start or goal marks; the viewer marks each robot's plan start and goal.
TEST(RobotDetail, EveryRobotsStartAndGoalFromThePlan) {
  const auto in = corridor();
  const auto m = starts_and_goals(in, 0.5);
  EXPECT_EQ(m["starts"], json::parse("[[0.5, 0.0], [0.0, 0.0]]"));
  EXPECT_EQ(m["goals"], json::parse("[[1.0, 0.0], [0.5, 0.0]]"));
}

TEST(RobotDetail, StepsTellWhenEachActionFinishedAndWhenItsPartnersDid) {
  const auto in = corridor();
  const auto times = parse_action_times(kActionsCsv, in.actions);
  const auto waiter = robot_detail(in, 1, 1.0, times);
  EXPECT_EQ(waiter["steps"][0]["finish_s"], 0.5);
  EXPECT_TRUE(waiter["steps"][1]["finish_s"].is_null());
  EXPECT_EQ(waiter["steps"][1]["in"], json::parse("[[0, 0, 1.0]]"));  // waits until 1 s
  const auto leader = robot_detail(in, 0, 1.0, times);
  EXPECT_EQ(leader["steps"][0]["type"], "move");
  // Robot 1 was ready for its second half-move at 0.5 s: it waited for robot 0 from then on.
  EXPECT_EQ(leader["steps"][0]["out"], json::parse("[[1, 1, 0.5]]"));
  EXPECT_TRUE(leader["steps"][1]["out"].empty());
}

TEST(RobotDetail, ActionTimesThatDoNotFitThePlanNameTheLine) {
  const auto in = corridor();
  for (const char* bad :
       {"h\n0,0,move,1\n5,0,move,1\n", "h\n0,0,move,1\n0,9,move,1\n",
        "h\n0,0,move,1\n0,1,move,soon\n", "h\n0,0,move,1\n0,1\n", "h\n0,0,move,1\n0,1,move,-3\n"}) {
    try {
      (void)parse_action_times(bad, in.actions);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("actions.csv line 3")) << bad;
    }
  }
  EXPECT_THROW((void)robot_detail(in, 2, 1.0), std::out_of_range);
}

TEST(FinishedCurve, CountsFinishedActionsOverTimeInAtMostMaxPoints) {
  const auto c = finished_curve({3, 1, std::nan(""), 2, 2, 5}, 400);
  EXPECT_EQ(c["t_s"], json::parse("[1.0, 2.0, 2.0, 3.0, 5.0]"));
  EXPECT_EQ(c["finished"], json::parse("[1, 2, 3, 4, 5]"));
  std::vector<double> many(1000);
  for (std::size_t i = 0; i < many.size(); ++i) many[i] = 0.5 * double(i);
  const auto d = finished_curve(many, 100);
  EXPECT_LE(d["t_s"].size(), 101u);
  EXPECT_EQ(d["finished"].back(), 1000);
  EXPECT_EQ(d["t_s"].back(), 499.5);
  EXPECT_EQ(d["finished"][0], 10);
  EXPECT_EQ(d["t_s"][0], 4.5);  // the 10th action finished at 4.5 s
  EXPECT_TRUE(finished_curve({}, 10)["t_s"].empty());
}

// Issue 29: a switchable run shown with the orders it ended with. Robot 0 crosses (2,1) west to
// east before robot 1 goes north to south in the plan; switches.csv says robot 1 passed first.
// The flipped edge carries `true`; a row off the map or naming robots not adjacent is skipped.
TEST(RobotDetail, ASwitchableRunShowsItsFlippedEdges) {
  monitor::Instance in;
  in.grid = test::grid_of({"....", "....", "...."});
  in.plan =
      test::plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}});
  in.scen = test::scen_of(in.plan, in.grid);
  in.actions = monitor::build_actions(in.plan, monitor::Heading::kEast);
  std::vector<monitor::Problem> problems;
  in.adg = monitor::build_adg(in.actions, in.grid, "fixture", problems);
  ASSERT_TRUE(problems.empty());
  // Plan: robot 1's entry into (2,1) (its action 2, after a turn south and a half-move) waits for
  // robot 0's leaving it (action 4).
  EXPECT_EQ(robot_detail(in, 1, 1.0)["steps"][2]["in"], json::parse("[[0, 4, null]]"));
  std::size_t unmatched = 0;
  const auto ended =
      ended_adg(in, {{1.0, 2, 1, 1, 0}, {1.0, 7, 1, 1, 0}, {1.0, 2, 0, 1, 0}}, {}, &unmatched);
  EXPECT_EQ(unmatched, 2u);  // (7, 1) is off the 4-wide map; (2, 0) has no such pair
  const auto late = robot_detail(in, 0, 1.0, {}, &ended);
  EXPECT_EQ(late["steps"][3]["in"], json::parse("[[1, 3, null, true]]"));  // waits for robot 1
  EXPECT_EQ(late["waits_for"], json::parse(R"([{"robot": 1, "edges": 1}])"));
  const auto ready = robot_detail(in, 1, 1.0, {}, &ended);
  EXPECT_TRUE(ready["steps"][2]["in"].empty());
  EXPECT_EQ(ready["steps"][3]["out"], json::parse("[[0, 3, null, true]]"));  // no times given
}

}  // namespace
}  // namespace smart::serve
