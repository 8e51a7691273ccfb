// The controller against a kinematic robot: goals reached within tolerance, limits respected at
// every control step.
#include "smart/agent/controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "smart/agent/kinematics.hpp"
#include "smart/agent/robot_model.hpp"
#include "support/fake_robot.hpp"
#include "support/robot_models.hpp"

namespace smart::agent {
namespace {

constexpr double kDt = 0.1;
constexpr double kEps = 1e-9;

// Checks the limits on consecutive commands.
struct LimitChecker {
  const RobotModel& m;
  Twist prev{};
  int steps = 0;
  double max_v = 0;
  void check(Twist t) {
    ++steps;
    EXPECT_LE(std::abs(t.linear_mps), m.max_speed_mps + kEps) << "step " << steps;
    EXPECT_LE(std::abs(t.angular_radps), m.max_turn_rate_radps + kEps) << "step " << steps;
    const double dv = t.linear_mps - prev.linear_mps;
    const bool speeding_up = std::abs(t.linear_mps) > std::abs(prev.linear_mps);
    EXPECT_LE(std::abs(dv), (speeding_up ? m.max_accel_mps2 : m.max_decel_mps2) * kDt + kEps)
        << "step " << steps;
    EXPECT_LE(std::abs(t.angular_radps - prev.angular_radps),
              m.max_angular_accel_radps2 * kDt + kEps)
        << "step " << steps;
    const auto w = to_wheels(t, m.wheel_base_m);
    EXPECT_LE(std::max(std::abs(w.left_mps), std::abs(w.right_mps)), m.max_speed_mps + kEps);
    max_v = std::max(max_v, std::abs(t.linear_mps));
    prev = t;
  }
};

TEST(Controller, ReachesAGoalTenMetresAwayWithinTwoCentimetresAndOneDegree) {
  const auto m = test::footbot_model();
  Controller c(m, kDt);
  test::FakeRobot robot(m.wheel_base_m);
  LimitChecker limits{m};
  const Segment seg{0, 0, 10, 0, 0};
  bool done = false;
  for (int i = 0; i < 2000 && !done; ++i) {
    const Twist t = c.drive(robot.read(), seg, &done);
    limits.check(t);
    robot.set_wheel_speeds(c.wheels(t));
    robot.advance(kDt);
  }
  ASSERT_TRUE(done);
  EXPECT_NEAR(robot.pose().x_m, 10.0, 0.02);
  EXPECT_NEAR(robot.pose().y_m, 0.0, 0.02);
  EXPECT_LT(std::abs(robot.pose().yaw_rad), std::numbers::pi / 180);
  // A trapezoid: 0.4 m/s² over 5 m reaches 2 m/s before braking.
  EXPECT_GT(limits.max_v, 1.8);
  // Minimum time for 10 m at 0.4 m/s² (triangle profile) is 2·sqrt(10/0.4) = 10 s.
  EXPECT_LT(limits.steps * kDt, 14.0);
}

TEST(Controller, CorrectsALateralOffsetWhileDriving) {
  const auto m = test::footbot_model();
  Controller c(m, kDt);
  test::FakeRobot robot(m.wheel_base_m, {0.0, 0.1, 0.0});
  bool done = false;
  for (int i = 0; i < 2000 && !done; ++i) {
    const Twist t = c.drive(robot.read(), {0, 0, 10, 0, 0}, &done);
    robot.set_wheel_speeds(c.wheels(t));
    robot.advance(kDt);
  }
  ASSERT_TRUE(done);
  EXPECT_NEAR(robot.pose().y_m, 0.0, 0.02);
  EXPECT_NEAR(robot.pose().x_m, 10.0, 0.02);
}

void rotate_to(double target) {
  const auto m = test::footbot_model();
  Controller c(m, kDt);
  test::FakeRobot robot(m.wheel_base_m);
  LimitChecker limits{m};
  bool done = false;
  for (int i = 0; i < 500 && !done; ++i) {
    const Twist t = c.rotate(robot.read(), target, &done);
    limits.check(t);
    EXPECT_EQ(t.linear_mps, 0.0);
    robot.set_wheel_speeds(c.wheels(t));
    robot.advance(kDt);
  }
  ASSERT_TRUE(done) << "target " << target;
  EXPECT_LT(std::abs(wrap_angle(robot.pose().yaw_rad - target)), std::numbers::pi / 180);
  EXPECT_NEAR(robot.pose().x_m, 0.0, 1e-9);
  // At 30°/s, 90° takes at least 3 s.
  EXPECT_GE(limits.steps * kDt, std::abs(target) / m.max_turn_rate_radps - kEps);
}

TEST(Controller, RotatesNinetyDegreesInPlace) { rotate_to(std::numbers::pi / 2); }
TEST(Controller, RotatesNinetyDegreesClockwiseInPlace) { rotate_to(-std::numbers::pi / 2); }
TEST(Controller, RotatesOneHundredEightyDegreesInPlace) { rotate_to(std::numbers::pi); }

TEST(Controller, BrakeStopsWithinTheDecelerationLimit) {
  const auto m = test::footbot_model();
  Controller c(m, kDt);
  test::FakeRobot robot(m.wheel_base_m);
  bool done = false;
  for (int i = 0; i < 30; ++i) c.drive(robot.read(), {0, 0, 100, 0, 0}, &done);
  LimitChecker limits{m, c.last()};
  bool stopped = false;
  int steps = 0;
  while (!stopped && steps < 100) {
    limits.check(c.brake(&stopped));
    ++steps;
  }
  EXPECT_TRUE(stopped);
  EXPECT_GE(steps, 5);
}

}  // namespace
}  // namespace smart::agent

namespace smart::agent {
namespace {

TEST(Controller, RegressionRotationWithAMinimumWheelSpeedFinishesInsteadOfStalling) {
  auto m = load_robot_model(std::string(SMART_SOURCE_DIR) + "/config/robots/jetbot.yaml");
  ASSERT_GT(m.gains.min_wheel_speed_mps, 0.0);
  Controller c(m, kDt);
  test::FakeRobot robot(m.wheel_base_m);
  bool done = false;
  int steps = 0;
  for (; steps < 200 && !done; ++steps) {
    Twist t = c.rotate(robot.read(), -M_PI / 2, &done);
    // A motor that does not move below the minimum wheel speed (dead band).
    auto w = c.wheels(t);
    for (double* v : {&w.left_mps, &w.right_mps}) {
      if (std::abs(*v) < m.gains.min_wheel_speed_mps * 0.999) *v = 0;
    }
    robot.set_wheel_speeds(w);
    robot.advance(kDt);
  }
  EXPECT_TRUE(done);
  EXPECT_LT(std::abs(wrap_angle(robot.pose().yaw_rad + M_PI / 2)),
            m.gains.heading_tolerance_rad + 1e-9);
}

}  // namespace
}  // namespace smart::agent
