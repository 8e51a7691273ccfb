#include "smart/agent/wheel_trim.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace smart::agent {

namespace {

constexpr double kMovedM = 0.002;  // beyond pose noise (Vicon: sub-millimetre)

// Least-squares slope of y over t.
double slope(const std::vector<double>& t, const std::vector<double>& y) {
  double mt = 0, my = 0;
  for (std::size_t i = 0; i < t.size(); ++i) mt += t[i], my += y[i];
  mt /= static_cast<double>(t.size());
  my /= static_cast<double>(t.size());
  double num = 0, den = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    num += (t[i] - mt) * (y[i] - my);
    den += (t[i] - mt) * (t[i] - mt);
  }
  return den > 0 ? num / den : 0.0;
}

}  // namespace

WheelTrial measure_wheel_trial(const std::vector<PoseSample>& samples, double command_mps,
                               double wheel_base_m, double settle_s) {
  if (!(std::abs(command_mps) > 1e-3) || !(wheel_base_m > 0)) {
    throw std::invalid_argument("a wheel trial needs a commanded speed and a wheel base");
  }
  std::vector<double> t, yaw;
  double path_m = 0;
  const PoseSample* prev = nullptr;
  const PoseSample* first = nullptr;
  double moving_s = NAN;  // when the robot first moved: commands may take a while to arrive
  for (const auto& s : samples) {
    if (!s.valid) continue;
    if (first == nullptr) first = &s;
    if (std::isnan(moving_s) &&
        std::hypot(s.pose.x_m - first->pose.x_m, s.pose.y_m - first->pose.y_m) > kMovedM) {
      moving_s = s.stamp_s;
    }
    if (std::isnan(moving_s) || s.stamp_s < moving_s + settle_s) continue;
    double y = s.pose.yaw_rad;
    if (prev != nullptr) {  // unwrap
      y = yaw.back() + std::remainder(s.pose.yaw_rad - prev->pose.yaw_rad, 2 * std::numbers::pi);
      path_m += std::hypot(s.pose.x_m - prev->pose.x_m, s.pose.y_m - prev->pose.y_m);
    }
    t.push_back(s.stamp_s);
    yaw.push_back(y);
    prev = &s;
  }
  if (t.size() < 10 || t.back() - t.front() < 0.5) {
    throw std::invalid_argument("the wheel trial has " + std::to_string(t.size()) +
                                " poses after settling; drive longer (--seconds) or check the "
                                "pose stream");
  }
  WheelTrial out;
  out.duration_s = t.back() - t.front();
  out.turn_rate_radps = slope(t, yaw);
  out.speed_mps = std::copysign(path_m / out.duration_s, command_mps);
  if (std::abs(out.speed_mps) < 0.1 * std::abs(command_mps)) {
    throw std::invalid_argument("the robot barely moved in the wheel trial (" +
                                std::to_string(path_m) + " m): check the motors and the pose");
  }
  const double half = out.turn_rate_radps * wheel_base_m / 2;
  out.gain = {(out.speed_mps - half) / command_mps, (out.speed_mps + half) / command_mps};
  const double slower = std::min(out.gain.left, out.gain.right);
  out.trim = {slower / out.gain.left, slower / out.gain.right};
  return out;
}

}  // namespace smart::agent
