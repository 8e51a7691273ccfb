// Contract: one simulated robot seen through the agent's interfaces: DriveBackend writes wheel
// targets into the World, PoseSource reads its pose (stamped with sim time). Deactivating
// commands zero wheel speed.
#pragma once

#include "smart/agent/interfaces.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim {

class SimRobot : public agent::DriveBackend, public agent::PoseSource {
 public:
  SimRobot(World& world, uint32_t id) : world_(world), id_(id) {}
  void set_wheel_speeds(agent::WheelSpeeds speeds) override {
    world_.set_wheel_targets(id_, speeds);
  }
  agent::PoseSample read() override { return world_.pose(id_); }

 private:
  World& world_;
  uint32_t id_;
};

}  // namespace smart::sim
