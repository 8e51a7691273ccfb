// Contract: the agent's only ways to touch the world. Every backend (Simbody sim, JetBot
// hardware, test fakes) implements these; agent code never includes sim/ or hw/ headers.
// Lifecycle as in ros2_control: configure() opens resources, activate() allows motion,
// deactivate() brings the wheels to zero; each returns a LifecycleResult (lifecycle.hpp) and
// never throws. Calls come from the agent's control loop thread.
#pragma once

#include "smart/agent/lifecycle.hpp"
#include "smart/agent/types.hpp"

namespace smart::agent {

class DriveBackend {
 public:
  virtual ~DriveBackend() = default;
  virtual LifecycleResult configure() { return LifecycleResult::success(); }
  virtual LifecycleResult activate() { return LifecycleResult::success(); }
  virtual LifecycleResult deactivate() {
    stop();
    return LifecycleResult::success();
  }
  // Wheel ground speeds in m/s (positive = forward).
  virtual void set_wheel_speeds(WheelSpeeds speeds) = 0;
  virtual void stop() { set_wheel_speeds({0.0, 0.0}); }
};

class PoseSource {
 public:
  virtual ~PoseSource() = default;
  // Latest pose; never blocks. valid = false when no pose is available.
  virtual PoseSample read() = 0;
};

}  // namespace smart::agent
