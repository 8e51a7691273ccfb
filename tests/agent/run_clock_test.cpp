// The time an agent reports: since its run began, not its host's uptime (issue 26).
#include "smart/agent/run_clock.hpp"

#include <gtest/gtest.h>

namespace smart::agent {
namespace {

TEST(RunClock, AJetbotHostsUptimeIsNotTheRunClock) {
  RunClock c;
  EXPECT_DOUBLE_EQ(c.since_run_start(0, 3257.0), 0.0);  // before any window: since the start
  EXPECT_DOUBLE_EQ(c.since_run_start(0, 3259.5), 2.5);
  EXPECT_DOUBLE_EQ(c.since_run_start(42, 3260.0), 0.0);  // its run's first window
  EXPECT_DOUBLE_EQ(c.since_run_start(42, 3275.0), 15.0);
  EXPECT_DOUBLE_EQ(c.since_run_start(43, 3300.0), 0.0);  // the next run starts again
}

}  // namespace
}  // namespace smart::agent
