#include "smart/monitor/plan_view.hpp"

#include <gtest/gtest.h>

#include "support/following_fixture.hpp"

namespace smart::monitor {
namespace {

using test::Following;

TEST(PlanView, PlannedPathIsTheStartAndEveryMovesEndInTheWorldFrame) {
  Following f;
  const auto path = planned_path(f.actions, f.grid, 0, 0.5);
  ASSERT_EQ(path.size(), 5u);  // start + 4 half-moves
  EXPECT_DOUBLE_EQ(path.front().x_m, 0.5);
  EXPECT_DOUBLE_EQ(path.front().y_m, 0.5);  // row 0 of 2 is y = 1 cell up
  EXPECT_DOUBLE_EQ(path[1].x_m, 0.75);
  EXPECT_DOUBLE_EQ(path.back().x_m, 1.5);
}

TEST(PlanView, SnapshotShowsWhoWaitsForWhomAsTheRunGoes) {
  Following f;
  ExecutionTracker t(f.actions, f.adg);
  auto s = snapshot(f.actions, f.adg, t);
  EXPECT_EQ(s.activity, (std::vector<Activity>{Activity::kMoving, Activity::kMoving}));
  EXPECT_TRUE(s.waits.empty());
  t.on_progress(1, 0);  // robot 1 reached the half-cell behind robot 0: it must wait now
  s = snapshot(f.actions, f.adg, t);
  EXPECT_EQ(s.activity[1], Activity::kWaiting);
  EXPECT_EQ(s.waits, (std::vector<WaitEdge>{{1, 0}}));
  t.on_progress(0, 0);  // robot 0 moved on: robot 1 may follow
  s = snapshot(f.actions, f.adg, t);
  EXPECT_EQ(s.activity[1], Activity::kMoving);
  EXPECT_TRUE(s.waits.empty());
  t.on_progress(0, 3);
  t.on_progress(1, 3);
  s = snapshot(f.actions, f.adg, t);
  EXPECT_EQ(s.activity, (std::vector<Activity>{Activity::kDone, Activity::kDone}));
}

}  // namespace
}  // namespace smart::monitor
