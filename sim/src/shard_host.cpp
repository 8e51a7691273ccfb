#include "shard_host.hpp"

#include <spdlog/spdlog.h>

namespace smart::sim::detail {

ShardPeer::ShardPeer(const dds::Participant& p, const dds::QosProfile& qos, uint32_t shard,
                     uint32_t shards, std::size_t robots, wire::Bounds bounds)
    : shard_(shard), shards_(shards), robots_(robots), bounds_(bounds), out_(p, qos), in_(p, qos) {}

void ShardPeer::publish(const Exchange& e) {
  const ExchangeBuffer buf(e);
  out_.write(buf.view());
}

void ShardPeer::take(const std::function<void(const Exchange&)>& on_receipt) {
  in_.take_each([&](const smart_msg_ShardExchange& m) {
    std::string why = wire::check_exchange(m, robots_, bounds_);
    if (why.empty() && m.shards != shards_) {
      why = "from a sim of " + std::to_string(m.shards) + " shards, this one has " +
            std::to_string(shards_) + " (every shard must be started with the same --shard I/N)";
    }
    if (!why.empty()) {
      if (rejected_.count("shard", why)) spdlog::warn("sim shard: exchange rejected: {}", why);
      return;
    }
    if (m.shard == shard_) return;  // our own (a second process with our --shard is refused)
    Exchange e = from_wire(m);
    on_receipt(e);
    if (e.last) {
      last_[e.shard] = std::move(e);
    } else {
      by_tick_[e.tick][e.shard] = std::move(e);
    }
  });
}

bool ShardPeer::complete(uint64_t tick) const {
  const auto it = by_tick_.find(tick);
  return it != by_tick_.end() && it->second.size() + 1 == shards_;
}

std::vector<const Exchange*> ShardPeer::of(uint64_t tick) const {
  std::vector<const Exchange*> out;
  if (const auto it = by_tick_.find(tick); it != by_tick_.end()) {
    for (const auto& [s, e] : it->second) out.push_back(&e);
  }
  return out;
}

std::vector<const Exchange*> ShardPeer::last() const {
  std::vector<const Exchange*> out;
  for (const auto& [s, e] : last_) out.push_back(&e);
  return out;
}

std::string ShardPeer::missing(uint64_t tick) const {
  std::string out;
  const auto it = by_tick_.find(tick);
  for (uint32_t s = 0; s < shards_; ++s) {
    if (s == shard_ || (it != by_tick_.end() && it->second.count(s))) continue;
    out += (out.empty() ? "" : ", ") + std::to_string(s);
  }
  return out;
}

void ShardPeer::forget_before(uint64_t tick) {
  by_tick_.erase(by_tick_.begin(), by_tick_.lower_bound(tick));
}

}  // namespace smart::sim::detail
