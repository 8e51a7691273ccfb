#include "smart/hw/ros_pose.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "smart/dds/writer.hpp"
#include "support/dds_test_support.hpp"

namespace smart::hw {
namespace {

double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

TEST(RosPoseSource, ReadsPoseStampedLikeAVrpnMocapPublisher) {
  dds::Domain domain(test::kRosPose, test::loopback());
  dds::Participant pub(domain), sub(domain);
  const geometry::FrameTransform identity;  // ROS poses are in metres
  RosPoseSource src(sub, "/vrpn_mocap/jetbot1/pose", identity, 0.3, steady_now_s);
  dds::Topic<geometry_msgs_msg_dds__PoseStamped_> topic(pub, "rt/vrpn_mocap/jetbot1/pose");
  dds::TopicQos q;
  q.reliability = dds::Reliability::kBestEffort;  // vrpn_mocap: sensor data QoS
  dds::Writer<geometry_msgs_msg_dds__PoseStamped_> w(pub, topic, q.to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, std::chrono::seconds(5)));
  geometry_msgs_msg_dds__PoseStamped_ m{};
  char frame[] = "world";
  m.header.frame_id = frame;
  m.pose.position = {1.5, -0.5, 0.0};
  const double yaw = 2.0;
  m.pose.orientation = {0, 0, std::sin(yaw / 2), std::cos(yaw / 2)};
  agent::PoseSample p;
  for (int i = 0; i < 200 && !p.valid; ++i) {
    w.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    p = src.read();
  }
  ASSERT_TRUE(p.valid);
  EXPECT_DOUBLE_EQ(p.pose.x_m, 1.5);
  EXPECT_DOUBLE_EQ(p.pose.y_m, -0.5);
  EXPECT_NEAR(p.pose.yaw_rad, yaw, 1e-12);
  EXPECT_GE(src.samples(), 1u);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  EXPECT_FALSE(src.read().valid);
}

// A ROS 2 base's odometry (nav_msgs/Odometry), its frame starting where the robot stood: the
// transform file's similarity puts it on the grid, and a silent base goes stale.
TEST(RosPoseSource, ReadsOdometryThroughATransformAndGoesStale) {
  dds::Domain domain(test::kRosOdom, test::loopback());
  dds::Participant pub(domain), sub(domain);
  const geometry::FrameTransform start{1.0, M_PI / 2, {0.6, 0.3}};  // robot started at (0.6, 0.3)
  RosPoseSource src(sub, dds::ros_odom_topic(dds::ros_namespace("/robot_{id}", 4)), start, 0.3,
                    steady_now_s, RosPoseSource::Message::kOdometry);
  dds::Topic<nav_msgs_msg_dds__Odometry_> topic(pub, "rt/robot_4/odom");
  dds::Writer<nav_msgs_msg_dds__Odometry_> w(pub, topic, dds::ros_sensor_qos().to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, std::chrono::seconds(5)));
  nav_msgs_msg_dds__Odometry_ m{};
  char frame[] = "odom", child[] = "base_footprint";
  m.header.frame_id = frame;
  m.child_frame_id = child;
  m.pose.pose.position = {0.3, 0.0, 0.0};  // 0.3 m ahead of the start
  m.pose.pose.orientation = {0, 0, 0, 1};
  agent::PoseSample p;
  for (int i = 0; i < 200 && !p.valid; ++i) {
    w.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    p = src.read();
  }
  ASSERT_TRUE(p.valid);
  EXPECT_NEAR(p.pose.x_m, 0.6, 1e-12);  // facing +y in the world: ahead is up
  EXPECT_NEAR(p.pose.y_m, 0.6, 1e-12);
  EXPECT_NEAR(p.pose.yaw_rad, M_PI / 2, 1e-12);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  EXPECT_FALSE(src.read().valid);
  m.pose.pose.orientation = {0, 0, 0, 0};  // an unset quaternion has no heading
  const auto before = src.samples();
  for (int i = 0; i < 200 && src.samples() == before; ++i) {
    w.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GT(src.samples(), before);  // received, and refused
  EXPECT_FALSE(src.read().valid);
}

TEST(RosTopics, RmwNaming) {
  EXPECT_EQ(dds::ros_namespace("/robot_{id}", 7), "/robot_7");
  EXPECT_EQ(dds::ros_namespace("tb3_{id}/", 0), "/tb3_0");
  EXPECT_EQ(dds::ros_namespace("", 3), "");
  EXPECT_EQ(dds::ros_cmd_vel_topic("/robot_7"), "/robot_7/cmd_vel");
  EXPECT_EQ(dds::ros_odom_topic(""), "/odom");
  EXPECT_EQ(dds::ros_topic("/vrpn_mocap/a/pose"), "rt/vrpn_mocap/a/pose");
  EXPECT_EQ(dds::ros_topic("tf"), "rt/tf");
  EXPECT_STREQ(geometry_msgs_msg_dds__PoseStamped__desc.m_typename,
               "geometry_msgs::msg::dds_::PoseStamped_");
}

}  // namespace
}  // namespace smart::hw
