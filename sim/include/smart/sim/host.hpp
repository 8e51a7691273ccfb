// Contract: the sim host, a pump around a Fleet (fleet.hpp): one process, one DDS participant,
// and the fleet's agents behind one AgentNode (the same DDS loop as `smart agent`).
// Each control period: apply received action windows, step the fleet, publish changed progress,
// robot states at state_rate_hz (and the ROS 2 view), the sim status when it changed, and the
// clock. Clock modes:
// - lockstep: before each period the host waits for the monitor's answer to its last tick and
//   for windows adding up to the answer's sync_total (wire/lockstep.hpp, HostHandshake). Runs
//   are bit-identical. A silent monitor for timeout_s ends the run with an error. With
//   real_time_factor > 0 periods start no faster than that many times real time (sim/pacer.hpp),
//   to watch a run live; the results are the same.
// - realtime: periods paced to the wall clock (hardware-in-the-loop, mixed runs).
// The host stops when the monitor's clock says stop, on `stop_requested`, or on error.
// Sharded (shards > 1, lock-step only; sim/shard.hpp): the host simulates the robots of its map
// strip; after each period it publishes its ShardExchange and steps again only once every other
// shard's exchange of that period is in (robots handed to it adopted, neighbours' robots near its
// strip as ghosts). Each robot speaks on the monitor's topics through its home shard (the strip
// it started in), which relays what other shards report for it. Shard 0 leads: it announces the
// ticks (sync_total summed over the shards) and publishes the fleet's SimStatus, so the monitor
// sees one sim host. No ROS 2 view in sharded runs. When a shard applies, steps or gives up is
// decided by the pure ShardBarrier (shard_barrier.hpp).
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "smart/agent/robot_model.hpp"
#include "smart/agent/types.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/grid/grid.hpp"
#include "smart/sim/fleet.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim {

enum class ClockMode { kLockstep, kRealtime };

struct SimHostOptions {
  ClockMode clock = ClockMode::kLockstep;
  double state_rate_hz = 2.0;
  double timeout_s = 30.0;      // lockstep: longest wait for the monitor
  double real_time_factor = 0;  // lockstep: at most this many times real time; 0: unpaced
  double pose_timeout_s = 0.5;
  SimConfig sim;
  // Robots executed by other hosts (mixed runs): shown at their published poses, not driven.
  std::vector<uint32_t> external_robots;
  // Robots that also get their own ROS 2 pose topic rt/robot_<id>/pose (ros_view.hpp).
  std::vector<uint32_t> ros_pose_robots;
  std::string ros_namespace;  // the ROS 2 view's topics under it ("" or "/run_a")
  uint32_t shard = 0;   // this host's shard, of
  uint32_t shards = 1;  // shards (1: not sharded)
};

struct SimHostResult {
  bool ok = false;
  std::string error;  // why it stopped, when not ok
  bool stopped_by_monitor = false;
  uint64_t ticks = 0;
  double sim_time_s = 0;
  double wall_time_s = 0;
  ContactStats contacts;
  // On average per period: robots stepped by Simbody (the rest sleep) and Simbody systems.
  double mean_awake_robots = 0;
  double mean_active_systems = 0;
  uint64_t handovers_in = 0;  // sharded: robots adopted from other shards
  // Samples dropped by the wire checks: topic -> reason -> count.
  std::map<std::string, std::map<std::string, uint64_t>> rejected_samples;
};

class SimHost {
 public:
  SimHost(const dds::Participant& participant, const dds::QosProfile& qos, const grid::Grid& grid,
          const agent::RobotModel& model, const std::vector<agent::Pose2D>& starts,
          const SimHostOptions& options);
  ~SimHost();
  SimHostResult run(const std::atomic<bool>& stop_requested);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::sim
