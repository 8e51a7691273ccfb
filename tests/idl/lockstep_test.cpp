// The lock-step handshake of both sides, scripted (no DDS).
#include "smart/wire/lockstep.hpp"

#include <gtest/gtest.h>

namespace smart::wire {
namespace {

TEST(SyncCounter, RaisesMarksNeverLowersThemAndSumsTheGrowth) {
  SyncCounter c(3);
  EXPECT_EQ(c.raise(0, 4), 4u);
  EXPECT_EQ(c.raise(2, 1), 1u);
  EXPECT_EQ(c.raise(0, 2), 0u);  // an older window
  EXPECT_EQ(c.raise(0, 6), 2u);
  EXPECT_EQ(c.total(), 7u);
  EXPECT_EQ(c.mark(0), 6u);
  c.reset();
  EXPECT_EQ(c.total(), 0u);
  EXPECT_EQ(c.mark(2), 0u);
}

TEST(MonitorHandshake, AnswersTheNewestTickOnceItsProgressAddsUp) {
  MonitorHandshake h;
  EXPECT_FALSE(h.ready(0));
  h.on_tick({5, 1, 0.1, 3, false});
  h.on_tick({5, 0, 0.0, 0, false});  // older than the pending one
  EXPECT_EQ(h.pending()->tick, 1u);
  EXPECT_FALSE(h.ready(2));
  ASSERT_TRUE(h.ready(3));
  const Tick a = h.answer(5, 11, false);
  EXPECT_EQ(a.tick, 1u);
  EXPECT_DOUBLE_EQ(a.sim_time_s, 0.1);
  EXPECT_EQ(a.sync_total, 11u);
  EXPECT_FALSE(h.pending());
  EXPECT_EQ(h.last_answered(), 1u);
  h.on_tick({5, 0, 0.0, 0, false});  // late: before the last answer
  EXPECT_FALSE(h.pending());
  h.on_tick({5, 1, 0.1, 3, false});  // re-announced: answered again
  EXPECT_TRUE(h.ready(3));
}

// The last answer goes out again once no newer tick came for the period since it went out:
// the same sample, for a host whose reader matched after it was sent.
TEST(MonitorHandshake, TheLastAnswerIsSentAgainWhileNoNewerTickComes) {
  MonitorHandshake h;
  EXPECT_FALSE(h.should_reanswer(100.0, 0.5));  // nothing answered yet
  h.on_tick({5, 0, 0.0, 0, false});
  const Tick a = h.answer(5, 7, false);
  h.sent(1.0);
  EXPECT_FALSE(h.should_reanswer(1.4, 0.5));
  ASSERT_TRUE(h.should_reanswer(1.6, 0.5));
  EXPECT_EQ(h.last_answer()->tick, a.tick);
  EXPECT_EQ(h.last_answer()->sync_total, 7u);
  h.sent(1.6);
  EXPECT_FALSE(h.should_reanswer(2.0, 0.5));
  EXPECT_TRUE(h.should_reanswer(2.2, 0.5));
  h.on_tick({5, 1, 0.1, 2, false});  // the next tick: answered when its progress is in
  EXPECT_FALSE(h.should_reanswer(9.0, 0.5));
}

TEST(HostHandshake, StepsOnlyWithTheAnswerToItsTickAndTheWindowsItAnnounces) {
  HostHandshake h(30.0, 0.5);
  h.announced(4, 10.0);
  h.on_answer({9, 3, 0.3, 12, false});  // an answer to an older tick
  EXPECT_FALSE(h.may_step(9, 12));
  h.on_answer({9, 4, 0.4, 12, false});
  EXPECT_FALSE(h.may_step(9, 11));  // a window has not arrived yet
  EXPECT_FALSE(h.may_step(8, 12));  // another run
  EXPECT_TRUE(h.may_step(9, 12));
  h.announced(5, 10.1);
  EXPECT_FALSE(h.may_step(9, 12));  // the next tick needs its own answer
}

TEST(HostHandshake, ReannouncesWithoutAnAnswerAndTimesOutFromTheFirstAnnouncement) {
  HostHandshake h(2.0, 0.5);
  h.announced(0, 1.0);
  EXPECT_FALSE(h.should_reannounce(1.4));
  EXPECT_TRUE(h.should_reannounce(1.6));
  h.reannounced(1.6);
  EXPECT_FALSE(h.should_reannounce(2.0));
  EXPECT_FALSE(h.timed_out(2.9));
  EXPECT_TRUE(h.timed_out(3.1));  // re-announcing does not extend the wait
  h.on_answer({1, 0, 0, 0, false});
  EXPECT_FALSE(h.should_reannounce(5.0));
}

TEST(HostHandshake, AStopIsKeptWhateverItsTick) {
  HostHandshake h(2.0, 0.5);
  h.announced(7, 0);
  EXPECT_FALSE(h.stop());
  h.on_answer({1, 3, 0, 0, true});
  EXPECT_TRUE(h.stop());
  EXPECT_TRUE(h.stop_settled(0));  // a stop of another tick counts no windows of ours
}

// Regression (lifelong determinism): a stop answering the host's tick may come with windows; the
// final states wait for them, or their queues differ run to run.
TEST(HostHandshake, AStopAnsweringOurTickSettlesOnceItsWindowsAreIn) {
  HostHandshake h(2.0, 0.5);
  h.announced(7, 0);
  h.on_answer({1, 7, 0, 12, true});
  EXPECT_TRUE(h.stop());
  EXPECT_FALSE(h.stop_settled(11));
  EXPECT_TRUE(h.stop_settled(12));
}

}  // namespace
}  // namespace smart::wire
