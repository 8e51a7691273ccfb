// A kinematic fake robot for agent tests: implements DriveBackend and PoseSource, integrates
// the commanded wheel speeds exactly (unicycle) and records every command.
#pragma once

#include <cmath>
#include <vector>

#include "smart/agent/interfaces.hpp"
#include "smart/agent/kinematics.hpp"

namespace smart::test {

class FakeRobot : public agent::DriveBackend, public agent::PoseSource {
 public:
  explicit FakeRobot(double wheel_base_m, agent::Pose2D start = {}) : b_(wheel_base_m) {
    pose_ = start;
  }
  // Each call counts and answers what the test set (success by default).
  agent::LifecycleResult configure() override {
    ++configured;
    return configure_answer;
  }
  agent::LifecycleResult activate() override {
    ++activated;
    return activate_answer;
  }
  agent::LifecycleResult deactivate() override {
    ++deactivated;
    stop();
    return agent::LifecycleResult::success();
  }
  agent::LifecycleResult configure_answer, activate_answer;
  void set_wheel_speeds(agent::WheelSpeeds w) override {
    wheels_ = w;
    commands.push_back(w);
  }
  void stop() override {
    ++stops;
    set_wheel_speeds({0, 0});
  }
  agent::PoseSample read() override {
    const auto t = agent::to_twist(wheels_, b_);
    return {pose_, t.linear_mps, t.angular_radps, stamp_, valid};
  }
  // Advances the robot by dt under the current wheel speeds.
  void advance(double dt) {
    const auto t = agent::to_twist(wheels_, b_);
    const int n = 10;
    for (int i = 0; i < n; ++i) {
      pose_.x_m += t.linear_mps * std::cos(pose_.yaw_rad) * dt / n;
      pose_.y_m += t.linear_mps * std::sin(pose_.yaw_rad) * dt / n;
      pose_.yaw_rad += t.angular_radps * dt / n;
    }
    stamp_ += dt;
  }
  const agent::Pose2D& pose() const { return pose_; }
  double time() const { return stamp_; }
  void freeze_stamp_at(double t) { stamp_ = t; }

  bool valid = true;
  int configured = 0, activated = 0, deactivated = 0, stops = 0;
  std::vector<agent::WheelSpeeds> commands;

 private:
  double b_;
  agent::Pose2D pose_;
  agent::WheelSpeeds wheels_;
  double stamp_ = 0;
};

}  // namespace smart::test
