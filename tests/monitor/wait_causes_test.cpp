// monitor/wait_causes.hpp: a plain ADG run's waits charged to the robot waited for, split by
// what it was doing meanwhile, on two-robot plans with scripted finish times (exact numbers).
#include "smart/monitor/wait_causes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "smart/monitor/action_builder.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using test::plan_of;

// Finish times by node: each robot's, in its actions' order.
std::vector<double> times(const ActionPlan& a, std::vector<std::vector<double>> per_robot) {
  std::vector<double> t;
  for (uint32_t r = 0; r < a.robots(); ++r) {
    EXPECT_EQ(per_robot[r].size(), a.count(r)) << "robot " << r;
    t.insert(t.end(), per_robot[r].begin(), per_robot[r].end());
  }
  return t;
}

const Grid kRoom(4, 3, std::vector<uint8_t>(12, 0));

// The crossing of switchable_tracker_test: robot 0 crosses cell (2, 1) eastwards at t = 2,
// robot 1 southwards at t = 3, after it. Robot 0: half-moves (1, 1) -> (2, 1) (seq 2, 3: its
// entry), out (4, 5). Robot 1: rotates south (0), half-moves to the cell's edge (1), in (2), out
// (3, 4). Robot 0 is late: its actions end at 4, 5, ..., 9 s. Robot 1 reaches the edge at 2 s
// and waits until robot 0 has left the cell (its seq 4, at 8 s): 6 s, of which robot 0 was on
// its way until it began its entry at 6 s (4 s: a switch could have let robot 1 go), entering
// until 7 s (1 s) and in the cell until 8 s (1 s).
TEST(WaitCauses, AWaitBehindALateRobotIsSplitByWhereThatRobotWas) {
  const auto actions = build_actions(
      plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}}),
      Heading::kEast);
  ASSERT_EQ(actions.count(0), 6u);
  ASSERT_EQ(actions.count(1), 5u);
  const auto w = wait_causes(actions, passing_orders(actions, kRoom),
                             times(actions, {{4, 5, 6, 7, 8, 9}, {1, 2, 9, 10, 11}}));
  EXPECT_EQ(w.waits, 1u);
  EXPECT_DOUBLE_EQ(w.total_s, 6.0);
  EXPECT_DOUBLE_EQ(w.on_its_way_s, 4.0);
  EXPECT_DOUBLE_EQ(w.entering_s, 1.0);
  EXPECT_DOUBLE_EQ(w.at_location_s, 1.0);
}

// On time, robot 1 waits at the edge only while robot 0 is in the cell: robot 0's entry ends at
// 4 s (seq 3), its leave at 5 s; robot 1 is at the edge at 4.5 s and waits 0.5 s, all of it
// behind a robot at the location.
TEST(WaitCauses, AWaitBehindARobotInTheCellIsAtTheLocation) {
  const auto actions = build_actions(
      plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}}),
      Heading::kEast);
  const auto w = wait_causes(actions, passing_orders(actions, kRoom),
                             times(actions, {{1, 2, 3, 4, 5, 6}, {3.5, 4.5, 6, 7, 8}}));
  EXPECT_EQ(w.waits, 1u);
  EXPECT_DOUBLE_EQ(w.total_s, 0.5);
  EXPECT_DOUBLE_EQ(w.at_location_s, 0.5);
  EXPECT_DOUBLE_EQ(w.on_its_way_s + w.entering_s, 0.0);
}

// Robot 1 stands on (1, 1) from the start and leaves it eastwards at t = 1; robot 0 follows it
// in at t = 2. Robot 1 is late (its first half-move ends at 5 s): robot 0, at the cell's edge at
// 1 s, waits 4 s behind a robot that was there from the start.
TEST(WaitCauses, ARobotThatStartedOnTheLocationIsAtIt) {
  const auto actions =
      build_actions(plan_of({{{0, 1}, {0, 1}, {1, 1}}, {{1, 1}, {2, 1}}}), Heading::kEast);
  ASSERT_EQ(actions.count(0), 2u);
  ASSERT_EQ(actions.count(1), 2u);
  const auto w =
      wait_causes(actions, passing_orders(actions, kRoom), times(actions, {{1, 6}, {5, 6}}));
  EXPECT_EQ(w.waits, 1u);
  EXPECT_DOUBLE_EQ(w.total_s, 4.0);
  EXPECT_DOUBLE_EQ(w.at_location_s, 4.0);
}

