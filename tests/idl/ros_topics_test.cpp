#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/dds/topics.hpp"

namespace smart::dds {
namespace {

using ::testing::HasSubstr;

std::string why(const std::string& ns) {
  try {
    check_ros_namespace(ns);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RosNamespace, AcceptsEmptyAndSlashSeparatedNames) {
  for (const char* ok : {"", "/run_a", "/lab/run_1", "/R2"}) EXPECT_EQ(why(ok), "") << ok;
  EXPECT_EQ(ros_view_topic("/run_a", "/tf"), "/run_a/tf");
  EXPECT_EQ(ros_view_topic("", "/tf"), "/tf");
  EXPECT_EQ(ros_topic(ros_view_topic("/run_a", ros_robot_plan_topic(3))), "rt/run_a/robot_3/plan");
}

TEST(RosNamespace, NamesTheRuleABadOneBreaks) {
  EXPECT_THAT(why("run_a"), HasSubstr("must start with '/'"));
  EXPECT_THAT(why("/run_a/"), HasSubstr("must not end with '/'"));
  EXPECT_THAT(why("/a//b"), HasSubstr("empty name"));
  EXPECT_THAT(why("/run a"), HasSubstr("has ' '"));
  EXPECT_THAT(why("/1run"), HasSubstr("starting with a digit"));
  EXPECT_THAT(why("/"), HasSubstr("must not end with '/'"));
}

}  // namespace
}  // namespace smart::dds
