// Who owns a run: strengths from start times and the ranking of announced monitors.
#include "smart/wire/ownership.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart.h"

namespace smart::wire {
namespace {

TEST(Ownership, AnEarlierMonitorIsStrongerAndResumeIsStrongestOfAll) {
  const uint64_t t = 1'795'000'000'000;  // ms since 1970, November 2026
  const int32_t first = monitor_strength(t, false), later = monitor_strength(t + 20, false);
  EXPECT_GT(first, later);
  EXPECT_GE(later, smart_msg_MONITOR_STRENGTH_MIN);
  EXPECT_LT(first, smart_msg_MONITOR_STRENGTH_RESUME);
  EXPECT_EQ(monitor_strength(t, true), smart_msg_MONITOR_STRENGTH_RESUME);
  EXPECT_GT(later, smart_msg_HOST_STRENGTH);  // a monitor never loses to a host's writers
}

TEST(Ownership, TheStrongestOtherMonitorOwnsEqualStrengthsGoToTheSmallerId) {
  const MonitorClaim self{5, 1, "b", 2, 1500, false};
  EXPECT_FALSE(owner_over(self, {}).has_value());
  EXPECT_FALSE(owner_over(self, {self, {6, 1, "c", 3, 1400, false}}).has_value());
  const auto owner = owner_over(
      self,
      {{6, 1, "c", 3, 1400, false}, {7, 9, "a", 4, 1600, false}, {3, 1, "d", 5, 1500, false}});
  ASSERT_TRUE(owner.has_value());
  EXPECT_EQ(owner->monitor_id, 7u);
  EXPECT_TRUE(outranks({3, 1, "", 0, 1500, false}, self));  // same strength, smaller id
  EXPECT_EQ(describe(*owner), "monitor on host a (pid 4, run id 9)");
}

// `smart monitor --resume` of another plan ended both runs (issue 25): resume now takes over only
// a run whose monitor stopped; a live resumed monitor still outranks a later fresh one.
TEST(Ownership, AResumingMonitorNeverOutranksALiveMonitorThatIsNotResuming) {
  const MonitorClaim running{5, 1, "a", 2, 1500, false}, resuming{6, 1, "b", 3, 2147483647, true};
  EXPECT_TRUE(outranks(running, resuming));
  EXPECT_FALSE(outranks(resuming, running));
  ASSERT_TRUE(owner_over(resuming, {running}).has_value());
  EXPECT_FALSE(owner_over(running, {resuming}).has_value());
  const MonitorClaim weaker_resume{7, 1, "c", 4, 1400, true};
  EXPECT_TRUE(outranks(resuming, {7, 1, "c", 4, 2147483647, true}));  // equal: smaller id
  EXPECT_FALSE(outranks(weaker_resume, resuming));
}

// One MonitorInfo written once (issue 25) made every run refuse itself.
TEST(ClaimBook, AClaimIsLiveOnlyOnceRepeatedAndUntilItGoesQuiet) {
  ClaimBook book;
  const MonitorClaim c{9, 1, "h", 1, 1600, false};
  book.heard(c, 0.0);
  EXPECT_TRUE(book.live(0.0).empty());
  EXPECT_TRUE(book.pending(1.0));
  EXPECT_FALSE(book.pending(0.1 + kClaimLiveS));  // never repeated: stale, not waited for
  EXPECT_TRUE(book.live(3.0).empty());
  book.heard(c, 3.0);
  book.heard(c, 4.0);
  ASSERT_EQ(book.live(4.0).size(), 1u);
  EXPECT_EQ(book.live(4.0)[0].monitor_id, 9u);
  EXPECT_FALSE(book.pending(4.0));
  EXPECT_TRUE(book.live(4.1 + kClaimLiveS).empty());  // it stopped announcing
  book.heard(c, 10.0);
  book.gone(9);
  EXPECT_TRUE(book.live(10.0).empty());
}

TEST(ClaimBook, AFloodOfMadeUpMonitorsKeepsAtMostTheCapAndEvictsTheQuietest) {
  ClaimBook book;
  const MonitorClaim real{1, 1, "real", 1, 1600, false};
  book.heard(real, 0.0);
  for (uint64_t id = 100; id < 100 + 10 * kMaxClaims; ++id) {
    book.heard({id, 1, "x", 1, 1600, false}, 0.5);
    book.heard(real, 1.0);  // the real monitor keeps announcing
  }
  const auto live = book.live(1.0);
  ASSERT_EQ(live.size(), 1u);
  EXPECT_EQ(live[0].monitor_id, 1u);
}

}  // namespace
}  // namespace smart::wire
