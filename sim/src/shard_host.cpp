#include "shard_host.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace smart::sim::detail {

ShardPeer::ShardPeer(const dds::Participant& p, const dds::QosProfile& qos, uint32_t shard,
                     uint32_t shards, std::size_t robots, wire::Bounds bounds)
    : shard_(shard),
      shards_(shards),
      robots_(robots),
      bounds_(bounds),
      out_(p, qos),
      from_sims_(dds::admit_roles(p, {"sim"})),
      in_(p, qos, from_sims_) {
  if (dds_get_instance_handle(out_.handle(), &self_) < 0) {
    throw std::runtime_error("sim shard " + std::to_string(shard) +
                             ": cannot read the handle of its own exchange writer");
  }
}

void ShardPeer::publish(const Exchange& e) {
  if (e.last) {
    const ExchangeBuffer buf(e);
    out_.write(buf.view());
    return;
  }
  mine_.emplace_back(e);
  if (mine_.size() > 2) mine_.pop_front();
  out_.write(mine_.back().view());
}

void ShardPeer::repeat() {
  for (const auto& buf : mine_) out_.write(buf.view());
}

bool ShardPeer::known(uint32_t shard, uint64_t tick) const {
  if (tick < forgotten_before_) return true;
  const auto it = by_tick_.find(tick);
  return it != by_tick_.end() && it->second.count(shard) > 0;
}

void ShardPeer::take(const std::function<void(const Exchange&)>& on_receipt) {
  for (const auto& [writer, n] : from_sims_.take_refused()) {
    if (rejected_.count("shard", dds::kNotRunMember, {}, n)) {
      spdlog::warn("sim shard: {} exchanges refused: {}", n, dds::kNotRunMember);
    }
  }
  in_.take_each_from([&](const smart_msg_ShardExchange& m, dds_instance_handle_t from) {
    if (from == self_) return;  // our own
    std::string why = wire::check_exchange(m, robots_, bounds_);
    if (why.empty() && m.shards != shards_) {
      why = "from a sim of " + std::to_string(m.shards) + " shards, this one has " +
            std::to_string(shards_) + " (every shard must be started with the same --shard I/N)";
    }
    if (why.empty()) why = admit(m.shard, from);
    if (!why.empty()) {
      if (rejected_.count("shard", why)) spdlog::warn("sim shard: exchange rejected: {}", why);
      return;
    }
    if (!m.last && known(m.shard, m.tick)) return;  // a repeat (ShardBarrier::should_repeat)
    Exchange e = from_wire(m);
    on_receipt(e);
    if (e.last) {
      last_[e.shard] = std::move(e);
    } else {
      by_tick_[e.tick][e.shard] = std::move(e);
    }
  });
}

std::string ShardPeer::admit(uint32_t shard, dds_instance_handle_t from) {
  const auto name = [this](uint32_t s) {
    return "shard " + std::to_string(s) + "/" + std::to_string(shards_);
  };
  if (shard == shard_) {
    return "another process also runs " + name(shard) +
           " of this run (this one does); stop it: each --shard I/N once per run";
  }
  for (const auto& [s, w] : holder_) {
    if (w == from && s != shard) {
      return "a writer that speaks for " + name(s) + " also claims " + name(shard) +
             "; refused (a forged exchange: run with --security to allow only the sim identity)";
    }
  }
  auto [it, fresh] = holder_.try_emplace(shard, from);
  if (fresh || it->second == from) return {};
  if (in_.writer_matched(it->second)) {
    return name(shard) + " is held by another writer in this run; a second writer's exchange " +
           "is refused (a second process with that --shard, or a forger: run with --security)";
  }
  it->second = from;  // the holder left: a restarted shard speaks for it now
  return {};
}

std::size_t ShardPeer::writers_discovered() const {
  std::vector<dds_instance_handle_t> handles(std::size_t{2} * dds::kMaxShards);
  const auto n = dds_get_matched_publications(in_.handle(), handles.data(), handles.size());
  if (n < 0) return 0;
  handles.resize(std::min(handles.size(), static_cast<std::size_t>(n)));
  return static_cast<std::size_t>(std::count_if(
      handles.begin(), handles.end(), [this](dds_instance_handle_t h) { return h != self_; }));
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

void ShardPeer::forget_before(uint64_t tick) {
  by_tick_.erase(by_tick_.begin(), by_tick_.lower_bound(tick));
  forgotten_before_ = std::max(forgotten_before_, tick);
}

}  // namespace smart::sim::detail
