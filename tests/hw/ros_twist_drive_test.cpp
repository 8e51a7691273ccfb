#include "smart/hw/ros_twist_drive.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <thread>

#include "smart/dds/reader.hpp"
#include "support/dds_test_support.hpp"

namespace smart::hw {
namespace {

// What a ROS 2 base hears on cmd_vel: the latest Twist within 2 s.
std::optional<geometry_msgs_msg_dds__Twist_> next_twist(
    dds::Reader<geometry_msgs_msg_dds__Twist_>& r) {
  std::optional<geometry_msgs_msg_dds__Twist_> last;
  for (int i = 0; i < 200 && !last; ++i) {
    r.take_each([&](const geometry_msgs_msg_dds__Twist_& t) { last = t; });
    if (!last) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return last;
}

TEST(RosTwistDrive, WheelSpeedsBecomeATwistAndShutdownWritesAStop) {
  dds::Domain domain(test::kRosTwist, test::loopback());
  dds::Participant robot(domain), base(domain);
  dds::Topic<geometry_msgs_msg_dds__Twist_> topic(base, "rt/robot_2/cmd_vel");
  dds::Reader<geometry_msgs_msg_dds__Twist_> cmd_vel(base, topic, dds::ros_command_qos().to_dds());
  {
    RosTwistDrive drive(robot, dds::ros_namespace("/robot_{id}", 2), 0.16);
    EXPECT_EQ(drive.topic(), "/robot_2/cmd_vel");
    // Reliable and matched before the first command: wait for the reader.
    for (int i = 0; i < 200; ++i) {
      drive.set_wheel_speeds({0.1, 0.26});
      if (const auto t = next_twist(cmd_vel)) {
        EXPECT_DOUBLE_EQ(t->linear.x, 0.18);    // (0.1 + 0.26) / 2
        EXPECT_NEAR(t->angular.z, 1.0, 1e-12);  // (0.26 - 0.1) / 0.16
        EXPECT_EQ(t->linear.y, 0.0);
        break;
      }
    }
    EXPECT_GE(drive.commands(), 1u);
    EXPECT_TRUE(drive.deactivate().ok());
    const auto stop = next_twist(cmd_vel);
    ASSERT_TRUE(stop.has_value());
    EXPECT_EQ(stop->linear.x, 0.0);
    EXPECT_EQ(stop->angular.z, 0.0);
    drive.set_wheel_speeds({0.2, 0.2});
    ASSERT_TRUE(next_twist(cmd_vel).has_value());
  }  // destroyed while moving: the last word is a stop
  const auto last = next_twist(cmd_vel);
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->linear.x, 0.0);
}

}  // namespace
}  // namespace smart::hw
