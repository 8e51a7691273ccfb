#include "smart/hw/ros_pose.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "smart/dds/writer.hpp"
#include "support/dds_test_support.hpp"

namespace smart::hw {
namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

TEST(RosPoseSource, ReadsPoseStampedLikeAVrpnMocapPublisher) {
  dds::Domain domain(test::kRosPose, test::loopback());
  dds::Participant pub(domain), sub(domain);
  ViconTransform identity;
  identity.scale = 1.0;  // ROS poses are in metres
  RosPoseSource src(sub, "/vrpn_mocap/jetbot1/pose", identity, 0.3, now_s);
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

TEST(RosTopics, RmwNaming) {
  EXPECT_EQ(dds::ros_topic("/vrpn_mocap/a/pose"), "rt/vrpn_mocap/a/pose");
  EXPECT_EQ(dds::ros_topic("tf"), "rt/tf");
  EXPECT_STREQ(geometry_msgs_msg_dds__PoseStamped__desc.m_typename,
               "geometry_msgs::msg::dds_::PoseStamped_");
}

}  // namespace
}  // namespace smart::hw
