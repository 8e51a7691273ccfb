// The ROS 2 view of the fleet, read back by plain DDS readers the way rmw_cyclonedds would.
#include "smart/sim/ros_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>

#include "smart/dds/reader.hpp"
#include "support/dds_test_support.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::sim {
namespace {

using namespace std::chrono_literals;

agent::RobotModel ros_view_model() {
  agent::RobotModel m;
  m.name = "test";
  m.radius_m = 0.2;
  m.mass_kg = 10;
  m.wheel_base_m = 0.3;
  return m;
}

double yaw_of(const geometry_msgs_msg_dds__Quaternion_& q) { return 2 * std::atan2(q.z, q.w); }

TEST(RosStamp, SplitsSecondsAndNanoseconds) {
  const auto a = ros_stamp(12.25);
  EXPECT_EQ(a.sec, 12);
  EXPECT_EQ(a.nanosec, 250000000u);
  const auto b = ros_stamp(0.9999999999);  // rounds up into the next second, not 1e9 ns
  EXPECT_EQ(b.sec, 1);
  EXPECT_EQ(b.nanosec, 0u);
}

TEST(YawQuaternion, IsAUnitRotationAboutZ) {
  for (const double yaw : {0.0, 0.3, std::numbers::pi / 2, -2.0, std::numbers::pi}) {
    const auto q = yaw_quaternion(yaw);
    EXPECT_DOUBLE_EQ(q.x, 0.0);
    EXPECT_DOUBLE_EQ(q.y, 0.0);
    EXPECT_NEAR(q.z * q.z + q.w * q.w, 1.0, 1e-12);
    EXPECT_NEAR(std::remainder(yaw_of(q) - yaw, 2 * std::numbers::pi), 0.0, 1e-12);
  }
}

TEST(OccupancyCells, BottomRowFirstBlockedIs100) {
  // Rows top to bottom; cell (col 2, row 0) is blocked: the top row, so the last OccupancyGrid row.
  const auto grid = test::grid_of({"..@", "...", "@.."});
  EXPECT_EQ(occupancy_cells(grid), (std::vector<int8_t>{100, 0, 0, 0, 0, 0, 0, 0, 100}));
}

TEST(RosView, TheMapReachesAViewerThatJoinsLater) {
  const auto grid = test::grid_of({"..@", "...", "@.."});
  dds::Domain domain(test::kRosMap, test::loopback());
  dds::Participant sim_p(domain), ros_p(domain);
  RosView view(sim_p, dds::default_qos_profile(), 0, {});
  view.publish_map(grid, 0.5);
  // rviz2's Map display subscribes reliable + transient local, after the map was written.
  dds::Topic<nav_msgs_msg_dds__OccupancyGrid_> tm(ros_p, "rt/map");
  dds::Reader<nav_msgs_msg_dds__OccupancyGrid_> map(
      ros_p, tm,
      dds::Qos()
          .reliability(dds::Reliability::kReliable)
          .durability(dds::Durability::kTransientLocal)
          .keep_last(1));
  bool got = false;
  for (int attempt = 0; attempt < 250 && !got; ++attempt) {
    map.take_each([&](const nav_msgs_msg_dds__OccupancyGrid_& m) {
      got = true;
      EXPECT_STREQ(m.header.frame_id, "map");
      EXPECT_FLOAT_EQ(m.info.resolution, 0.5f);
      EXPECT_EQ(m.info.width, 3u);
      EXPECT_EQ(m.info.height, 3u);
      EXPECT_DOUBLE_EQ(m.info.origin.position.x, -0.25);
      EXPECT_DOUBLE_EQ(m.info.origin.position.y, -0.25);
      ASSERT_EQ(m.data._length, 9u);
      EXPECT_EQ(m.data._buffer[0], 100);
      EXPECT_EQ(m.data._buffer[4], 0);
      EXPECT_EQ(m.data._buffer[8], 100);
    });
    if (!got) std::this_thread::sleep_for(20ms);
  }
  EXPECT_TRUE(got) << "no transient-local map for a late reader";
}

TEST(RosView, PublishesPosesTfAndChosenRobotsPoseTopics) {
  const auto grid = test::grid_of({".....", ".....", "....."});
  const std::vector<agent::Pose2D> starts = {{1.0, 2.0, 0.0}, {3.0, 1.0, 1.5}, {4.0, 0.0, -3.0}};
  World world(grid, ros_view_model(), {}, starts);
  dds::Domain domain(test::kRosView, test::loopback());
  dds::Participant sim_p(domain), ros_p(domain);
  const auto qos = dds::default_qos_profile();
  EXPECT_THROW(RosView(sim_p, qos, 3, {3}), std::invalid_argument);
  RosView view(sim_p, qos, 3, {1});

  // What a ROS 2 node would create: topic names and type names per the rmw conventions.
  dds::Topic<geometry_msgs_msg_dds__PoseArray_> tp(ros_p, "rt/smart/poses");
  dds::Topic<tf2_msgs_msg_dds__TFMessage_> tt(ros_p, "rt/tf");
  dds::Topic<geometry_msgs_msg_dds__PoseStamped_> tr(ros_p, "rt/robot_1/pose");
  EXPECT_STREQ(geometry_msgs_msg_dds__PoseArray__desc.m_typename,
               "geometry_msgs::msg::dds_::PoseArray_");
  EXPECT_STREQ(tf2_msgs_msg_dds__TFMessage__desc.m_typename, "tf2_msgs::msg::dds_::TFMessage_");
  dds::Reader<geometry_msgs_msg_dds__PoseArray_> poses(ros_p, tp, qos.state.to_dds());
  dds::Reader<tf2_msgs_msg_dds__TFMessage_> tf(ros_p, tt, qos.state.to_dds());
  dds::Reader<geometry_msgs_msg_dds__PoseStamped_> pose1(ros_p, tr, qos.state.to_dds());
  ASSERT_TRUE(poses.wait_for_writers(1, 5s));
  ASSERT_TRUE(tf.wait_for_writers(1, 5s));
  ASSERT_TRUE(pose1.wait_for_writers(1, 5s));

  for (int k = 0; k < 3; ++k) world.step();  // sim time 0.3 s
  bool got_poses = false, got_tf = false, got_pose1 = false;
  for (int attempt = 0; attempt < 100 && !(got_poses && got_tf && got_pose1); ++attempt) {
    view.publish(world);
    std::this_thread::sleep_for(20ms);
    poses.take_each([&](const geometry_msgs_msg_dds__PoseArray_& m) {
      got_poses = true;
      EXPECT_STREQ(m.header.frame_id, "map");
      EXPECT_EQ(m.header.stamp.sec, 0);
      EXPECT_NEAR(m.header.stamp.nanosec, 300000000u, 1);
      ASSERT_EQ(m.poses._length, 3u);
      for (uint32_t i = 0; i < 3; ++i) {
        EXPECT_DOUBLE_EQ(m.poses._buffer[i].position.x, starts[i].x_m);
        EXPECT_DOUBLE_EQ(m.poses._buffer[i].position.y, starts[i].y_m);
        EXPECT_NEAR(yaw_of(m.poses._buffer[i].orientation), starts[i].yaw_rad, 1e-12);
      }
    });
    tf.take_each([&](const tf2_msgs_msg_dds__TFMessage_& m) {
      got_tf = true;
      ASSERT_EQ(m.transforms._length, 3u);
      for (uint32_t i = 0; i < 3; ++i) {
        const auto& t = m.transforms._buffer[i];
        EXPECT_STREQ(t.header.frame_id, "map");
        EXPECT_EQ(std::string(t.child_frame_id), "robot_" + std::to_string(i));
        EXPECT_DOUBLE_EQ(t.transform.translation.x, starts[i].x_m);
        EXPECT_DOUBLE_EQ(t.transform.translation.y, starts[i].y_m);
        EXPECT_NEAR(yaw_of(t.transform.rotation), starts[i].yaw_rad, 1e-12);
      }
    });
    pose1.take_each([&](const geometry_msgs_msg_dds__PoseStamped_& m) {
      got_pose1 = true;
      EXPECT_STREQ(m.header.frame_id, "map");
      EXPECT_DOUBLE_EQ(m.pose.position.x, 3.0);
      EXPECT_DOUBLE_EQ(m.pose.position.y, 1.0);
    });
  }
  EXPECT_TRUE(got_poses);
  EXPECT_TRUE(got_tf);
  EXPECT_TRUE(got_pose1);
}

TEST(RosView, TwoRunsUnderTheirNamespacesPublishOnTheirOwnTopics) {
  const auto grid = test::grid_of({".....", ".....", "....."});
  World a(grid, ros_view_model(), {}, {{1.0, 2.0, 0.0}, {3.0, 1.0, 0.0}});
  World b(grid, ros_view_model(), {}, {{4.0, 0.0, 0.0}});
  dds::Domain domain(test::kRosViewNamespaces, test::loopback());
  dds::Participant sim_p(domain), ros_p(domain);
  const auto qos = dds::default_qos_profile();
  EXPECT_THROW(RosView(sim_p, qos, 1, {}, "run_a"), std::invalid_argument);
  RosView view_a(sim_p, qos, 2, {}, "/run_a");
  RosView view_b(sim_p, qos, 1, {}, "/run_b");
  dds::Topic<geometry_msgs_msg_dds__PoseArray_> ta(ros_p, "rt/run_a/smart/poses");
  dds::Topic<geometry_msgs_msg_dds__PoseArray_> tb(ros_p, "rt/run_b/smart/poses");
  dds::Reader<geometry_msgs_msg_dds__PoseArray_> ra(ros_p, ta, qos.state.to_dds());
  dds::Reader<geometry_msgs_msg_dds__PoseArray_> rb(ros_p, tb, qos.state.to_dds());
  ASSERT_TRUE(ra.wait_for_writers(1, 5s));
  ASSERT_TRUE(rb.wait_for_writers(1, 5s));
  std::optional<uint32_t> na, nb;
  for (int attempt = 0; attempt < 100 && !(na && nb); ++attempt) {
    view_a.publish(a);
    view_b.publish(b);
    std::this_thread::sleep_for(20ms);
    ra.take_each([&](const geometry_msgs_msg_dds__PoseArray_& m) { na = m.poses._length; });
    rb.take_each([&](const geometry_msgs_msg_dds__PoseArray_& m) { nb = m.poses._length; });
  }
  EXPECT_EQ(na, 2u);
  EXPECT_EQ(nb, 1u);
}

}  // namespace
}  // namespace smart::sim
