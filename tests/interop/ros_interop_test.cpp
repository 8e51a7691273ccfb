// ROS 2 interop across DDS vendors: `smart run` publishes rt/smart/poses with Cyclone DDS; a
// Fast DDS program (fastdds_pose_listener.cpp, the stand-in for a ROS 2 node) discovers it on
// loopback and decodes geometry_msgs/PoseArray. Real processes, own domain. The run is paced to
// 50x real time (about 4 s), as for someone watching in rviz2: unpaced it ends in about a
// second, sometimes before the Fast DDS node has discovered it.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "smart/dds/topics.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

TEST(RosInterop, FastDdsNodeReadsTheFleetPosesWrittenByCyclone) {
  const auto b = benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  const auto out = temp_file("fastdds_listener.out");
  common::ChildProcess listener({FASTDDS_POSE_LISTENER, std::to_string(kFastDdsInterop), "4", "60"},
                                out);
  const auto run = run_smart(
      {"run", "--map", (b / "maps/random-32-32-20.map").string(), "--scen",
       (b / "scens/random-32-32-20-random-1.scen").string(), "--plan",
       (b / "smart-examples/example_paths_xy.txt").string(), "--axis", "xy", "--agents", "50",
       "--domain", std::to_string(kFastDdsInterop), "--no-progress", "--real-time-factor", "50"},
      120s, "interop_run");
  ASSERT_EQ(run.code, 0) << run.out;
  const auto rc = listener.wait(10s);
  ASSERT_TRUE(rc.has_value()) << "the Fast DDS listener did not finish";
  EXPECT_EQ(*rc, 0) << "the Fast DDS listener got fewer than 4 PoseArray messages";
  std::istringstream lines(slurp(out));
  std::string word, frame;
  std::size_t poses = 0, count = 0;
  double stamp = 0, last_stamp = -1, x = 0, y = 0, qz = 0, qw = 0;
  while (lines >> word >> poses >> word >> frame >> word >> stamp >> word >> x >> y >> qz >> qw) {
    ++count;
    EXPECT_EQ(poses, 50u);
    EXPECT_EQ(frame, "map");
    EXPECT_GT(stamp, last_stamp);  // sim time goes forward
    last_stamp = stamp;
    // Robot 0 is on the 32x32 map, its orientation a unit quaternion about z.
    EXPECT_GE(x, -0.5);
    EXPECT_LE(x, 31.5);
    EXPECT_GE(y, -0.5);
    EXPECT_LE(y, 31.5);
    EXPECT_NEAR(qz * qz + qw * qw, 1.0, 1e-5);
  }
  EXPECT_EQ(count, 4u);
  std::filesystem::remove(out);
}

// rviz2's view of the plan (`--ros-plan-hz`): a Fast DDS reader decodes robot 0's planned path
// and the MarkerArray stream. Robot 0 turns south before leaving (1,0) while robot 1 behind it
// must wait to enter that cell (a Type-2 wait): the markers show robot 1 orange with an arrow
// to robot 0, and at the end every robot grey.
TEST(RosInterop, FastDdsReaderDecodesThePlanViewRviz2Shows) {
  const auto map = temp_file("plan_view.map"), scen = temp_file("plan_view.scen"),
             plan = temp_file("plan_view.plan"), out = temp_file("fastdds_plan.out");
  std::ofstream(map) << "type octile\nheight 2\nwidth 5\nmap\n.....\n.....\n";
  std::ofstream(scen) << "version 1\n0\tm.map\t5\t2\t1\t0\t2\t1\t2\n"
                         "0\tm.map\t5\t2\t0\t0\t2\t0\t2\n";
  std::ofstream(plan) << "Agent 0:(1,0)->(1,1)->(2,1)->\nAgent 1:(0,0)->(1,0)->(2,0)->\n";
  common::ChildProcess listener({FASTDDS_PLAN_LISTENER, std::to_string(kRosPlanView), "60"}, out);
  const auto run = run_smart({"run", "--map", map.string(), "--scen", scen.string(), "--plan",
                              plan.string(), "--axis", "xy", "--clock", "realtime", "--ros-plan-hz",
                              "10", "--domain", std::to_string(kRosPlanView), "--no-progress"},
                             60s, "plan_view_run");
  ASSERT_EQ(run.code, 0) << run.out;
  ASSERT_EQ(listener.wait(10s).value_or(-1), 0) << slurp(out);
  std::istringstream lines(slurp(out));
  std::string line;
  bool path = false, waited = false, last_done = false;
  while (std::getline(lines, line)) {
    if (line.rfind("path", 0) == 0) {
      // start (1,0) and 4 half-moves to (2,1), in metres (cell 1 m, y up)
      EXPECT_EQ(line, "path 5 1.000 1.000 2.000 0.000 frame map");
      path = true;
      continue;
    }
    int m = 0, moving = 0, waiting = 0, done = 0, goals = 0, arrows = 0, del = 0;
    ASSERT_EQ(std::sscanf(line.c_str(),
                          "markers %d moving %d waiting %d done %d goals %d arrows "
                          "%d deleteall %d",
                          &m, &moving, &waiting, &done, &goals, &arrows, &del),
              7)
        << line;
    EXPECT_EQ(goals, 2);
    EXPECT_EQ(del, 1);                   // the old arrows are cleared each time
    EXPECT_EQ(arrows, waiting) << line;  // one robot waits for one other here
    waited = waited || (waiting == 1 && arrows == 1);
    last_done = done == 2;
  }
  EXPECT_TRUE(path);
  EXPECT_TRUE(waited) << "robot 1 was never shown waiting for robot 0";
  EXPECT_TRUE(last_done);
  for (const auto& f : {map, scen, plan, out}) std::filesystem::remove(f);
}

// The shipped rviz2 configuration names the topics, frame and QoS the bridge really uses (the
// constants of idl/smart.idl), so it shows a run as it is.
TEST(RosInterop, Rviz2ConfigShowsTheTopicsTheBridgePublishes) {
  const auto rviz = YAML::LoadFile(std::string(SMART_SOURCE_DIR) + "/config/rviz/smart.rviz");
  const auto manager = rviz["Visualization Manager"];
  EXPECT_EQ(manager["Global Options"]["Fixed Frame"].as<std::string>(), dds::kRosMapFrame);
  std::map<std::string, std::string> durability;  // topic -> durability
  for (const auto& d : manager["Displays"]) {
    if (d["Topic"])
      durability[d["Topic"]["Value"].as<std::string>()] =
          d["Topic"]["Durability Policy"].as<std::string>();
  }
  EXPECT_EQ(durability.at(std::string(dds::kRosMapTopic)), "Transient Local");
  EXPECT_EQ(durability.at(std::string(dds::kRosMarkersTopic)), "Transient Local");
  EXPECT_EQ(durability.at(dds::ros_robot_plan_topic(0)), "Transient Local");
  EXPECT_TRUE(durability.count(std::string(dds::kRosPosesTopic)));
}

}  // namespace
}  // namespace smart::test
