#include "smart/sim/fleet.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/sim_fixtures.hpp"

namespace smart::sim {
namespace {

const grid::Grid kOpen(6, 3, std::vector<uint8_t>(18, 0), "open");

agent::AgentAction move_east(uint32_t seq, double from_x, double to_x, double y) {
  return {seq, agent::ActionKind::kMove, from_x, y, to_x, y, 0.0};
}

TEST(Fleet, StartPosesAreCellCentresInTheWorldFrame) {
  const auto p = start_poses(kOpen, 0.5, {{1, 0}, {3, 2}}, 1.0);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_DOUBLE_EQ(p[0].x_m, 0.5);
  EXPECT_DOUBLE_EQ(p[0].y_m, 1.0);  // row 0 is the top of a 3-row map
  EXPECT_DOUBLE_EQ(p[1].y_m, 0.0);
  EXPECT_DOUBLE_EQ(p[1].yaw_rad, 1.0);
}

TEST(Fleet, StepDrivesEveryAgentThroughItsActions) {
  Fleet fleet(kOpen, test::sim_test_model(), {}, start_poses(kOpen, 1.0, {{0, 0}, {0, 2}}, 0.0));
  fleet.agent(0).on_window(1, {move_east(0, 0, 0.5, 2), move_east(1, 0.5, 1, 2)});
  for (int k = 0; k < 60 && fleet.agent(0).finished_seq() < 1; ++k) fleet.step();
  EXPECT_EQ(fleet.agent(0).finished_seq(), 1);
  EXPECT_NEAR(fleet.world().pose(0).pose.x_m, 1.0, 0.05);
  EXPECT_EQ(fleet.agent(1).finished_seq(), -1);  // no window: stays
  EXPECT_DOUBLE_EQ(fleet.world().pose(1).pose.x_m, 0.0);
  const auto s = fleet.stats();
  EXPECT_GT(s.periods, 5u);
  EXPECT_GT(s.mean_awake_robots, 0.0);
  EXPECT_LT(s.mean_awake_robots, 1.0);  // robot 1 slept throughout
}

TEST(Fleet, ExternalRobotsAreNotDrivenAndSitWhereTheyAreReported) {
  Fleet fleet(kOpen, test::sim_test_model(), {}, start_poses(kOpen, 1.0, {{0, 0}, {0, 2}}, 0.0));
  fleet.set_external(1);
  EXPECT_TRUE(fleet.external(1));
  EXPECT_EQ(fleet.agent(1).state(), agent::LifecycleState::kInactive);
  fleet.agent(1).on_window(1, {move_east(0, 0, 0.5, 0)});
  fleet.world().set_external_pose(1, {4.0, 0.0, 0.0});
  for (int k = 0; k < 10; ++k) fleet.step();
  EXPECT_EQ(fleet.agent(1).finished_seq(), -1);
  EXPECT_NEAR(fleet.world().pose(1).pose.x_m, 4.0, 0.1);
  EXPECT_THROW(fleet.set_external(7), std::invalid_argument);
}

}  // namespace
}  // namespace smart::sim
