#include "smart/commissioning/verdicts.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace smart::commissioning {
namespace {

std::vector<agent::PoseSample> stream(double hz, double seconds, double gap_at = -1,
                                      double gap_s = 0) {
  std::vector<agent::PoseSample> out;
  for (double t = 0; t < seconds; t += 1.0 / hz) {
    if (gap_at >= 0 && t > gap_at && t < gap_at + gap_s) continue;
    out.push_back({{0, 0, 0}, 0, 0, t, true});
  }
  return out;
}

TEST(Verdicts, PoseStreamRateAndGapsAreJudged) {
  const auto ok = pose_stream_check("1", stream(100, 2), 2, 20, 0.1);
  EXPECT_EQ(ok.level, Level::kOk) << ok.measured;
  EXPECT_NE(ok.measured.find("100 Hz"), std::string::npos) << ok.measured;
  EXPECT_EQ(pose_stream_check("1", stream(10, 2), 2, 20, 0.5).level, Level::kWarn);
  const auto gap = pose_stream_check("1", stream(100, 2, 1.0, 0.3), 2, 20, 0.1);
  EXPECT_EQ(gap.level, Level::kWarn);
  EXPECT_NE(gap.fix.find("--pose-max-age-s"), std::string::npos);
  const auto none = pose_stream_check("1", {}, 2, 20, 0.1);
  EXPECT_EQ(none.level, Level::kFail);
  EXPECT_NE(none.fix.find("--vicon-object"), std::string::npos);
}

TEST(Verdicts, AHostsClockFarOffIsAWarning) {
  const auto ok = clock_check("a1b2", {0, 1, 2}, 0.002, 40, 0.02);
  EXPECT_EQ(ok.level, Level::kOk);
  EXPECT_NE(ok.measured.find("robots 0,1,2;"), std::string::npos) << ok.measured;
  const auto monitor = clock_check("c3d4", {}, 0.001, 5, 0.02);
  EXPECT_NE(monitor.measured.find("the monitor;"), std::string::npos) << monitor.measured;
  const auto off = clock_check("a1b2", {3}, -0.25, 40, 0.02);
  EXPECT_EQ(off.level, Level::kWarn);
  EXPECT_NE(off.fix.find("chrony"), std::string::npos);
}

TEST(Verdicts, AWheelAloneMustTurnTheRobotAwayFromIt) {
  const agent::Pose2D start{1, 1, M_PI / 2};  // facing +y
  // Left wheel forward: clockwise, ahead along +y.
  EXPECT_EQ(wheel_check("0", Wheel::kLeft, start, {1.02, 1.04, M_PI / 2 - 0.8}).level, Level::kOk);
  const auto backwards = wheel_check("0", Wheel::kLeft, start, {1.02, 0.96, M_PI / 2 + 0.8});
  EXPECT_EQ(backwards.level, Level::kFail);
  EXPECT_NE(backwards.fix.find("hardware.left.sign"), std::string::npos);
  EXPECT_EQ(wheel_check("0", Wheel::kRight, start, {0.98, 1.04, M_PI / 2 + 0.8}).level, Level::kOk);
  const auto still = wheel_check("0", Wheel::kRight, start, start);
  EXPECT_EQ(still.level, Level::kFail);
  EXPECT_NE(still.fix.find("did not move"), std::string::npos);
  EXPECT_NE(still.fix.find("hardware.right.beta"), std::string::npos) << "a dead band is named";
}

TEST(Verdicts, ASlowResponseToTheFirstCommandIsAWarningAndNoneAFailure) {
  const auto ok = response_check("2", 0.12);
  EXPECT_EQ(ok.level, Level::kOk);
  EXPECT_NE(ok.measured.find("120 ms"), std::string::npos) << ok.measured;
  const auto slow = response_check("2", 0.6);
  EXPECT_EQ(slow.level, Level::kWarn);
  EXPECT_NE(slow.fix.find("overshoot"), std::string::npos);
  EXPECT_EQ(response_check("2", std::nullopt).level, Level::kFail);
}

TEST(Verdicts, SamplesThatFailTheWireChecksAreOneWarningNamingTopicCountAndReason) {
  wire::Rejections rejected;
  EXPECT_FALSE(rejected_row(rejected).has_value());
  rejected.count("monitor", "host name has a non-printable byte (27 at 2)");
  rejected.count("state", "robot_id 4000000000 ...");
  rejected.count("state", "robot_id 4000000000 ...");
  const auto row = rejected_row(rejected);
  ASSERT_TRUE(row.has_value());
  EXPECT_EQ(row->level, Level::kWarn);
  EXPECT_EQ(row->check, "wire");
  EXPECT_NE(row->measured.find("3 sample(s)"), std::string::npos) << row->measured;
  EXPECT_NE(row->measured.find("1 monitor: host name has a non-printable byte"), std::string::npos)
      << row->measured;
  EXPECT_NE(row->measured.find("2 state: robot_id"), std::string::npos) << row->measured;
  EXPECT_NE(row->fix.find("--security"), std::string::npos);
}

}  // namespace
}  // namespace smart::commissioning
