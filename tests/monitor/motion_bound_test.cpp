// The motion lower bound on hand-computed profiles.
#include "smart/monitor/motion_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "smart/monitor/action_builder.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

TEST(MotionBound, TrapezoidAndTriangleProfiles) {
  // 1 m/s, 0.5 m/s² both ways: ramps of 1 m each; 4 m = 2 m at speed (2 s) + two 2 s ramps.
  EXPECT_DOUBLE_EQ(rest_to_rest_s(4.0, 1.0, 0.5, 0.5), 6.0);
  // 1 m never reaches 1 m/s: peak sqrt(0.5) m/s, sqrt(2) s up and down.
  EXPECT_NEAR(rest_to_rest_s(1.0, 1.0, 0.5, 0.5), 2 * std::sqrt(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(rest_to_rest_s(0.0, 1.0, 0.5, 0.5), 0.0);
}

TEST(MotionBound, ARobotsRunsAndTurnsAddUp) {
  // Robot 0: two cells east (one run of 2 m), then a quarter turn north and one cell (1 m).
  const auto plan = test::plan_of({{{0, 2}, {1, 2}, {2, 2}, {2, 1}}, {{0, 0}, {0, 0}}});
  const auto actions = build_actions(plan, Heading::kEast);
  MotionLimits l{1.0, 0.5, 0.5, std::numbers::pi / 2, 100.0};
  const auto b = motion_lower_bounds_s(actions, 1.0, l);
  ASSERT_EQ(b.size(), 2u);
  const double turn = rest_to_rest_s(std::numbers::pi / 2, std::numbers::pi / 2, 100, 100);
  EXPECT_NEAR(b[0], rest_to_rest_s(2.0, 1, 0.5, 0.5) + turn + rest_to_rest_s(1.0, 1, 0.5, 0.5),
              1e-12);
  EXPECT_GT(turn, 1.0);         // 90° at 90°/s, plus a little for the ramps
  EXPECT_DOUBLE_EQ(b[1], 0.0);  // never moves
}

}  // namespace
}  // namespace smart::monitor
