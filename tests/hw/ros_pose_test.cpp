#include "smart/hw/ros_pose.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <thread>

#include "smart/dds/writer.hpp"
#include "support/dds_test_support.hpp"

namespace smart::hw {
namespace {

// The sources' clock, told the time by the test (read from DDS's listener thread too): a pose
// goes stale when the test moves the clock past its age limit, not after a sleep long enough on
// an idle machine.
struct TestClock {
  std::atomic<double> now_s{100.0};
  std::function<double()> fn() {
    return [this] { return now_s.load(); };
  }
};

// Writes `m` one sample at a time, each waited for (counted by the source) before the next,
// until the source reads a valid pose: none is left in flight to refresh it afterwards. A sample
// lost on the way (best effort) is written again after 2 s.
template <class Writer, class Message>
agent::PoseSample write_until_valid(Writer& w, const Message& m, RosPoseSource& src) {
  agent::PoseSample p;
  for (int i = 0; i < 200 && !p.valid; ++i) {
    const auto before = src.samples();
    w.write(m);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (src.samples() == before && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    p = src.read();
  }
  return p;
}

TEST(RosPoseSource, ReadsPoseStampedLikeAVrpnMocapPublisher) {
  dds::Domain domain(test::kRosPose, test::loopback());
  dds::Participant pub(domain), sub(domain);
  const geometry::FrameTransform identity;  // ROS poses are in metres
  TestClock clock;
  RosPoseSource src(sub, "/vrpn_mocap/jetbot1/pose", identity, 0.3, clock.fn());
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
  const agent::PoseSample p = write_until_valid(w, m, src);
  ASSERT_TRUE(p.valid);
  EXPECT_DOUBLE_EQ(p.pose.x_m, 1.5);
  EXPECT_DOUBLE_EQ(p.pose.y_m, -0.5);
  EXPECT_NEAR(p.pose.yaw_rad, yaw, 1e-12);
  EXPECT_GE(src.samples(), 1u);
  clock.now_s = clock.now_s + 0.29;
  EXPECT_TRUE(src.read().valid) << "within its age limit of 0.3 s";
  clock.now_s = clock.now_s + 0.02;
  EXPECT_FALSE(src.read().valid) << "stale past 0.3 s";
}

// A ROS 2 base's odometry (nav_msgs/Odometry), its frame starting where the robot stood: the
// transform file's similarity puts it on the grid, and a silent base goes stale.
TEST(RosPoseSource, ReadsOdometryThroughATransformAndGoesStale) {
  dds::Domain domain(test::kRosOdom, test::loopback());
  dds::Participant pub(domain), sub(domain);
  const geometry::FrameTransform start{1.0, M_PI / 2, {0.6, 0.3}};  // robot started at (0.6, 0.3)
  TestClock clock;
  RosPoseSource src(sub, dds::ros_odom_topic(dds::ros_namespace("/robot_{id}", 4)), start, 0.3,
                    clock.fn(), RosPoseSource::Message::kOdometry);
  dds::Topic<nav_msgs_msg_dds__Odometry_> topic(pub, "rt/robot_4/odom");
  dds::Writer<nav_msgs_msg_dds__Odometry_> w(pub, topic, dds::ros_sensor_qos().to_dds());
  ASSERT_TRUE(w.wait_for_readers(1, std::chrono::seconds(5)));
  nav_msgs_msg_dds__Odometry_ m{};
  char frame[] = "odom", child[] = "base_footprint";
  m.header.frame_id = frame;
  m.child_frame_id = child;
  m.pose.pose.position = {0.3, 0.0, 0.0};  // 0.3 m ahead of the start
  m.pose.pose.orientation = {0, 0, 0, 1};
  const agent::PoseSample p = write_until_valid(w, m, src);
  ASSERT_TRUE(p.valid);
  EXPECT_NEAR(p.pose.x_m, 0.6, 1e-12);  // facing +y in the world: ahead is up
  EXPECT_NEAR(p.pose.y_m, 0.6, 1e-12);
  EXPECT_NEAR(p.pose.yaw_rad, M_PI / 2, 1e-12);
  clock.now_s = clock.now_s + 0.29;
  EXPECT_TRUE(src.read().valid) << "within its age limit of 0.3 s";
  clock.now_s = clock.now_s + 0.02;
  EXPECT_FALSE(src.read().valid) << "stale past 0.3 s";
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
