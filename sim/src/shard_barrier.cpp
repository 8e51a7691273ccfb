#include "smart/sim/shard_barrier.hpp"

#include <stdexcept>
#include <string>

namespace smart::sim {

ShardBarrier::ShardBarrier(uint32_t shard, uint32_t shards, double timeout_s, double reannounce_s,
                           double join_s)
    : shard_(shard),
      shards_(shards),
      handshake_(timeout_s, reannounce_s),
      timeout_s_(timeout_s),
      reannounce_s_(reannounce_s),
      join_s_(join_s) {
  if (shards < 2 || shard >= shards) {
    throw std::invalid_argument("shard " + std::to_string(shard) + "/" + std::to_string(shards) +
                                ": a sharded sim has at least 2 shards, numbered from 0");
  }
  if (!(join_s >= timeout_s)) {
    throw std::invalid_argument("shard " + std::to_string(shard) + ": the start-up wait (" +
                                std::to_string(join_s) + " s) is shorter than the timeout (" +
                                std::to_string(timeout_s) + " s)");
  }
}

void ShardBarrier::sent(uint64_t tick, uint64_t finished_total, double now_s) {
  const uint64_t expected = started_ ? tick_ + 1 : 0;
  if (tick != expected || (started_ && !applied_)) {
    throw std::logic_error("shard " + std::to_string(shard_) + ": exchange of period " +
                           std::to_string(tick) + " sent, expected " + std::to_string(expected) +
                           (started_ && !applied_
                                ? " after applying period " + std::to_string(tick_)
                                : std::string()));
  }
  started_ = true;
  tick_ = tick;
  own_total_ = finished_total;
  applied_ = false;
  repeated_at_s_ = now_s;
  // The lead waits from its announcement to the monitor (or the start), the others from here.
  if (!lead() || tick == 0) announced(tick, now_s);
}

bool ShardBarrier::received(uint32_t shard, uint64_t tick, uint64_t finished_total) {
  if (shard == shard_ || shard >= shards_) return false;
  const bool current = tick == tick_ && !applied_;
  const bool next = tick == tick_ + 1 || (tick == tick_ && !started_);
  if (!current && !next) return false;
  totals_[tick][shard] = finished_total;
  return true;
}

bool ShardBarrier::ready() const {
  if (!started_ || applied_) return false;
  const auto it = totals_.find(tick_);
  return it != totals_.end() && it->second.size() + 1 == shards_;
}

void ShardBarrier::apply(double now_s) {
  if (!ready()) {
    throw std::logic_error("shard " + std::to_string(shard_) + ": period " + std::to_string(tick_) +
                           " applied before every exchange was in");
  }
  uint64_t total = own_total_;
  for (const auto& [s, t] : totals_.at(tick_)) total += t;
  totals_.erase(totals_.begin(), totals_.upper_bound(tick_));
  applied_ = true;
  if (lead()) {
    announced_total_ = total;
    announced(tick_, now_s);
  }
}

void ShardBarrier::announced(uint64_t tick, double now_s) {
  handshake_.announced(tick, now_s);
  waiting_since_s_ = now_s;
}

ShardTimeout ShardBarrier::timed_out(double now_s) const {
  if (!started_) return {};
  if (applied_) {
    if (!handshake_.timed_out(now_s)) return {};
    return {ShardTimeout::Waiting::kMonitor, tick_, {}, timeout_s_};
  }
  const double wait_s = tick_ <= kLastJoinPeriod ? join_s_ : timeout_s_;
  if (now_s - waiting_since_s_ <= wait_s) return {};
  return {ShardTimeout::Waiting::kShards, tick_, missing(), wait_s};
}

ShardTimeout ShardBarrier::waiting() const {
  if (!started_) return {};
  if (!applied_) return {ShardTimeout::Waiting::kShards, tick_, missing(), 0};
  if (!handshake_.answered()) return {ShardTimeout::Waiting::kMonitor, tick_, {}, 0};
  return {};
}

std::vector<uint32_t> ShardBarrier::missing() const {
  std::vector<uint32_t> out;
  const auto it = totals_.find(tick_);
  for (uint32_t s = 0; s < shards_; ++s) {
    if (s != shard_ && (it == totals_.end() || !it->second.count(s))) out.push_back(s);
  }
  return out;
}

}  // namespace smart::sim
