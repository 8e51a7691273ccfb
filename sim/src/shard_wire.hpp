// Internal to the sim host: a sim shard's exchange (sim/shard.hpp) to and from the wire type
// smart_msg_ShardExchange of idl/smart.idl. ExchangeBuffer owns what the sample's sequences
// point into (written without dds_alloc); from_wire() copies a received sample out. Received
// samples must have passed wire::check_exchange.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/dds/topics.hpp"
#include "smart/sim/shard.hpp"
#include "smart/sim/world.hpp"

namespace smart::sim::detail {

// One shard's exchange of one period, as the sim host handles it.
struct Exchange {
  uint32_t shard = 0;
  uint32_t shards = 0;
  uint64_t run_id = 0;
  uint64_t tick = 0;
  bool last = false;
  ShardOutbox outbox;
  std::vector<smart_msg_Progress> progress;  // relayed to the robots' homes
  std::vector<smart_msg_RobotState> states;
  uint64_t finished_total = 0;
  ContactStats contacts;
  double peak_rss_mb = 0;
};

class ExchangeBuffer {
 public:
  explicit ExchangeBuffer(const Exchange& e);
  // Valid while the buffer lives.
  const smart_msg_ShardExchange& view() const { return msg_; }

 private:
  std::vector<smart_msg_RobotHandover> handovers_;
  std::vector<std::vector<smart_msg_PairContact>> pairs_;
  std::vector<std::vector<smart_msg_QueuedAction>> pending_;
  std::vector<smart_msg_GhostRobot> ghosts_;
  std::vector<smart_msg_Progress> progress_;
  std::vector<smart_msg_RobotState> states_;
  smart_msg_ShardExchange msg_{};
};

Exchange from_wire(const smart_msg_ShardExchange& m);

}  // namespace smart::sim::detail
