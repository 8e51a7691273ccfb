#include "smart/agent/wheel_trim.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace smart::agent {
namespace {

// A unicycle whose wheels reach gain * command after a ramp, sampled at 100 Hz like Vicon.
std::vector<PoseSample> trial(double gain_left, double gain_right, double command, double base,
                              double seconds) {
  std::vector<PoseSample> out;
  Pose2D p{1.0, 2.0, 3.0};  // heading near pi: the unwrap matters
  double l = 0, r = 0;
  for (double t = 0; t < seconds; t += 0.01) {
    l = std::min(l + 0.02, command), r = std::min(r + 0.02, command);
    const double gl = l * gain_left, gr = r * gain_right;
    const double v = (gl + gr) / 2, w = (gr - gl) / base;
    p.x_m += v * std::cos(p.yaw_rad) * 0.01;
    p.y_m += v * std::sin(p.yaw_rad) * 0.01;
    p.yaw_rad = std::remainder(p.yaw_rad + w * 0.01, 2 * M_PI);
    out.push_back({p, 0, 0, 100.0 + t, true});
  }
  return out;
}

TEST(WheelTrial, FindsTheWeakWheelAndProposesATrimThatSlowsTheOther) {
  const auto t = measure_wheel_trial(trial(1.0, 0.9, 0.2, 0.1025, 4.0), 0.2, 0.1025, 0.5);
  EXPECT_NEAR(t.gain.left, 1.0, 0.01);
  EXPECT_NEAR(t.gain.right, 0.9, 0.01);
  EXPECT_NEAR(t.trim.left, 0.9, 0.01);
  EXPECT_DOUBLE_EQ(t.trim.right, 1.0);
  EXPECT_LT(t.turn_rate_radps, 0);  // a weak right wheel turns it right (clockwise)
  // Trimmed, the same robot drives straight.
  const auto straight = measure_wheel_trial(
      trial(1.0 * t.trim.left, 0.9 * t.trim.right, 0.2, 0.1025, 4.0), 0.2, 0.1025, 0.5);
  EXPECT_NEAR(straight.turn_rate_radps, 0.0, 0.01);
}

// Regression: a ROS 2 base heard its first cmd_vel late (discovery under load), and the
// standing start skewed the fit; the settle time now counts from the first motion.
TEST(WheelTrial, AStandingStartBeforeTheFirstCommandArrivesIsIgnored) {
  auto samples = trial(1.0, 0.85, 0.15, 0.16, 4.0);
  std::vector<PoseSample> late;
  for (int k = 0; k < 150; ++k) {  // 1.5 s standing still first
    late.push_back({samples.front().pose, 0, 0, 98.5 + 0.01 * k, true});
  }
  late.insert(late.end(), samples.begin(), samples.end());
  const auto t = measure_wheel_trial(late, 0.15, 0.16, 0.5);
  EXPECT_NEAR(t.trim.left, 0.85, 0.01);
  EXPECT_NEAR(t.speed_mps, 0.15 * (1.0 + 0.85) / 2, 0.003);
}

TEST(WheelTrial, RefusesTrialsThatShowNothing) {
  EXPECT_THROW(measure_wheel_trial(trial(1, 1, 0.2, 0.1, 0.3), 0.2, 0.1, 0.5),
               std::invalid_argument);  // too short
  EXPECT_THROW(measure_wheel_trial(trial(0.01, 0.01, 0.2, 0.1, 3.0), 0.2, 0.1, 0.5),
               std::invalid_argument);  // did not move
}

}  // namespace
}  // namespace smart::agent