// A queue: robot 2 crosses (1, 1) southwards before robot 0 comes through it eastwards, and
// robot 0 crosses (2, 1) before robot 1, as in the crossing. Robot 2 is late (its actions end at
// 5-9 s; it leaves (1, 1) with seq 3 at 8 s). Robot 0, at the edge of (1, 1) at 1 s, waits 7 s
// for it: 5 s while robot 2 was on its way (its entry, seq 2, began at 6 s), 1 s entering, 1 s
// in the cell. Robot 1, at the edge of (2, 1) at 2 s, waits 10 s for robot 0 (it leaves at
// 12 s): 8 s on its way (its entry began at 10 s), of which robot 0 itself waited 6 s (2-8 s,
// for robot 2), 1 s entering, 1 s in the cell. With entries sent one action ahead, robot 2's
// was unsent until 5 s (its seq 0 ended) and robot 0's until 9 s (seq 1): 4 s + 7 s of the
// waits were behind an entry a switch could still take; six actions ahead, none.
Plan queue() {
  return plan_of({{{0, 1}, {0, 1}, {0, 1}, {1, 1}, {2, 1}, {3, 1}},
                  {{2, 0}, {2, 0}, {2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}},
                  {{1, 0}, {1, 1}, {1, 2}}});
}

TEST(WaitCauses, AWaitBehindARobotThatWaitsInAQueueIsCountedAsItsWaiting) {
  const auto actions = build_actions(queue(), Heading::kEast);
  ASSERT_EQ(actions.count(2), 5u);
  const auto t = times(actions, {{1, 9, 10, 11, 12, 13}, {1, 2, 13, 14, 15}, {5, 6, 7, 8, 9}});
  const auto orders = passing_orders(actions, kRoom);
  const auto w = wait_causes(actions, orders, t, 1);
  EXPECT_EQ(w.waits, 2u);
  EXPECT_DOUBLE_EQ(w.total_s, 17.0);
  EXPECT_DOUBLE_EQ(w.on_its_way_s, 13.0);
  EXPECT_DOUBLE_EQ(w.on_its_way_waiting_s, 6.0);
  EXPECT_DOUBLE_EQ(w.uncommitted_s, 11.0);
  EXPECT_DOUBLE_EQ(w.uncommitted_cycle_s, 0.0);  // crossings: each could have passed
  EXPECT_DOUBLE_EQ(w.entering_s, 2.0);
  EXPECT_DOUBLE_EQ(w.at_location_s, 2.0);
  EXPECT_DOUBLE_EQ(wait_causes(actions, orders, t, 6).uncommitted_s, 0.0);
}

// Following: robot 1 comes down into (1, 1) after robot 0 has crossed it eastwards and follows
// it east to (2, 1). Robot 0 is late (its actions end at 5-10 s); robot 1 waits at the edge of
// (1, 1) from 2 s until robot 0 leaves it (seq 2, 7 s), 3 s of it before robot 0 began its entry.
// Letting robot 1 in first would close a cycle: to leave (1, 1) eastwards it must wait for robot 0
// to pass the edge midpoint ahead, which robot 0 reaches only through (1, 1).
TEST(WaitCauses, PassingARobotThatGoesOnAheadWouldCloseACycle) {
  const auto actions =
      build_actions(plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, {{1, 0}, {1, 0}, {1, 1}, {2, 1}}}),
                    Heading::kEast);
  ASSERT_EQ(actions.count(1), 6u);
  const auto w = wait_causes(actions, passing_orders(actions, kRoom),
                             times(actions, {{5, 6, 7, 8, 9, 10}, {1, 2, 8, 9, 10, 11}}), 0);
  EXPECT_EQ(w.waits, 1u);
  EXPECT_DOUBLE_EQ(w.total_s, 5.0);
  EXPECT_DOUBLE_EQ(w.on_its_way_s, 3.0);
  EXPECT_DOUBLE_EQ(w.uncommitted_s, 3.0);
  EXPECT_DOUBLE_EQ(w.uncommitted_cycle_s, 3.0);
}

// A run that ended early: the actions after one never finished are not counted.
TEST(WaitCauses, ActionsAfterOneNeverFinishedAreNotCounted) {
  const auto actions = build_actions(
      plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}}),
      Heading::kEast);
  constexpr double kNever = std::numeric_limits<double>::quiet_NaN();
  const auto w = wait_causes(
      actions, passing_orders(actions, kRoom),
      times(actions, {{4, 5, kNever, kNever, kNever, kNever}, {1, 2, kNever, kNever, kNever}}));
  EXPECT_EQ(w.waits, 0u);
  EXPECT_DOUBLE_EQ(w.total_s, 0.0);
}

TEST(WaitCauses, FinishTimesOfAnotherPlanAreRefused) {
  const auto actions = build_actions(plan_of({{{0, 1}, {1, 1}}}), Heading::kEast);
  EXPECT_THROW(wait_causes(actions, passing_orders(actions, kRoom), {1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace smart::monitor
