#include "smart/agent/controller.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "smart/agent/kinematics.hpp"

namespace smart::agent {

namespace {
double clamp(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
double sign(double v) { return v < 0 ? -1.0 : 1.0; }
// Speed from which `decel` stops within `dist`, discretised so that one period at that speed
// never overshoots (v·dt <= dist): the trapezoid's braking ramp.
double braking_speed(double dist, double decel, double dt) {
  const double a = decel;
  // Largest v with v·dt + v²/(2a) <= dist.
  return std::max(0.0, -a * dt + std::sqrt(a * a * dt * dt + 2.0 * a * dist));
}
// The segment's frame: unit vectors along its heading and to its left, and the offset of the
// robot from a point (the same arithmetic, in the same order, as written out by hand before).
Eigen::Vector2d along(const Segment& s) {
  return {std::cos(s.heading_rad), std::sin(s.heading_rad)};
}
Eigen::Vector2d leftward(const Segment& s) {
  return {-std::sin(s.heading_rad), std::cos(s.heading_rad)};
}
Eigen::Vector2d position(const Pose2D& p) { return {p.x_m, p.y_m}; }
Eigen::Vector2d start(const Segment& s) { return {s.start_x_m, s.start_y_m}; }
Eigen::Vector2d end(const Segment& s) { return {s.end_x_m, s.end_y_m}; }
}  // namespace

Controller::Controller(const RobotModel& model, double period_s) : m_(model), dt_(period_s) {}

Twist Controller::limit(double v_target, double w_target) {
  v_target = clamp(v_target, -m_.max_speed_mps, m_.max_speed_mps);
  w_target = clamp(w_target, -m_.max_turn_rate_radps, m_.max_turn_rate_radps);
  // Speeding up (away from zero) uses max_accel, slowing down max_decel.
  const bool speeding_up = std::abs(v_target) > std::abs(v_) && v_target * v_ >= 0;
  const double dv = (speeding_up ? m_.max_accel_mps2 : m_.max_decel_mps2) * dt_;
  v_ = clamp(v_target, v_ - dv, v_ + dv);
  const double dw = m_.max_angular_accel_radps2 * dt_;
  w_ = clamp(w_target, w_ - dw, w_ + dw);
  // Both wheels within the speed limit too (a turning robot's outer wheel is faster).
  const auto wheels = saturate(to_wheels({v_, w_}, m_.wheel_base_m), m_.max_speed_mps);
  const auto t = to_twist(wheels, m_.wheel_base_m);
  v_ = t.linear_mps;
  w_ = t.angular_radps;
  return {v_, w_};
}

Twist Controller::rotate(const PoseSample& p, double target, bool* done) {
  const double err = wrap_angle(target - p.pose.yaw_rad);
  const double speed = std::min(braking_speed(std::abs(err), m_.max_angular_accel_radps2, dt_),
                                m_.gains.heading_kp * std::abs(err));
  double w = sign(err) * speed - m_.gains.heading_kd * p.angular_radps;
  const double w_min = 2.0 * m_.gains.min_wheel_speed_mps / m_.wheel_base_m;
  if (std::abs(err) > m_.gains.heading_tolerance_rad && std::abs(w) < w_min) {
    w = sign(err) * std::min(w_min, std::abs(err) / dt_);  // never overshoot in one period
  }
  const Twist t = limit(0.0, w);
  *done = std::abs(err) <= m_.gains.heading_tolerance_rad &&
          std::abs(w_) <= std::max(m_.max_angular_accel_radps2 * dt_, w_min);
  return t;
}

double Controller::remaining_m(const Pose2D& pose, const Segment& s) {
  return (end(s) - position(pose)).dot(along(s));
}

double Controller::progress_m(const Pose2D& pose, const Segment& s) {
  return (position(pose) - start(s)).dot(along(s));
}

Twist Controller::drive(const PoseSample& p, const Segment& s, bool* done) {
  const double d = remaining_m(p.pose, s);
  // Lateral offset, positive when the robot is left of the line.
  const double lateral = leftward(s).dot(position(p.pose) - start(s));
  const double yaw_target = s.heading_rad - std::atan(m_.gains.cross_track_kp * lateral);
  const double yaw_err = wrap_angle(yaw_target - p.pose.yaw_rad);
  double speed = std::min({m_.max_speed_mps, braking_speed(std::abs(d), m_.max_decel_mps2, dt_),
                           m_.gains.distance_kp * std::abs(d)});
  // Do not drive on while badly misaligned: slow down in proportion.
  speed *= std::max(0.0, std::cos(std::min(std::abs(yaw_err) * 2.0, std::numbers::pi / 2)));
  const double w =
      clamp(m_.gains.heading_kp * yaw_err, -m_.max_turn_rate_radps, m_.max_turn_rate_radps) -
      m_.gains.heading_kd * p.angular_radps;
  const Twist t = limit(sign(d) * speed, w);
  *done = std::abs(d) <= m_.gains.position_tolerance_m && std::abs(v_) <= m_.max_decel_mps2 * dt_;
  return t;
}

Twist Controller::brake(bool* stopped) {
  const Twist t = limit(0.0, 0.0);
  *stopped = v_ == 0.0 && w_ == 0.0;
  return t;
}

WheelSpeeds Controller::wheels(Twist t) const { return to_wheels(t, m_.wheel_base_m); }

}  // namespace smart::agent
