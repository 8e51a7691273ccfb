// Internal to the sim host: the DDS edge between the shards of a sharded sim (sim/shard.hpp,
// idl/smart.idl "Sim shards"). ShardPeer publishes this shard's exchange of each period and
// takes the others': each is checked (wire::check_exchange; dropped and counted otherwise),
// handed to the caller once on receipt (to relay the progress and states of robots homed here)
// and kept by period until the caller has applied that period. It keeps its own last two
// exchanges (not the final one) to send them again (repeat(), shard_barrier.hpp should_repeat);
// an exchange it has already, or of a period applied and forgotten, is dropped uncounted.
// Who may speak for a shard: the first writer whose exchange for it passed the checks, until that
// writer leaves (as the monitor's SenderGate holds each robot's progress). A second writer
// claiming a held shard, a writer claiming a second shard number, or any writer but this one's
// claiming this shard's number (a second process started with the same --shard I/N) is refused
// and counted. Without --security the first writer of a shard number wins, whoever it is; under
// --security only the `sim` identity may write on smart/shard (security/keystore.hpp); with a
// run key only participants proven as the run's sim hosts are heard at all (dds/admission.hpp).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <vector>

#include "shard_wire.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/wire.hpp"

namespace smart::sim::detail {

class ShardPeer {
 public:
  ShardPeer(const dds::Participant& participant, const dds::QosProfile& qos, uint32_t shard,
            uint32_t shards, std::size_t robots, wire::Bounds bounds);
  void publish(const Exchange& e);
  // This shard's kept exchanges (the last two periods') go out again.
  void repeat();
  // Takes what arrived; on_receipt(e) for each exchange that passed the checks.
  void take(const std::function<void(const Exchange&)>& on_receipt);
  // Every other shard's last exchange is in.
  bool last_complete() const { return last_.size() + 1 == shards_; }
  // The other shards' exchanges of `tick`, by shard; last(): their final ones.
  std::vector<const Exchange*> of(uint64_t tick) const;
  std::vector<const Exchange*> last() const;
  void forget_before(uint64_t tick);
  dds_entity_t reader() const { return in_.handle(); }
  // Exchange writers of other processes discovered now (a timeout's message tells a shard that
  // was never discovered from one that is up but silent).
  std::size_t writers_discovered() const;
  const wire::Rejections& rejections() const { return rejected_; }

 private:
  uint32_t shard_, shards_;
  // Why an exchange for `shard` from writer `from` is refused, or "" (and `from` holds it now).
  std::string admit(uint32_t shard, dds_instance_handle_t from);
  // A repeat of an exchange this shard has (or had: its period is applied and forgotten).
  bool known(uint32_t shard, uint64_t tick) const;

  std::size_t robots_;
  wire::Bounds bounds_;
  dds::WireWriter<smart_msg_ShardExchange> out_;
  dds::WriterAdmission from_sims_;  // before in_: its filter (sim shards proven with the key)
  dds::WireReader<smart_msg_ShardExchange> in_;
  std::map<uint64_t, std::map<uint32_t, Exchange>> by_tick_;
  uint64_t forgotten_before_ = 0;
  std::deque<ExchangeBuffer> mine_;  // this shard's last two exchanges, built in place
  std::map<uint32_t, Exchange> last_;
  dds_instance_handle_t self_ = 0;                    // out_'s publication handle
  std::map<uint32_t, dds_instance_handle_t> holder_;  // shard -> the writer speaking for it
  wire::Rejections rejected_;
};

}  // namespace smart::sim::detail
