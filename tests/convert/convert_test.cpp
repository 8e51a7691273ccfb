// The one conversion between core types and wire types, both ways.
#include "smart/convert/convert.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace smart::wire {
namespace {

TEST(Convert, AnActionReachesTheAgentInWorldMetresWithItsHalfCells) {
  const grid::Grid g(4, 3, std::vector<uint8_t>(12, 0));
  grid::Action a{2, 5, grid::ActionType::kMove, grid::Heading::kNorth, {2, 4}, {2, 3}, 1.0, 1.5};
  const auto step = to_wire(a, g, 0.5);
  EXPECT_EQ(step.seq, 5u);
  EXPECT_EQ(step.type, smart_msg_ACTION_MOVE);
  EXPECT_EQ(step.from.col2, 2);
  EXPECT_EQ(step.to.row2, 3);
  EXPECT_DOUBLE_EQ(step.from.x_m, 0.5);
  EXPECT_DOUBLE_EQ(step.from.y_m, 0.0);  // row 2 of 3 is the bottom
  EXPECT_DOUBLE_EQ(step.to.y_m, 0.25);   // half a cell up
  EXPECT_DOUBLE_EQ(step.plan_time_s, 1.0);
  const auto back = from_wire(step);
  EXPECT_EQ(back.seq, 5u);
  EXPECT_EQ(back.kind, agent::ActionKind::kMove);
  EXPECT_DOUBLE_EQ(back.to_y_m, 0.25);
  EXPECT_DOUBLE_EQ(back.heading_rad, std::numbers::pi / 2);
  a.type = grid::ActionType::kRotate;
  EXPECT_EQ(from_wire(to_wire(a, g, 1.0)).kind, agent::ActionKind::kRotate);
}

TEST(Convert, ClockRoundTripsAndCarriesTheSender) {
  const Tick t{9, 12, 1.2, 40, true};
  const auto c = to_wire(t, 1);
  EXPECT_EQ(c.source_id, 1u);
  const Tick back = from_wire(c);
  EXPECT_EQ(back.run_id, 9u);
  EXPECT_EQ(back.tick, 12u);
  EXPECT_DOUBLE_EQ(back.sim_time_s, 1.2);
  EXPECT_EQ(back.sync_total, 40u);
  EXPECT_TRUE(back.stop);
}

TEST(Convert, RobotStateAndProgress) {
  agent::PoseSample p;
  p.pose = {1, 2, 0.5};
  p.linear_mps = 0.3;
  const auto s = robot_state(3, 8, 4.5, p, {0.1, 0.2}, 6);
  EXPECT_EQ(s.robot_id, 3u);
  EXPECT_DOUBLE_EQ(s.pose.yaw_rad, 0.5);
  EXPECT_DOUBLE_EQ(s.wheel_right_mps, 0.2);
  EXPECT_EQ(s.queue_length, 6u);
  const auto pr = progress(3, 8, -1, 4);
  EXPECT_EQ(pr.finished_seq, -1);
  EXPECT_EQ(pr.executing_seq, 4);
}

}  // namespace
}  // namespace smart::wire
