#include "smart/agent/kinematics.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace smart::agent {
namespace {

TEST(Kinematics, TwistAndWheelsRoundTrip) {
  const auto w = to_wheels({1.0, 2.0}, 0.2);
  EXPECT_DOUBLE_EQ(w.left_mps, 0.8);
  EXPECT_DOUBLE_EQ(w.right_mps, 1.2);
  const auto t = to_twist(w, 0.2);
  EXPECT_DOUBLE_EQ(t.linear_mps, 1.0);
  EXPECT_DOUBLE_EQ(t.angular_radps, 2.0);
}

TEST(Kinematics, WrapAndSaturate) {
  EXPECT_NEAR(wrap_angle(3 * std::numbers::pi / 2), -std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-std::numbers::pi), std::numbers::pi, 1e-12);
  const auto s = saturate({2.0, -4.0}, 1.0);
  EXPECT_DOUBLE_EQ(s.left_mps, 0.5);
  EXPECT_DOUBLE_EQ(s.right_mps, -1.0);
}

}  // namespace
}  // namespace smart::agent
