// Contract: pure, deterministic motion controller for one differential-drive robot, called
// once per control period dt with the latest pose. It never commands more than the model's
// limits: |v| <= max_speed, |ω| <= max_turn_rate, and v (ω) changes by at most
// max_accel·dt or max_decel·dt (max_angular_accel·dt) per period.
// - rotate(): turn in place to a yaw, trapezoidal in angle (decelerate to stop on target).
// - drive(): follow the straight segment start->end at the segment's heading: trapezoidal speed
//   (accelerate, cruise, brake to stop at `end`), PID on heading with cross-track correction.
//   The end may move further along the line between calls (a growing merged run) without
//   the robot stopping.
// done = within position/heading tolerance and (almost) at rest.
#pragma once

#include "smart/agent/robot_model.hpp"
#include "smart/agent/types.hpp"

namespace smart::agent {

struct Segment {
  double start_x_m = 0, start_y_m = 0;
  double end_x_m = 0, end_y_m = 0;
  double heading_rad = 0;
};

class Controller {
 public:
  Controller(const RobotModel& model, double period_s);

  Twist rotate(const PoseSample& pose, double target_yaw_rad, bool* done);
  Twist drive(const PoseSample& pose, const Segment& segment, bool* done);
  // Brings the command to zero within the deceleration limits (e.g. when the queue is empty).
  Twist brake(bool* stopped);
  // After an emergency stop (stale pose): the robot was stopped outright.
  void reset() { v_ = w_ = 0; }
  Twist last() const { return {v_, w_}; }
  // Continues from a command given elsewhere (the controller's only state).
  void restore(Twist last) {
    v_ = last.linear_mps;
    w_ = last.angular_radps;
  }
  WheelSpeeds wheels(Twist t) const;

  // Signed distance still to go along the segment's heading (negative once past the end).
  static double remaining_m(const Pose2D& pose, const Segment& s);
  // Distance travelled along the segment's heading from its start.
  static double progress_m(const Pose2D& pose, const Segment& s);

 private:
  Twist limit(double v_target, double w_target);

  RobotModel m_;
  double dt_;
  double v_ = 0;  // last command
  double w_ = 0;
};

}  // namespace smart::agent
