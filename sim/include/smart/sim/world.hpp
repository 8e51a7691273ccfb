// Contract: a headless Simbody world of N differential-drive robots on a MovingAI grid map
// (design (c') of ../shared/design/simulation.md).
// - Robots are MobilizedBody::Planar bodies (q = θ, x, y in the world frame of
//   monitor/grid.hpp) split over a fixed number of Simbody systems ("shards", robot i in shard
//   i mod S), stepped in parallel with a fixed-step semi-explicit Euler integrator.
// - One Force::Custom per shard applies, as mobility forces: wheel traction with linear slip and
//   Coulomb saturation, the wheel-command ramp (motor acceleration limit), wall contact
//   (walls.hpp) and robot-robot Hertz/Hunt-Crossley contact against a snapshot of all robots
//   taken at each physics sub-step (neighbours from a spatial hash on map cells).
// - step() advances one control period (sub-steps of physics_step_s). Commands set before it
//   take effect at its start. Results are bit-identical for the same inputs whatever the thread
//   count, because shards see each other only through the snapshot.
// - Contacts are counted as events (a robot pair or robot-wall contact that begins, bounces
//   within contact_debounce_s counting once), and the
//   smallest surface gap between robots is tracked (negative = overlap).
// - A shard whose robots are all at rest (no command, no motion, no contact) is not stepped:
//   robots waiting for their next action or finished cost nothing but their bookkeeping.
// Sim time only: nothing here reads the wall clock.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "smart/agent/robot_model.hpp"
#include "smart/agent/types.hpp"
#include "smart/monitor/grid.hpp"

namespace smart::sim {

struct SimConfig {
  double cell_m = 1.0;
  double physics_step_s = 0.01;
  double control_period_s = 0.1;
  // Simbody systems; 0 = automatic: about 125 robots each, 2 to 8 (measured on 2 cores:
  // per-system overhead dominates small fleets, one big system serialises large ones).
  int shards = 0;
  int threads = 2;
  double contact_modulus_pa = 2e5;   // effective Hertz modulus E
  double contact_damping_spm = 0.5;  // Hunt-Crossley c (s/m)
  double friction_mu = 0.6;          // wheel-ground Coulomb limit
  double slip_time_s = 0.02;         // traction time constant
  // A contact that resumes within this time of the last one is the same collision (bounces).
  double contact_debounce_s = 1.0;
};

struct ContactStats {
  uint64_t robot_robot_events = 0;
  uint64_t robot_wall_events = 0;
  uint32_t robot_robot_now = 0;  // pairs in contact after the last sub-step
  uint32_t robot_wall_now = 0;
  double min_gap_m = 1e9;  // smallest surface distance between two robots seen so far
};

class World {
 public:
  // Throws std::invalid_argument for a robot wider than half a cell or a start off the map.
  World(const monitor::Grid& grid, const agent::RobotModel& model, const SimConfig& config,
        const std::vector<agent::Pose2D>& starts);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  std::size_t robots() const;
  double time_s() const;
  uint64_t steps() const;  // control periods done

  // A robot executed elsewhere (hardware in a mixed run): no traction; a stiff spring-damper
  // holds it at its last reported pose, so simulated robots collide with it where it really is.
  void set_external(uint32_t robot, bool external);
  void set_external_pose(uint32_t robot, const agent::Pose2D& pose);
  bool external(uint32_t robot) const;

  // Wheel ground-speed targets, reached through the motor ramp.
  void set_wheel_targets(uint32_t robot, agent::WheelSpeeds targets);
  agent::PoseSample pose(uint32_t robot) const;
  agent::WheelSpeeds wheel_speeds(uint32_t robot) const;  // ramped motor command
  void step();

  // Rebuilds the shards with robots grouped in `order` (robot order[k] in shard k·S/n), e.g.
  // by plan length so that robots finishing together share a shard and it can sleep. Only
  // while every robot is at rest (throws std::logic_error otherwise). Results are unchanged:
  // shards see each other only through the snapshot.
  void repartition(const std::vector<uint32_t>& order);

  const ContactStats& contacts() const;
  std::size_t awake_shards() const;
  // FNV-1a over every robot's pose and velocity bits: equal hashes = identical trajectories.
  uint64_t state_hash() const;
  const SimConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::sim
