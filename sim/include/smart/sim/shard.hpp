// Contract: a simulated fleet split across sim shards by map region (`smart sim --shard I/N`,
// docs/simulation.md "Sharded sim"); pure: no DDS, no clocks, deterministic.
// - ShardMap: N strips across the map's longer axis, cut at cell edges so that each strip holds
//   about as many robot starts (robots that can touch are mostly in one strip). A robot is kept
//   by its shard until it is more than half a cell beyond the strip (hysteresis: no hand-over
//   back and forth on a border). A robot is a neighbour's concern when it is within margin_m of
//   the neighbour's strip: two robot diameters, the way both can close in one period at top
//   speed, and the hysteresis.
// - FleetShard: one shard's view of a Fleet of every robot: it simulates the robots of its strip
//   (the World's others are ghosts or absent, world.hpp Presence). After each period its Outbox
//   lists the robots that left for another strip (RobotHandover: the World's physics and the
//   agent's snapshot, bit for bit) and the motion of its robots near other strips (ghosts); at
//   the next period boundary, with every other shard's outbox of the same period, it adopts the
//   robots handed to it and shows the neighbours' robots near its strip as ghosts. A robot's
//   trajectory does not depend on which shard steps it; a contact across a border is simulated
//   against the neighbour's robot as a ghost moving at its last velocity (up to one period's
//   lag), so only plans with contacts across borders can differ from an unsharded run.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "smart/agent/agent.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/grid/grid.hpp"
#include "smart/sim/fleet.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim {

class ShardMap {
 public:
  // Throws std::invalid_argument when shards is 0 or the map is narrower than one cell per
  // shard.
  ShardMap(const grid::Grid& grid, const SimConfig& config, const agent::RobotModel& model,
           uint32_t shards, const std::vector<agent::Pose2D>& starts);
  uint32_t shards() const { return static_cast<uint32_t>(cuts_m_.size()) - 1; }
  bool along_x() const { return along_x_; }
  // Strip s spans [cut(s), cut(s + 1)) of the axis, in metres of the world frame.
  double cut_m(uint32_t s) const { return cuts_m_.at(s); }
  double margin_m() const { return margin_m_; }
  uint32_t region_of(double x_m, double y_m) const;
  // The shard that simulates a robot at (x, y) next period, when `current` simulates it now.
  uint32_t keeper(uint32_t current, double x_m, double y_m) const;
  // Whether a robot at (x, y) may touch a robot of strip s within the next period.
  bool near(uint32_t s, double x_m, double y_m) const;

 private:
  double axis(double x_m, double y_m) const { return along_x_ ? x_m : y_m; }
  double distance_to_strip(uint32_t s, double a) const;
  bool along_x_ = true;
  double hysteresis_m_ = 0;
  double margin_m_ = 0;
  std::vector<double> cuts_m_;  // shards + 1, the outer two infinite
};

// A robot leaving one shard for another.
struct RobotHandover {
  uint32_t robot = 0;
  uint32_t to_shard = 0;
  RobotPhysics physics;
  agent::AgentSnapshot agent;
  // What the leaving shard's host last reported for it (progress is cumulative and counted per
  // host: the next host continues the count instead of reporting the robot's actions again).
  int64_t reported_finished = -1;
  int64_t reported_executing = -1;
};

struct Ghost {
  uint32_t robot = 0;
  RobotMotion motion;
};

struct ShardOutbox {
  std::vector<RobotHandover> handovers;
  std::vector<Ghost> ghosts;
};

class FleetShard {
 public:
  // Simulates the robots whose start lies in the shard's strip; every other robot is absent
  // until the first outboxes of the other shards come (initial_outbox()).
  FleetShard(Fleet& fleet, const ShardMap& map, uint32_t shard);
  uint32_t shard() const { return shard_; }
  bool simulates(uint32_t robot) const {
    return fleet_.world().presence(robot) == Presence::kSimulated;
  }
  // The shard whose strip the robot started in (its DDS home: the shard that speaks for it).
  uint32_t home(uint32_t robot) const { return home_.at(robot); }
  std::size_t simulated() const;

  // Before the first period: the ghosts the neighbours need.
  ShardOutbox initial_outbox() const;
  // After a period: robots past the strip are released (reported(r) gives what the host last
  // reported for r), and the ghosts of the robots simulated in that period.
  using Reported = std::pair<int64_t, int64_t>;
  ShardOutbox after_step(const std::function<Reported(uint32_t)>& reported);
  // At the next boundary, with the other shards' outboxes of the same period: returns the
  // robots adopted here (sorted), with what their previous host had reported.
  std::vector<RobotHandover> before_step(const std::vector<const ShardOutbox*>& others);

 private:
  std::vector<Ghost> ghosts_near_others() const;
  Fleet& fleet_;
  const ShardMap& map_;
  uint32_t shard_;
  std::vector<uint32_t> home_;
  std::vector<Ghost> released_ghosts_;  // robots released here, still near this strip
};

}  // namespace smart::sim
