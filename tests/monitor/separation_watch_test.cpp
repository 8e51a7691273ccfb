#include "smart/monitor/separation_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace smart::monitor {
namespace {

constexpr double kRadius = 0.09;  // a JetBot

TEST(SeparationWatch, NothingUntilTwoRobotsAreCompared) {
  SeparationWatch w(3, kRadius);
  w.on_pose(0, 0, 0, 1.0);
  EXPECT_FALSE(w.min_gap_m());
  w.on_pose(1, 5, 0, 1.0);  // far beyond 4·radius: not compared
  EXPECT_FALSE(w.min_gap_m());
  EXPECT_EQ(w.contacts(), 0u);
}

TEST(SeparationWatch, SmallestSurfaceGapOfRobotsReportedAtAboutTheSameTime) {
  SeparationWatch w(2, kRadius);
  w.on_pose(0, 0, 0, 1.0);
  w.on_pose(1, 0.30, 0, 1.02);
  EXPECT_NEAR(*w.min_gap_m(), 0.12, 1e-12);
  w.on_pose(1, 0, 0.25, 1.05);
  EXPECT_NEAR(*w.min_gap_m(), 0.07, 1e-12);
  w.on_pose(1, 0.33, 0, 1.08);  // farther again: the minimum stays
  EXPECT_NEAR(*w.min_gap_m(), 0.07, 1e-12);
  EXPECT_EQ(w.contacts(), 0u);
}

TEST(SeparationWatch, PosesTooFarApartInTimeAreNotCompared) {
  SeparationWatch w(2, kRadius, 0.1);
  w.on_pose(0, 0, 0, 1.0);
  w.on_pose(1, 0.1, 0, 1.5);  // where robot 0 was half a second ago says nothing
  EXPECT_FALSE(w.min_gap_m());
  EXPECT_EQ(w.contacts(), 0u);
}

TEST(SeparationWatch, AContactCountsOnceUntilThePairSeparates) {
  SeparationWatch w(3, kRadius);
  w.on_pose(2, 0.5, 0.5, 0.0);
  w.on_pose(0, 0, 0, 1.0);
  w.on_pose(1, 0.15, 0, 1.0);  // 0.15 m apart: 3 cm overlap
  w.on_pose(1, 0.16, 0, 1.05);
  w.on_pose(0, 0.01, 0, 1.05);
  EXPECT_EQ(w.contacts(), 1u);
  ASSERT_TRUE(w.first_contact());
  EXPECT_EQ(w.first_contact()->a, 0u);
  EXPECT_EQ(w.first_contact()->b, 1u);
  EXPECT_DOUBLE_EQ(w.first_contact()->t_s, 1.0);
  EXPECT_NEAR(w.first_contact()->gap_m, -0.03, 1e-12);
  w.on_pose(1, 0.40, 0, 1.1);   // apart
  w.on_pose(1, 0.10, 0, 1.12);  // and touching again
  EXPECT_EQ(w.contacts(), 2u);
  EXPECT_NEAR(*w.min_gap_m(), -0.09, 1e-12);
}

// Regression: a pair that touched and was next seen far apart (two buckets away, so never
// compared) stayed "touching", and its next contact was not counted.
TEST(SeparationWatch, APairThatJumpedApartCountsItsNextContact) {
  SeparationWatch w(2, kRadius);
  w.on_pose(0, 0, 0, 1.0);
  w.on_pose(1, 0.1, 0, 1.0);
  EXPECT_EQ(w.contacts(), 1u);
  w.on_pose(1, 2.0, 0, 1.05);  // a gap in its samples: next seen far away
  w.on_pose(1, 0.1, 0, 2.0);
  w.on_pose(0, 0, 0, 2.0);
  EXPECT_EQ(w.contacts(), 2u);
}

TEST(SeparationWatch, NeighboursAcrossBucketBordersAreCompared) {
  SeparationWatch w(2, kRadius);  // buckets of 0.36 m
  w.on_pose(0, 0.359, -0.001, 2.0);
  w.on_pose(1, 0.361, 0.001, 2.0);
  EXPECT_NEAR(*w.min_gap_m(), std::hypot(0.002, 0.002) - 0.18, 1e-12);
  EXPECT_EQ(w.contacts(), 1u);
}

TEST(SeparationWatch, HostilePosesAreIgnored) {
  SeparationWatch w(2, kRadius);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  w.on_pose(7, 0, 0, 1.0);  // no such robot
  w.on_pose(0, nan, 0, 1.0);
  w.on_pose(0, 0, inf, 1.0);
  w.on_pose(0, 0, 0, nan);
  w.on_pose(0, 1e300, -1e300, 1.0);  // far off but finite: a bucket at the clamp
  w.on_pose(1, 1e300, -1e300, 1.0);
  EXPECT_EQ(w.contacts(), 1u);
  w.on_pose(0, 0, 0, 1.0);
  w.on_pose(1, 0.5, 0, 1.0);
  EXPECT_EQ(w.contacts(), 1u);
}

}  // namespace
}  // namespace smart::monitor
