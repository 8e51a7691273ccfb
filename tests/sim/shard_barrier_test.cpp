// The shard barrier driven by scripted event sequences: no DDS, no threads, no sleeps.
#include "smart/sim/shard_barrier.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace smart::sim {
namespace {

constexpr uint64_t kRun = 7;
constexpr double kTimeoutS = 5, kReannounceS = 1, kJoinS = 20;

wire::Tick answer(uint64_t k, uint64_t windows, bool stop = false) {
  return {kRun, k, 0.1 * double(k), windows, stop};
}

using Waiting = ShardTimeout::Waiting;

TEST(ShardBarrier, ThePeriodIsAppliedOnceEveryShardsExchangeIsInAndTheLeadAnnouncesTheSum) {
  ShardBarrier lead(0, 3, kTimeoutS, kReannounceS, kJoinS);
  lead.sent(0, 4, 0.0);
  EXPECT_FALSE(lead.ready());
  EXPECT_TRUE(lead.received(2, 0, 10));
  EXPECT_FALSE(lead.ready()) << "shard 1 is missing";
  EXPECT_TRUE(lead.received(1, 0, 100));
  ASSERT_TRUE(lead.ready());
  lead.apply(0.5);
  EXPECT_TRUE(lead.applied());
  EXPECT_FALSE(lead.ready()) << "applied once";
  EXPECT_EQ(lead.announced_total(), 114u);
}

TEST(ShardBarrier, AShardStepsOnlyWhenItsPeriodIsAppliedAndTheMonitorsAnswerAddsUp) {
  ShardBarrier b(1, 2, kTimeoutS, kReannounceS, kJoinS);
  b.sent(0, 0, 0.0);
  b.on_answer(answer(0, 12));
  EXPECT_FALSE(b.may_step(kRun, 12)) << "the other shard's exchange of period 0 is not in";
  b.received(0, 0, 0);
  b.apply(0.1);
  EXPECT_FALSE(b.may_step(kRun, 11)) << "windows do not add up to the answer yet";
  EXPECT_FALSE(b.may_step(kRun + 1, 12)) << "an answer of another run";
  EXPECT_TRUE(b.may_step(kRun, 12));
  b.sent(1, 3, 0.2);
  EXPECT_FALSE(b.applied());
  EXPECT_FALSE(b.may_step(kRun, 12)) << "period 1 is not applied, the answer was for period 0";
}

TEST(ShardBarrier, AFasterShardsNextExchangeWaitsForItsPeriodAndRepeatsAreIgnored) {
  ShardBarrier b(1, 2, kTimeoutS, kReannounceS, kJoinS);
  b.sent(0, 0, 0.0);
  EXPECT_TRUE(b.received(0, 0, 5));
  b.apply(0.0);
  EXPECT_FALSE(b.received(0, 0, 5)) << "period 0 is applied already";
  EXPECT_TRUE(b.received(0, 1, 9)) << "shard 0 stepped first";
  EXPECT_FALSE(b.ready()) << "this shard has not stepped to period 1";
  b.sent(1, 2, 0.1);
  EXPECT_TRUE(b.ready());
  EXPECT_FALSE(b.received(0, 3, 1)) << "two periods ahead: impossible, ignored";
  EXPECT_FALSE(b.received(1, 1, 1)) << "this shard's own number";
  EXPECT_FALSE(b.received(2, 1, 1)) << "no shard 2 of 2";
}

TEST(ShardBarrier, ARepeatedExchangeReplacesTheFirstInTheLeadsTotal) {
  ShardBarrier lead(0, 2, kTimeoutS, kReannounceS, kJoinS);
  lead.sent(0, 1, 0.0);
  lead.received(1, 0, 5);
  lead.received(1, 0, 6);
  lead.apply(0.0);
  EXPECT_EQ(lead.announced_total(), 7u);
}

// Steps shard `b` of four through periods 0 and 1 (every exchange in, answered), to period 2 sent
// at now_s.
void run_to_period_two(ShardBarrier& b, uint32_t shard, double now_s) {
  for (uint64_t k = 0; k < 2; ++k) {
    b.sent(k, 0, now_s - 2 + double(k));
    for (uint32_t s = 0; s < 4; ++s) {
      if (s != shard) b.received(s, k, 0);
    }
    b.apply(now_s - 2 + double(k));
    b.on_answer(answer(k, 0));
    ASSERT_TRUE(b.may_step(kRun, 0));
  }
  b.sent(2, 0, now_s);
}

TEST(ShardBarrier, WaitingForShardsTimesOutNamingTheMissingOnes) {
  ShardBarrier b(2, 4, kTimeoutS, kReannounceS, kJoinS);
  run_to_period_two(b, 2, 10.0);
  b.received(1, 2, 0);
  EXPECT_EQ(b.timed_out(15.0).waiting, Waiting::kNothing);
  const auto t = b.timed_out(15.5);
  EXPECT_EQ(t.waiting, Waiting::kShards);
  EXPECT_EQ(t.tick, 2u);
  EXPECT_EQ(t.missing, (std::vector<uint32_t>{0, 3}));
  EXPECT_EQ(t.waited_s, kTimeoutS);
}

// Regression (CI, stop 42): the shards of `smart run --sim-hosts 4` on a loaded machine gave up
// on shard 0's first exchange after --timeout-s (30 s) while their monitor still waited its
// join window; periods 0 and 1 (start-up and every shard's first step) now wait as long.
TEST(ShardBarrier, StartUpAndTheFirstStepWaitTheJoinWindow) {
  for (const uint64_t period : {0u, 1u}) {
    SCOPED_TRACE(period);
    ShardBarrier b(3, 4, kTimeoutS, kReannounceS, kJoinS);
    b.sent(0, 0, 10.0);
    if (period == 1) {
      for (uint32_t s = 0; s < 3; ++s) b.received(s, 0, 0);
      b.apply(11.0);
      b.on_answer(answer(0, 0));
      b.sent(1, 0, 12.0);
    }
    const double sent_s = period == 0 ? 10.0 : 12.0;
    b.received(1, period, 0);
    EXPECT_EQ(b.timed_out(sent_s + kTimeoutS + 1).waiting, Waiting::kNothing);
    EXPECT_EQ(b.timed_out(sent_s + kJoinS).waiting, Waiting::kNothing);
    const auto t = b.timed_out(sent_s + kJoinS + 0.5);
    EXPECT_EQ(t.waiting, Waiting::kShards);
    EXPECT_EQ(t.tick, period);
    EXPECT_EQ(t.missing, (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(t.waited_s, kJoinS);
  }
}

TEST(ShardBarrier, AnAppliedPeriodWithoutAnAnswerTimesOutOnTheMonitor) {
  ShardBarrier b(1, 2, kTimeoutS, kReannounceS, kJoinS);
  b.sent(0, 0, 0.0);
  b.received(0, 0, 0);
  b.apply(1.0);
  const auto t = b.timed_out(5.5);
  EXPECT_EQ(t.waiting, Waiting::kMonitor) << "the wait runs from this shard's own exchange";
  EXPECT_TRUE(t.missing.empty());
  EXPECT_EQ(t.waited_s, kTimeoutS)
      << "the monitor's answer is waited for timeout_s, start-up or not";
}

TEST(ShardBarrier, TheLeadsWaitRunsFromItsAnnouncementAndOnlyTheLeadReannounces) {
  ShardBarrier lead(0, 2, kTimeoutS, kReannounceS, kJoinS);
  ShardBarrier other(1, 2, kTimeoutS, kReannounceS, kJoinS);
  lead.sent(0, 0, 0.0);
  other.sent(0, 0, 0.0);
  lead.received(1, 0, 0);
  other.received(0, 0, 0);
  EXPECT_FALSE(lead.should_reannounce(3.0)) << "nothing announced before the period is applied";
  lead.apply(4.0);
  other.apply(4.0);
  EXPECT_EQ(lead.timed_out(8.5).waiting, Waiting::kNothing);
  EXPECT_EQ(other.timed_out(8.5).waiting, Waiting::kMonitor);
  EXPECT_FALSE(lead.should_reannounce(4.5));
  EXPECT_TRUE(lead.should_reannounce(5.5));
  EXPECT_FALSE(other.should_reannounce(5.5));
  lead.reannounced(5.5);
  EXPECT_FALSE(lead.should_reannounce(6.0));
  lead.on_answer(answer(0, 0));
  EXPECT_FALSE(lead.should_reannounce(9.0)) << "answered";
}

// What a shard reports when the monitor stops the run while the fleet waits (the log of a lost
// run: CI stop 52's sharded run went silent after tick 0 and no shard said why).
TEST(ShardBarrier, WhatAShardWaitsForIsTheMissingShardsThenTheMonitorThenNothing) {
  ShardBarrier lead(0, 3, kTimeoutS, kReannounceS, kJoinS);
  EXPECT_EQ(lead.waiting().waiting, Waiting::kNothing) << "not started";
  lead.sent(0, 0, 0.0);
  lead.received(2, 0, 0);
  auto w = lead.waiting();
  EXPECT_EQ(w.waiting, Waiting::kShards);
  EXPECT_EQ(w.tick, 0u);
  EXPECT_EQ(w.missing, std::vector<uint32_t>{1});
  lead.received(1, 0, 0);
  lead.apply(0.1);
  w = lead.waiting();
  EXPECT_EQ(w.waiting, Waiting::kMonitor);
  EXPECT_EQ(w.tick, 0u);
  lead.on_answer(answer(0, 4));
  EXPECT_EQ(lead.waiting().waiting, Waiting::kNothing) << "answered: the windows are the host's";
  lead.sent(1, 2, 0.2);
  lead.received(2, 1, 0);
  lead.on_answer(answer(0, 4, true));  // the monitor gave up and stops at the tick it answered
  w = lead.waiting();
  EXPECT_EQ(w.waiting, Waiting::kShards);
  EXPECT_EQ(w.tick, 1u);
  EXPECT_EQ(w.missing, std::vector<uint32_t>{1});
  EXPECT_TRUE(lead.stop());
}

// CI stop 52: one shard never got another's exchange of period 0 (nothing refused) and the
// fleet waited for it until the monitor gave up.
TEST(ShardBarrier, AShardThatWaitsWithoutSteppingRepeatsItsExchangesEveryReannouncePeriod) {
  ShardBarrier b(1, 2, kTimeoutS, kReannounceS, kJoinS);
  EXPECT_FALSE(b.should_repeat(5.0)) << "nothing sent yet";
  b.sent(0, 0, 0.0);
  EXPECT_FALSE(b.should_repeat(0.9));
  EXPECT_TRUE(b.should_repeat(1.1)) << "waiting for the other shard's exchange";
  b.repeated(1.1);
  EXPECT_FALSE(b.should_repeat(2.0));
  b.received(0, 0, 0);
  b.apply(2.0);
  EXPECT_TRUE(b.should_repeat(2.2)) << "applied, waiting for the answer: the lead may lack ours";
  b.repeated(2.2);
  b.on_answer(answer(0, 0));
  ASSERT_TRUE(b.may_step(kRun, 0));
  b.sent(1, 0, 2.5);
  EXPECT_FALSE(b.should_repeat(3.4)) << "a step sends a new exchange: the wait starts again";
  EXPECT_TRUE(b.should_repeat(3.6));
}

TEST(ShardBarrier, AStopIsKeptWhateverItsTick) {
  ShardBarrier b(1, 2, kTimeoutS, kReannounceS, kJoinS);
  b.sent(0, 0, 0.0);
  EXPECT_FALSE(b.stop());
  b.on_answer(answer(41, 0, true));
  EXPECT_TRUE(b.stop());
}

TEST(ShardBarrier, MisuseIsAnErrorNamingTheShardAndThePeriod) {
  EXPECT_THROW(ShardBarrier(0, 1, kTimeoutS, kReannounceS, kJoinS), std::invalid_argument);
  EXPECT_THROW(ShardBarrier(2, 2, kTimeoutS, kReannounceS, kJoinS), std::invalid_argument);
  EXPECT_THROW(ShardBarrier(0, 2, kTimeoutS, kReannounceS, kTimeoutS / 2), std::invalid_argument)
      << "a start-up wait shorter than the timeout";
  ShardBarrier b(0, 2, kTimeoutS, kReannounceS, kJoinS);
  EXPECT_THROW(b.sent(1, 0, 0.0), std::logic_error) << "the first exchange is period 0's";
  b.sent(0, 0, 0.0);
  EXPECT_THROW(b.apply(0.0), std::logic_error) << "shard 1's exchange is not in";
  try {
    b.sent(1, 0, 0.0);
    FAIL() << "stepped before period 0 was applied";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(),
                 "shard 0: exchange of period 1 sent, expected 1 after applying period 0");
  }
}

}  // namespace
}  // namespace smart::sim
