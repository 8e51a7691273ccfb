// A shard's exchange through the wire type and back, and the checks a received one passes
// (wire::check_exchange) on forged copies.
#include "shard_wire.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "smart/convert/validate.hpp"

namespace smart::sim::detail {
namespace {

using ::testing::HasSubstr;

const wire::Bounds kBounds{-1, -1, 10, 10};

Exchange sample() {
  Exchange e;
  e.shard = 1;
  e.shards = 2;
  e.run_id = 7;
  e.tick = 42;
  RobotHandover h;
  h.robot = 3;
  h.to_shard = 0;
  h.physics = {{1.25, 2.5, 0.1, 0.3, -0.2, 0.05}, 0.4, 0.5, 0.35, 0.45, 3.9, true, {{2, 4.1}}};
  h.agent.last_command = {0.3, 0.01};
  h.agent.queue = {7, true, 11, {{12, agent::ActionKind::kMove, 1, 2, 1.5, 2, 0}}, 1};
  h.agent.pose = {{1.2, 2.5, 0.1}, 0.3, 0.01, 4.2, true};
  h.agent.wheels = {0.29, 0.31};
  h.agent.now_s = 4.2;
  h.agent.stall_until_s = 5.0;
  h.agent.stall_checked_seq = 12;
  h.agent.last_front_move = true;
  h.agent.stalls = 2;
  h.agent.delay_until_s = 6.3;
  h.agent.delay_tick = 42;
  h.agent.delays = 3;
  h.reported_finished = 11;
  h.reported_executing = 12;
  e.outbox.handovers.push_back(h);
  e.outbox.ghosts.push_back({5, {4, 4, 1, 0.5, 0, 0}});
  e.progress.push_back({6, 7, 3, 4});
  e.finished_total = 99;
  e.contacts.robot_robot_events = 1;
  e.contacts.min_gap_m = -0.01;
  return e;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ShardWire, AnExchangeSurvivesTheWireBitForBit) {
  const Exchange e = sample();
  const ExchangeBuffer buf(e);
  ASSERT_EQ(wire::check_exchange(buf.view(), 8, kBounds), "");
  const Exchange back = from_wire(buf.view());
  EXPECT_EQ(back.tick, 42u);
  EXPECT_EQ(back.finished_total, 99u);
  ASSERT_EQ(back.outbox.handovers.size(), 1u);
  const auto& a = e.outbox.handovers[0];
  const auto& b = back.outbox.handovers[0];
  EXPECT_EQ(b.robot, 3u);
  EXPECT_TRUE(same_bits(b.physics.motion.vy_mps, a.physics.motion.vy_mps));
  EXPECT_TRUE(same_bits(b.physics.ramp_from_r_mps, a.physics.ramp_from_r_mps));
  EXPECT_EQ(b.physics.pair_last_contact_s, a.physics.pair_last_contact_s);
  EXPECT_TRUE(b.physics.awake);
  ASSERT_EQ(b.agent.queue.pending.size(), 1u);
  EXPECT_EQ(b.agent.queue.pending[0].seq, 12u);
  EXPECT_TRUE(same_bits(b.agent.queue.pending[0].to_x_m, 1.5));
  EXPECT_EQ(b.agent.queue.finished_seq, 11);
  EXPECT_TRUE(same_bits(b.agent.pose.stamp_s, a.agent.pose.stamp_s));
  EXPECT_EQ(b.agent.stall_checked_seq, 12);
  EXPECT_EQ(b.agent.stalls, 2u);
  EXPECT_TRUE(same_bits(b.agent.delay_until_s, 6.3));
  EXPECT_EQ(b.agent.delay_tick, 42);
  EXPECT_EQ(b.agent.delays, 3u);
  EXPECT_EQ(b.reported_executing, 12);
  ASSERT_EQ(back.outbox.ghosts.size(), 1u);
  EXPECT_EQ(back.outbox.ghosts[0].robot, 5u);
  ASSERT_EQ(back.progress.size(), 1u);
  EXPECT_EQ(back.progress[0].finished_seq, 3);
  EXPECT_DOUBLE_EQ(back.contacts.min_gap_m, -0.01);
}

// Each forgery breaks one thing; the check names it.
TEST(ShardWire, ForgedExchangesAreRejectedWithTheReason) {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    void (*forge)(Exchange&);
    const char* reason;
  };
  const std::vector<Case> cases = {
      {[](Exchange& e) { e.shards = 1; }, "is not a shard of a sharded sim"},
      {[](Exchange& e) { e.shard = 2; }, "is not a shard of a sharded sim"},
      {[](Exchange& e) { e.outbox.handovers[0].robot = 8; }, "robot 8 is not in this fleet"},
      {[](Exchange& e) { e.outbox.handovers[0].to_shard = 2; }, "not in this sim"},
      {[](Exchange& e) { e.outbox.handovers[0].physics.motion.x_m = 1e9; }, "outside the map"},
      {[](Exchange& e) { e.outbox.handovers[0].agent.wheels.left_mps = nan; },
       "not a finite number: handovers[0].wheel_left_mps"},
      {[](Exchange& e) { e.outbox.handovers[0].agent.queue.pending[0].to_y_m = nan; },
       "pending[0].to_y_m"},
      {[](Exchange& e) { e.outbox.handovers[0].physics.pair_last_contact_s[0].first = 9; },
       "robot 9 is not in this fleet"},
      {[](Exchange& e) { e.outbox.ghosts[0].motion.w_radps = nan; }, "ghosts[0].motion.w_radps"},
      {[](Exchange& e) { e.progress[0].robot_id = 100; }, "robot 100 is not in this fleet"},
  };
  for (const auto& c : cases) {
    Exchange e = sample();
    c.forge(e);
    const ExchangeBuffer buf(e);
    EXPECT_THAT(wire::check_exchange(buf.view(), 8, kBounds), HasSubstr(c.reason));
  }
  // A forged action type is no enumerator: its bytes are written directly.
  Exchange e = sample();
  ExchangeBuffer buf(e);
  auto msg = buf.view();
  auto* action = msg.handovers._buffer[0].pending._buffer;
  const uint32_t bogus = 7;
  std::memcpy(&action->type, &bogus, sizeof bogus);
  EXPECT_THAT(wire::check_exchange(msg, 8, kBounds), HasSubstr("unknown action type"));
  // A sequence claiming more elements than the fleet has robots.
  msg.ghosts._length = 9;
  EXPECT_THAT(wire::check_exchange(msg, 8, kBounds), HasSubstr("longer than the fleet"));
}

}  // namespace
}  // namespace smart::sim::detail
