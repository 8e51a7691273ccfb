// Who may speak for which robot (smart/dds/robot_speakers.hpp): partition names parsed strictly;
// a sim host speaks for any robot, an agent for its own, a stranger for none. Over DDS:
// admission_test.cpp.
#include "smart/dds/robot_speakers.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::dds {
namespace {

using ::testing::HasSubstr;

TEST(RobotPartition, OnlyTheRunsOwnRobotPartitionsNameARobot) {
  const std::string run = "smart.run.r1";
  EXPECT_EQ(robot_of_partition(run, "smart.run.r1.robot.3"), 3u);
  EXPECT_EQ(robot_of_partition(run, "smart.run.r1.robot.0"), 0u);
  for (const char* bad :
       {"smart.run.r1", "smart.run.r1.robot.", "smart.run.r1.robot.03", "smart.run.r1.robot.3x",
        "smart.run.r1.robot.*", "smart.run.r2.robot.3", "smart.run.r1.robot.5.robot.3",
        "smart.run.r1.robot.1234567890", "smart.run.*"}) {
    EXPECT_FALSE(robot_of_partition(run, bad)) << bad;
  }
}

TEST(RobotPartition, ASimHostSpeaksForAnyRobotAnAgentForItsOwnAStrangerForNone) {
  const std::string run = "smart.run.r1";
  EXPECT_EQ(why_not(speaks_for(run, {run}), 7), "");
  const auto agent = speaks_for(run, {"smart.run.r1.robot.3", "smart.run.r1.robot.4"});
  EXPECT_EQ(why_not(agent, 4), "");
  EXPECT_THAT(why_not(agent, 5),
              HasSubstr("robot 5: for another robot from a writer that speaks for robot(s) 3, 4"));
  EXPECT_EQ(speaks_only(speaks_for(run, {run})), "");
  EXPECT_THAT(why_not(speaks_for(run, {"smart.run.*"}), 0), HasSubstr("outside this run"));
  EXPECT_THAT(why_not(speaks_for(run, {run, "smart.run.*"}), 0), HasSubstr("outside this run"));
}

}  // namespace
}  // namespace smart::dds
