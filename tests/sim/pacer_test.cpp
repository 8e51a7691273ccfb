#include "smart/sim/pacer.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace smart::sim {
namespace {

TEST(Pacer, UnpacedNeverWaits) {
  Pacer p(0, 0.1);
  EXPECT_FALSE(p.paced());
  p.started(5.0);
  EXPECT_EQ(p.wait_s(5.0), 0);
}

TEST(Pacer, TenTimesRealTimeStartsAPeriodEveryTenthOfItsLength) {
  Pacer p(10, 0.1);  // 0.1 sim s per period: one every 0.01 wall s
  ASSERT_TRUE(p.paced());
  EXPECT_EQ(p.wait_s(100.0), 0);  // the first period starts at once
  p.started(100.0);
  EXPECT_NEAR(p.wait_s(100.004), 0.006, 1e-12);
  EXPECT_EQ(p.wait_s(100.010), 0);
}

TEST(Pacer, WakingUpLateDoesNotDriftTheSchedule) {
  Pacer p(1, 0.1);
  p.started(0.0);
  p.started(0.103);  // 3 ms late: the next is still due at 0.2, not 0.203
  EXPECT_NEAR(p.wait_s(0.15), 0.05, 1e-12);
  p.started(0.2);
  EXPECT_NEAR(p.wait_s(0.25), 0.05, 1e-12);
}

TEST(Pacer, PeriodsThatStartedABitLateAreCaughtUpOn) {
  Pacer p(100, 0.1);  // one period every 1 ms
  p.started(0.0);
  p.started(0.0025);  // 1.5 ms late (a slow round trip): the next, due at 0.002, may start now
  EXPECT_EQ(p.wait_s(0.0026), 0);
  p.started(0.0026);
  EXPECT_NEAR(p.wait_s(0.0027), 0.0003, 1e-12);  // back on the schedule: due at 0.003
}

TEST(Pacer, ASlowStretchRestartsTheScheduleInsteadOfCatchingUpInABurst) {
  Pacer p(1, 0.1);
  p.started(0.0);
  p.started(0.55);                           // 0.45 s late (the sim was slower than real time)
  EXPECT_NEAR(p.wait_s(0.56), 0.09, 1e-12);  // due at 0.65, not at once
}

TEST(Pacer, RefusesANegativeFactorOrAnEmptyPeriod) {
  EXPECT_THROW(Pacer(-1, 0.1), std::invalid_argument);
  EXPECT_THROW(Pacer(1, 0), std::invalid_argument);
}

}  // namespace
}  // namespace smart::sim
