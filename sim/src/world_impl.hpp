// Internal to sim/: World's state, shared by world.cpp (stepping, the public interface),
// body_slots.cpp (awake robots in Simbody body slots) and contacts.cpp (contact search and the
// forces of one robot).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "simbody_system.hpp"
#include "smart/sim/walls.hpp"
#include "smart/sim/world.hpp"
#include "workers.hpp"

namespace smart::sim {

inline constexpr double kGravity = 9.81;
inline constexpr uint32_t kNoRobot = 0xffffffffu;

// Everything the force elements read: per-robot commands, the sub-step snapshot and the
// contacts found in it; and the assignment of awake robots to Simbody body slots.
struct World::Impl : detail::RobotForces {
  const grid::Grid& grid;
  agent::RobotModel model;
  SimConfig cfg;
  std::size_t n;
  int substeps;
  uint64_t substep = 0;  // physics sub-steps done; time = substep · h
  uint64_t control_steps = 0;

  // Commands: the motor ramps from `ramp_from` (at time ramp_t0) towards `target`.
  std::vector<double> target_l, target_r, ramp_from_l, ramp_from_r;
  double ramp_t0 = 0;
  double ramp_rate = 0;  // m/s² per wheel

  // Snapshot at the start of the current sub-step (world frame). For a sleeping robot this is
  // its resting state.
  std::vector<double> x, y, yaw, vx, vy, w;
  // Each awake robot's state after the sub-step, written by the threads stepping the systems
  // while other threads' forces still read the snapshot; copied into it after the barrier.
  std::vector<std::array<double, 6>> stepped;
  // Contacts in the snapshot, per robot (CSR): the robots it overlaps and the walls it touches.
  // A robot's forces for the next sub-step are computed from exactly these.
  std::vector<uint32_t> touch_begin, touch;
  std::vector<uint32_t> wall_begin;
  std::vector<WallContact> wall;

  // Spatial hash on map cells.
  std::vector<uint32_t> head, next;
  std::vector<std::size_t> touched;

  std::vector<uint8_t> is_external;
  std::vector<Presence> presence;  // sim shards: simulated here, a ghost, or absent
  bool contacts_stale = false;     // presence changed since the last contact search
  bool any_ghosts = false;
  std::vector<agent::Pose2D> external_pose;
  ContactStats stats;
  std::vector<uint64_t> pairs_now;
  std::unordered_map<uint64_t, double> pair_last_contact;  // pair -> last time in contact
  std::vector<double> wall_last_contact;
  std::vector<uint8_t> in_contact;  // any contact at the last snapshot
  std::vector<WallContact> scratch;
  std::vector<uint32_t> fill_at;

  // Awake robots and their body slots.
  std::size_t capacity = 1;
  std::vector<std::unique_ptr<detail::SimbodySystem>> systems;
  static constexpr uint32_t kAsleep = 0xffffffffu;
  std::vector<uint32_t> system_of, slot_of;  // system_of[i] == kAsleep: robot i sleeps
  std::size_t awake_count = 0;
  std::vector<detail::SimbodySystem*> active;  // systems stepped in this sub-step
  detail::Workers workers;

  Impl(const grid::Grid& g, const agent::RobotModel& m, const SimConfig& c, std::size_t robots)
      : grid(g), model(m), cfg(c), n(robots), workers(sim_threads(c.threads, robots)) {}

  double command(const std::vector<double>& from, const std::vector<double>& target, uint32_t i,
                 double t) const {
    const double max_change = ramp_rate * std::max(0.0, t - ramp_t0);
    return from[i] + std::clamp(target[i] - from[i], -max_change, max_change);
  }
  bool commanded(uint32_t i, double t) const {
    return is_external[i] || target_l[i] != 0 || target_r[i] != 0 ||
           command(ramp_from_l, target_l, i, t) != 0 || command(ramp_from_r, target_r, i, t) != 0;
  }
  bool awake(uint32_t i) const { return system_of[i] != kAsleep; }
  bool simulated(uint32_t i) const { return presence[i] == Presence::kSimulated; }

  void wake(uint32_t i);
  void sleep(uint32_t i);
  void move(uint32_t i, std::size_t to);
  void pack();
  void find_contacts(bool everyone);
  void bin_robots();
  void build_touch_lists();
  void count_robot_contacts(double now);
  void substep_once(double h);
  void move_ghosts(double h);
  void settle(double time_s);
  void robot_force(uint32_t robot, double time_s, const double* q, const double* u,
                   double* f) const override;
};

}  // namespace smart::sim
