// Contract: a headless Simbody world of N differential-drive robots on a MovingAI grid map
// (design (c') of docs/simulation.md).
// - A robot that moves is a MobilizedBody::Planar body (q = θ, x, y in the world frame of
//   grid/grid.hpp) in one of several Simbody systems of `system_capacity` bodies, stepped in
//   parallel with fixed-step semi-explicit Euler.
// - A robot at rest (no command, no motion, no contact) sleeps: it leaves its Simbody system and
//   stays in the snapshot as an obstacle, so robots waiting for their next action or finished
//   cost only their bookkeeping. A command or a contact wakes it into a free body slot. After
//   each period, robots are packed into as few systems as possible; empty systems are not
//   stepped (simbody_system.hpp).
// - One Force::Custom per system applies, as mobility forces: wheel traction with linear slip
//   and Coulomb saturation, the wheel-command ramp (motor acceleration limit), wall contact
//   (walls.hpp) and robot-robot Hertz/Hunt-Crossley contact against a snapshot of all robots
//   taken at each physics sub-step (contacts found with a spatial hash on map cells).
// - step() advances one control period (sub-steps of physics_step_s). Commands set before it
//   take effect at its start. Results are bit-identical for the same inputs whatever the thread
//   count and system capacity: robots see each other only through the snapshot, and which slot
//   a robot occupies does not change its arithmetic (tested).
// - Contacts are counted as events (a robot pair or robot-wall contact that begins, bounces
//   within contact_debounce_s counting once), and the smallest surface gap between robots is
//   tracked (negative = overlap).
// Sim time only: nothing here reads the wall clock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "smart/agent/robot_model.hpp"
#include "smart/agent/types.hpp"
#include "smart/grid/grid.hpp"

namespace smart::sim {

struct SimConfig {
  double cell_m = 1.0;
  double physics_step_s = 0.01;
  double control_period_s = 0.1;
  // Bodies per Simbody system; 0 = automatic (see World::World). Each system costs ~10 µs per
  // step plus ~1.2 µs per body, occupied or not (docs/performance.md).
  int system_capacity = 0;
  // Threads stepping the systems; 0 = automatic (sim_threads below).
  int threads = 0;
  double contact_modulus_pa = 2e5;   // effective Hertz modulus E
  double contact_damping_spm = 0.5;  // Hunt-Crossley c (s/m)
  double friction_mu = 0.6;          // wheel-ground Coulomb limit
  double slip_time_s = 0.02;         // traction time constant
  // A contact that resumes within this time of the last one is the same collision (bounces).
  double contact_debounce_s = 1.0;
};

// Fewer robots than this per thread and a second thread costs more at the sub-step barriers
// than it saves (docs/performance.md, "Automatic sim threads"): end to end in lock-step on
// 2 cores, where the monitor and the DDS threads share the cores with the sim, 1 vs 2 threads
// gave 46x vs 38x on SMART's 1000-robot warehouse plan, 25x vs 27x on a 1000-robot random walk
// (every robot always moving) and 12x vs 15x at 2000. Under CPU contention a barrier waits for
// a descheduled thread: 50 robots ran 9 s with 1 thread and over 120 s with 2 while two other
// processes kept both cores busy.
inline constexpr std::size_t kMinRobotsPerThread = 1000;

// The threads a World of `robots` simulated robots uses: `requested` if > 0, else one per
// kMinRobotsPerThread robots, at least 1 and at most 2 (the only count measured on this
// machine; more are used only when asked for).
int sim_threads(int requested, std::size_t robots);

struct ContactStats {
  uint64_t robot_robot_events = 0;
  uint64_t robot_wall_events = 0;
  uint32_t robot_robot_now = 0;  // pairs in contact after the last sub-step
  uint32_t robot_wall_now = 0;
  double min_gap_m = 1e9;     // smallest surface distance between two robots seen so far
  int64_t first_pair_a = -1;  // robots of the first robot-robot episode (-1: none yet)
  int64_t first_pair_b = -1;
};

// One robot's motion in the world frame: pose and velocity (vx, vy in the world frame).
struct RobotMotion {
  double x_m = 0, y_m = 0, yaw_rad = 0;
  double vx_mps = 0, vy_mps = 0, w_radps = 0;
};

// Everything the World keeps about one robot between control periods, so that another World
// (a sim shard on another host, shard.hpp) continues it bit for bit. The motor ramp is relative
// to the period's start, which every shard shares (lock-step).
struct RobotPhysics {
  RobotMotion motion;
  double target_l_mps = 0, target_r_mps = 0;
  double ramp_from_l_mps = 0, ramp_from_r_mps = 0;
  double wall_last_contact_s = -1e300;
  bool awake = false;
  // Its robot pairs still within the contact debounce: (other robot, last contact time).
  std::vector<std::pair<uint32_t, double>> pair_last_contact_s;
};

// Which robots a World steps (sim shards, shard.hpp): its own (kSimulated, the default), a
// neighbour shard's near the border (kGhost: an obstacle at the motion it was given, moved on at
// that velocity through the period, never stepped nor woken), the rest (kAbsent: not there).
enum class Presence : uint8_t { kSimulated, kGhost, kAbsent };

class World {
 public:
  // Throws std::invalid_argument for a robot wider than half a cell or a start off the map.
  World(const grid::Grid& grid, const agent::RobotModel& model, const SimConfig& config,
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

  // Sim shards, at a period boundary: a robot leaves (export_robot, then set_presence), arrives
  // (import_robot: simulated from then on) or is shown as a ghost (set_ghost). A contact between
  // a simulated robot and a ghost counts here only when the simulated one has the lower index,
  // so that the neighbour, seeing the same pair the other way round, does not count it again.
  Presence presence(uint32_t robot) const;
  void set_presence(uint32_t robot, Presence presence);
  RobotPhysics export_robot(uint32_t robot) const;
  void import_robot(uint32_t robot, const RobotPhysics& physics);
  void set_ghost(uint32_t robot, const RobotMotion& motion);
  RobotMotion motion(uint32_t robot) const;

  // Wheel ground-speed targets, reached through the motor ramp.
  void set_wheel_targets(uint32_t robot, agent::WheelSpeeds targets);
  agent::PoseSample pose(uint32_t robot) const;
  agent::WheelSpeeds wheel_speeds(uint32_t robot) const;  // ramped motor command
  void step();

  const ContactStats& contacts() const;
  bool awake(uint32_t robot) const;
  std::size_t awake_robots() const;
  std::size_t active_systems() const;  // Simbody systems with a robot in them
  std::size_t system_capacity() const;
  int threads() const;  // the threads stepping the systems (SimConfig::threads resolved)
  // FNV-1a over every robot's pose and velocity bits: equal hashes = identical trajectories.
  uint64_t state_hash() const;
  const SimConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::sim
