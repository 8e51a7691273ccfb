// ShardPeer over real DDS (loopback, one domain): which writer may speak for a shard. Exchanges
// that pass the wire checks but come from a second writer of a held shard number, from a writer
// that already speaks for another shard, or claim this shard's own number are refused, named
// and counted; a holder that left is replaced.
#include "shard_host.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "smart/dds/domain.hpp"
#include "support/dds_test_support.hpp"

namespace smart::sim::detail {
namespace {

using ::testing::HasSubstr;
using namespace std::chrono_literals;

constexpr uint32_t kShards = 3;
constexpr std::size_t kRobots = 4;
const wire::Bounds kBounds{-1, -1, 10, 10};

Exchange exchange(uint32_t shard, uint64_t tick, uint64_t finished_total) {
  Exchange e;
  e.shard = shard;
  e.shards = kShards;
  e.run_id = 7;
  e.tick = tick;
  e.finished_total = finished_total;
  return e;
}

// A shard on a participant of its own (a process, as far as DDS can tell).
struct Shard {
  Shard(dds::Domain& d, uint32_t shard)
      : participant(d),
        peer(participant, dds::default_qos_profile(), shard, kShards, kRobots, kBounds) {}
  dds::Participant participant;
  ShardPeer peer;
};

// Takes what arrives at `s` until `done` holds (or 5 s passed).
template <class Done>
bool take_until(ShardPeer& s, Done&& done) {
  const auto until = std::chrono::steady_clock::now() + 5s;
  while (std::chrono::steady_clock::now() < until) {
    s.take([](const Exchange&) {});
    if (done()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

uint64_t refused(const ShardPeer& s, const std::string& part) {
  uint64_t n = 0;
  for (const auto& [topic, reasons] : s.rejections().counts()) {
    for (const auto& [why, count] : reasons) {
      if (topic == "shard" && why.find(part) != std::string::npos) n += count;
    }
  }
  return n;
}

TEST(ShardPeer, ASecondWriterOfAHeldShardIsRefusedUntilTheHolderLeaves) {
  dds::Domain domain(test::kShardPeerWriters, test::loopback());
  Shard me(domain, 0), forger(domain, 1);
  auto real = std::make_unique<Shard>(domain, 1);
  me.peer.publish(exchange(0, 1, 0));  // our own exchange comes back to our reader: not counted
  real->peer.publish(exchange(1, 1, 5));
  ASSERT_TRUE(take_until(me.peer, [&] { return !me.peer.of(1).empty(); }));
  ASSERT_EQ(me.peer.of(1).at(0)->finished_total, 5u);

  // A forger (or a second `smart sim --shard 1/3`) speaks for shard 1 too.
  forger.peer.publish(exchange(1, 1, 99));
  forger.peer.publish(exchange(1, 2, 99));
  ASSERT_TRUE(take_until(me.peer, [&] { return refused(me.peer, "held by another writer") >= 2; }))
      << "the second writer's exchanges were not refused";
  EXPECT_EQ(me.peer.of(1).at(0)->finished_total, 5u);
  EXPECT_TRUE(me.peer.of(2).empty());
  EXPECT_EQ(me.peer.rejections().total(), 2u) << "our own exchange was counted as refused";

  // The holder leaves: the next writer of shard 1 (a restarted shard) is taken.
  real.reset();
  ASSERT_TRUE(take_until(me.peer, [&] {
    forger.peer.publish(exchange(1, 3, 7));
    return !me.peer.of(3).empty();
  }));
  EXPECT_EQ(me.peer.of(3).at(0)->finished_total, 7u);
}

TEST(ShardPeer, AWriterClaimingAnotherShardOrThisShardsNumberIsRefused) {
  dds::Domain domain(test::kShardPeerClaims, test::loopback());
  Shard me(domain, 0), other(domain, 1);
  other.peer.publish(exchange(1, 1, 3));
  ASSERT_TRUE(take_until(me.peer, [&] { return !me.peer.of(1).empty(); }));
  // The writer that speaks for shard 1 also claims shard 2, then this shard's number 0.
  other.peer.publish(exchange(2, 1, 3));
  // Reasons are counted by class (numbers as '#'), the first ones kept verbatim.
  ASSERT_TRUE(take_until(me.peer, [&] { return refused(me.peer, "also claims shard #/#") == 1; }));
  other.peer.publish(exchange(0, 1, 3));
  ASSERT_TRUE(
      take_until(me.peer, [&] { return refused(me.peer, "another process also runs shard #/#"); }));
  const auto& examples = me.peer.rejections().examples().at("shard");
  std::string all;
  for (const auto& [cls, texts] : examples) {
    for (const auto& t : texts) all += t + "\n";
  }
  EXPECT_NE(all.find("also claims shard 2/3"), std::string::npos) << all;
  EXPECT_NE(all.find("another process also runs shard 0/3"), std::string::npos) << all;
  EXPECT_EQ(me.peer.of(1).size(), 1u) << "only the holder's exchange of period 1 is kept";
}

// A shard that waits sends its last two exchanges again (ShardBarrier::should_repeat; CI stop
// 52 lost one on its way to one shard). A receiver hands each exchange over once: a repeat of a
// period it holds, or of one applied and forgotten, is dropped uncounted (no progress relayed
// twice), and exchanges after the repeat arrive as usual.
TEST(ShardPeer, RepeatedExchangesAreHandedOverOnceAndRefuseNothing) {
  dds::Domain domain(test::kShardPeerRepeats, test::loopback());
  Shard me(domain, 0), other(domain, 1);
  std::vector<uint64_t> handed;  // the periods of the exchanges handed over, in order
  const auto take_until_period = [&](uint64_t tick) {
    const auto until = std::chrono::steady_clock::now() + 5s;
    while (std::chrono::steady_clock::now() < until) {
      me.peer.take([&](const Exchange& e) { handed.push_back(e.tick); });
      if (!handed.empty() && handed.back() == tick) return true;
      std::this_thread::sleep_for(5ms);
    }
    return false;
  };
  for (uint64_t tick = 0; tick < 3; ++tick) other.peer.publish(exchange(1, tick, 10 + tick));
  ASSERT_TRUE(take_until_period(2));
  me.peer.forget_before(2);  // periods 0 and 1 applied
  other.peer.repeat();       // periods 1 and 2 again: one forgotten, one held
  other.peer.publish(exchange(1, 3, 13));
  ASSERT_TRUE(take_until_period(3));  // one writer's samples arrive in order: the repeats first
  EXPECT_EQ(handed, (std::vector<uint64_t>{0, 1, 2, 3}));
  EXPECT_EQ(me.peer.of(2).at(0)->finished_total, 12u);
  EXPECT_EQ(me.peer.of(3).at(0)->finished_total, 13u);
  EXPECT_TRUE(me.peer.of(1).empty()) << "forgotten";
  EXPECT_TRUE(me.peer.rejections().counts().empty());
}

}  // namespace
}  // namespace smart::sim::detail
