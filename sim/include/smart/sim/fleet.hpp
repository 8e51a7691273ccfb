// Contract: a simulated fleet without DDS: one World, and for each robot a SimRobot backend and
// an Agent (the same Agent class as on hardware), activated. step() is one control period:
// every driven agent's read/update/write at the current sim time, then the world's step.
// External robots (executed by other hosts in mixed runs) are not driven: their agent is
// deactivated and the world shows them where set_external_pose() puts them. Used by the sim
// host (with DDS around it) and `smart bench sim` (without).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "smart/agent/agent.hpp"
#include "smart/grid/grid.hpp"
#include "smart/sim/sim_robot.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim {

// Robot i's start pose: the centre of cell starts[i] facing `yaw_rad`.
std::vector<agent::Pose2D> start_poses(const grid::Grid& grid, double cell_m,
                                       const std::vector<grid::Cell>& starts, double yaw_rad);

struct FleetStats {
  uint64_t periods = 0;
  // On average per period: robots stepped by Simbody (the rest sleep) and Simbody systems.
  double mean_awake_robots = 0;
  double mean_active_systems = 0;
};

class Fleet {
 public:
  Fleet(const grid::Grid& grid, const agent::RobotModel& model, const SimConfig& config,
        const std::vector<agent::Pose2D>& starts, double pose_timeout_s = 0.5);

  std::size_t robots() const { return agents_.size(); }
  World& world() { return world_; }
  const World& world() const { return world_; }
  agent::Agent& agent(uint32_t robot) { return *agents_.at(robot); }
  const agent::Agent& agent(uint32_t robot) const { return *agents_.at(robot); }
  // Throws std::invalid_argument naming the robot when it is not in the fleet.
  void set_external(uint32_t robot);
  bool external(uint32_t robot) const { return world_.external(robot); }

  // Sim shards (shard.hpp), at a period boundary: a robot leaves this fleet's World (its state
  // is returned; from then on it is `now` here and its agent is not driven) or arrives and is
  // continued from the state another fleet returned.
  std::pair<RobotPhysics, agent::AgentSnapshot> release(uint32_t robot, Presence now);
  void adopt(uint32_t robot, const RobotPhysics& physics, const agent::AgentSnapshot& agent);

  void step();
  void deactivate();
  FleetStats stats() const;

 private:
  World world_;
  std::vector<std::unique_ptr<SimRobot>> backends_;
  std::vector<std::unique_ptr<agent::Agent>> agents_;
  FleetStats stats_;
  double awake_sum_ = 0, systems_sum_ = 0;
};

}  // namespace smart::sim
