// Contract: one simulated robot seen through the agent's interfaces: DriveBackend writes wheel
// targets into the World, PoseSource reads its pose (stamped with sim time). Deactivating
// commands zero wheel speed. With wheel slip (agent/uncertainty.hpp slip_sigma) each wheel's
// target is scaled by that robot's slip factor of the control period.
#pragma once

#include <cmath>

#include "smart/agent/interfaces.hpp"
#include "smart/agent/uncertainty.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim {

class SimRobot : public agent::DriveBackend, public agent::PoseSource {
 public:
  SimRobot(World& world, uint32_t id, agent::Uncertainty uncertainty = {},
           double control_period_s = 0.1)
      : world_(world), id_(id), u_(uncertainty), period_s_(control_period_s) {}
  void set_wheel_speeds(agent::WheelSpeeds speeds) override {
    if (u_.slip_sigma > 0) {
      const auto tick = static_cast<uint64_t>(std::llround(world_.time_s() / period_s_));
      speeds.left_mps *= agent::slip_factor(u_, id_, tick, 0);
      speeds.right_mps *= agent::slip_factor(u_, id_, tick, 1);
    }
    world_.set_wheel_targets(id_, speeds);
  }
  agent::PoseSample read() override { return world_.pose(id_); }

 private:
  World& world_;
  uint32_t id_;
  agent::Uncertainty u_;
  double period_s_;
};

}  // namespace smart::sim
