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

}  // namespace
}  // namespace smart::wire
