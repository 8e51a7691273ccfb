#include "smart/monitor/action_durations.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace smart::monitor {
namespace {

using grid::ActionType;

TEST(ActionDurations, LearnsAMeanPerKindAndIgnoresImpossibleSamples) {
  ActionDurations d(1.0);
  d.observe(ActionType::kMove, 2.0);
  d.observe(ActionType::kMove, 4.0);
  d.observe(ActionType::kMove, -1.0);  // out of order: ignored
  EXPECT_DOUBLE_EQ(d.mean_s(ActionType::kMove), 3.0);
  EXPECT_DOUBLE_EQ(d.mean_s(ActionType::kRotate), 1.0);  // nothing seen: the initial guess
  for (int i = 0; i < 2000; ++i) d.observe(ActionType::kRotate, 0.5);
  EXPECT_NEAR(d.mean_s(ActionType::kRotate), 0.5, 1e-9);
}

// Forgets slowly: after many samples of one duration the mean follows a change within a few
// hundred samples instead of averaging over the whole run.
TEST(ActionDurations, FollowsAChangeInDurations) {
  ActionDurations d(1.0);
  for (int i = 0; i < 10000; ++i) d.observe(ActionType::kMove, 1.0);
  for (int i = 0; i < 1000; ++i) d.observe(ActionType::kMove, 3.0);
  EXPECT_GT(d.mean_s(ActionType::kMove), 2.9);
}

TEST(ActionDurations, FinishAddsMeansAndALateActionTakesOneMoreMean) {
  ActionDurations d(1.0);
  d.observe(ActionType::kMove, 2.0);  // moves 2 s, rotations 1 s
  const ActionType queue[] = {ActionType::kMove, ActionType::kRotate, ActionType::kMove};
  EXPECT_DOUBLE_EQ(d.finish_s(10.0, 9.5, queue), 9.5 + 2 + 1 + 2);   // on time
  EXPECT_DOUBLE_EQ(d.finish_s(10.0, 5.0, queue), 10.0 + 2 + 1 + 2);  // late by 3 s
  EXPECT_DOUBLE_EQ(d.finish_s(10.0, -1, queue), 10.0 + 2 + 1 + 2);   // not started yet
  EXPECT_DOUBLE_EQ(d.finish_s(10.0, 9.0, {}), 10.0);
}

// The queue both switchable-opt executions compare: a free location, i expected at 5 s for 2 s,
// j at 2 s for 2 s. i first: j waits 5 s (enters at 7); j first: i enters at 5, nobody waits.
// A robot after them at 3 s waits for the later of the two to leave (9 s or 7 s).
TEST(ActionDurations, QueueSavingComparesBothOrdersWaits) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(queue_saving({0, {5, 2}, {2, 2}, kNone}), 5);
  EXPECT_DOUBLE_EQ(queue_saving({0, {2, 2}, {5, 2}, kNone}), -5);
  EXPECT_DOUBLE_EQ(queue_saving({0, {5, 2}, {2, 2}, 3}), 5 + (6 - 4));
  // The location frees only at 6 s: either order waits 7 s in all (1 + 6 or 4 + 3), no saving.
  EXPECT_DOUBLE_EQ(queue_saving({6, {5, 2}, {2, 2}, kNone}), 0);
}

}  // namespace
}  // namespace smart::monitor
