// Internal to the sim host: one shard of a sharded sim (`smart sim --shard I/N`, sim/shard.hpp,
// docs/simulation.md "Sharded sim") as a pump around the pure ShardBarrier (shard_barrier.hpp):
// read what arrived (windows, the monitor's answers, the other shards' exchanges through
// ShardPeer), let the barrier decide, write (exchanges, the lead's clock and status, the progress
// and states of the robots homed here). Lock-step only, no external robots, no link model, no
// ROS 2 view.
#pragma once

#include <memory>
#include <vector>

#include "host_core.hpp"

namespace smart::sim::detail {

// Throws std::invalid_argument naming the shard when the options do not allow sharding.
std::unique_ptr<HostLoop> make_sharded_host(const dds::Participant& participant,
                                            const dds::QosProfile& qos, const grid::Grid& grid,
                                            const agent::RobotModel& model,
                                            const std::vector<agent::Pose2D>& starts,
                                            const SimHostOptions& options);

}  // namespace smart::sim::detail
