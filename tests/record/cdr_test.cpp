#include "smart/record/cdr.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "smart/dds/sequence.hpp"
#include "smart/dds/topics.hpp"

namespace smart::record {
namespace {

template <class T>
T at(const std::string& b, std::size_t offset) {
  T v;
  std::memcpy(&v, b.data() + offset, sizeof v);
  return v;
}

TEST(CdrBytes, PoseArrayIsTheEncapsulationHeaderThenXcdr1LittleEndian) {
  char frame[] = "map";
  std::vector<geometry_msgs_msg_dds__Pose_> poses{{{1.5, -2.0, 0.0}, {0, 0, 0.5, 0.75}}};
  geometry_msgs_msg_dds__PoseArray_ m{};
  m.header = {{3, 500}, frame};
  dds::borrow(m.poses, poses);
  const std::string b = cdr_bytes(m);
  ASSERT_EQ(b.size(), 4u + 80u);
  EXPECT_EQ(b.substr(0, 4), std::string("\x00\x01\x00\x00", 4));
  // After the header, offsets count from 0: stamp (8), "map\0" with its length (8), the
  // sequence length (4), padding to 8, then 7 doubles.
  EXPECT_EQ(at<int32_t>(b, 4), 3);
  EXPECT_EQ(at<uint32_t>(b, 8), 500u);
  EXPECT_EQ(at<uint32_t>(b, 12), 4u);
  EXPECT_EQ(b.substr(16, 4), std::string("map\0", 4));
  EXPECT_EQ(at<uint32_t>(b, 20), 1u);
  EXPECT_EQ(at<double>(b, 28), 1.5);
  EXPECT_EQ(at<double>(b, 36), -2.0);
  EXPECT_EQ(at<double>(b, 68), 0.5);
  EXPECT_EQ(at<double>(b, 76), 0.75);
}

TEST(CdrBytes, RobotStateCarriesEveryField) {
  smart_msg_RobotState s{};
  s.robot_id = 7;
  s.run_id = 0x0102030405060708ULL;
  s.sim_time_s = 2.5;
  s.pose = {1, 2, 3};
  s.queue_length = 9;
  const std::string b = cdr_bytes(s);
  EXPECT_EQ(at<uint32_t>(b, 4), 7u);
  EXPECT_EQ(at<uint64_t>(b, 12), 0x0102030405060708ULL);  // aligned to 8
  EXPECT_EQ(at<double>(b, 20), 2.5);
  EXPECT_EQ(at<uint32_t>(b, b.size() - 4), 9u);
}

TEST(RosTypeName, IsTheRmwNameOfTheIdlTypeBackInRos2Form) {
  EXPECT_EQ(ros_type_name<geometry_msgs_msg_dds__PoseArray_>(), "geometry_msgs/msg/PoseArray");
  EXPECT_EQ(ros_type_name<visualization_msgs_msg_dds__MarkerArray_>(),
            "visualization_msgs/msg/MarkerArray");
  EXPECT_EQ(ros_type_name<smart_msg_RobotState>(), "smart/msg/RobotState");
}

}  // namespace
}  // namespace smart::record
