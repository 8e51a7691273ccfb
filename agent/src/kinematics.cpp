#include "smart/agent/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace smart::agent {

WheelSpeeds to_wheels(Twist t, double b) {
  return {t.linear_mps - t.angular_radps * b / 2.0, t.linear_mps + t.angular_radps * b / 2.0};
}

Twist to_twist(WheelSpeeds w, double b) {
  return {(w.left_mps + w.right_mps) / 2.0, (w.right_mps - w.left_mps) / b};
}

double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

WheelSpeeds saturate(WheelSpeeds w, double max_wheel_mps) {
  const double m = std::max(std::abs(w.left_mps), std::abs(w.right_mps));
  if (m <= max_wheel_mps || m == 0.0) return w;
  const double k = max_wheel_mps / m;
  return {w.left_mps * k, w.right_mps * k};
}

}  // namespace smart::agent
