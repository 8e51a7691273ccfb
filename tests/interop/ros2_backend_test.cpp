// `smart agent --backend ros2` against a ROS 2 diff-drive robot written with the second DDS
// vendor (fastdds_diffdrive.cpp: cmd_vel in, odometry out, a unicycle with TurtleBot3 Burger's
// limits). Real processes, real DDS traffic on loopback, own domain: `smart monitor` (real
// time), one `smart agent` hosting the robots, the Fast DDS robots.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "smart/geometry/frame_transform.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

constexpr double kCellM = 0.3;

// A 4x4 open map; robot 0 drives (0,3) -> (2,3) along the bottom row, robot 1 (3,0) -> (3,2)
// down the right column (MovingAI rows: y = 3 - row in the world).
struct Ros2Fleet {
  std::string map = temp_file("ros2.map").string(), scen = temp_file("ros2.scen").string(),
              plan = temp_file("ros2.plan").string();
  Ros2Fleet() {
    std::ofstream(map) << "type octile\nheight 4\nwidth 4\nmap\n....\n....\n....\n....\n";
    std::ofstream(scen) << "version 1\n0\tm.map\t4\t4\t0\t3\t2\t3\t2\n"
                           "0\tm.map\t4\t4\t3\t0\t3\t2\t2\n";
    const auto r =
        run_smart({"plan", "--map", map, "--scen", scen, "--out", plan}, 30s, "ros2_plan");
    EXPECT_EQ(r.code, 0) << r.out;
  }
  ~Ros2Fleet() {
    for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
  }
  std::vector<std::string> monitor(int domain, const std::filesystem::path& out) const {
    return {"monitor",
            "--map",
            map,
            "--scen",
            scen,
            "--plan",
            plan,
            "--clock",
            "realtime",
            "--cell-m",
            "0.3",
            "--robot",
            "turtlebot3-burger",
            "--domain",
            std::to_string(domain),
            "--no-progress",
            "--timeout-s",
            "40",
            "--out",
            out.string()};
  }
};

// The world pose of a cell's centre.
std::string start_pose(const char* ns, int col, int row, double yaw) {
  std::ostringstream s;
  s << ns << ":" << col * kCellM << "," << (3 - row) * kCellM << "," << yaw;
  return s.str();
}

common::ChildProcess start_robots(int domain, const std::string& odom,
                                  const std::vector<std::string>& robots,
                                  const std::filesystem::path& out) {
  std::vector<std::string> argv{
      FASTDDS_DIFFDRIVE, std::to_string(domain), "90", "0.22", "2.84", "0.5", "3.0", odom};
  argv.insert(argv.end(), robots.begin(), robots.end());
  return common::ChildProcess(argv, out);
}

struct FinalPose {
  double x = 0, y = 0, yaw = 0, last_v = 0, last_w = 0;
  long cmds = 0;
};
// "robot NS x y yaw cmds N last V W" lines of the stand-in.
std::map<std::string, FinalPose> final_poses(const std::string& text) {
  std::map<std::string, FinalPose> out;
  std::istringstream in(text);
  std::string word, ns;
  FinalPose p;
  while (in >> word >> ns >> p.x >> p.y >> p.yaw >> word >> p.cmds >> word >> p.last_v >>
         p.last_w) {
    out[ns] = p;
  }
  return out;
}

void expect_at(const FinalPose& p, int col, int row) {
  EXPECT_NEAR(p.x, col * kCellM, 0.03);
  EXPECT_NEAR(p.y, (3 - row) * kCellM, 0.03);
}

TEST(Ros2Backend, OneAgentProcessDrivesTwoRos2RobotsThroughCmdVelAndOdom) {
  Ros2Fleet fleet;
  const auto robots_out = temp_file("ros2_robots.out"), agent_out = temp_file("ros2_agent.out");
  const auto out = temp_file("ros2_run");
  auto robots = start_robots(kRos2Fleet, "world",
                             {start_pose("/robot_0", 0, 3, 0.0), start_pose("/robot_1", 3, 0, 0.0)},
                             robots_out);
  // Odometry older than 1 s stops a robot: the default 0.1 s is a real base's, and on a machine
  // loaded by other work the Fast DDS robot processes were starved past it (watchdog stops in a
  // run that otherwise succeeded); a stream that stops for good still trips it.
  auto agent = start_smart({"agent", "--backend", "ros2", "--robot-ids", "0-1", "--pose-max-age-s",
                            "1", "--domain", std::to_string(kRos2Fleet)},
                           agent_out);
  const auto r = run_smart(fleet.monitor(kRos2Fleet, out), 60s, "ros2_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_EQ(agent.wait(10s).value_or(-1), 0) << "the agent stops when the monitor's run ends";
  robots.terminate();
  const auto s = r.last_json();
  EXPECT_TRUE(s["success"].get<bool>()) << r.out << slurp(robots_out);
  EXPECT_EQ(s["collisions"], 0);
  EXPECT_EQ(s["finished_actions"], s["total_actions"]);
  const auto report = summary_in(slurp(agent_out));
  EXPECT_TRUE(report["stopped_by_monitor"].get<bool>());
  ASSERT_EQ(report["robots"].size(), 2u);
  for (const auto& robot : report["robots"]) {
    EXPECT_GT(robot["cmd_vel_writes"].get<int>(), 20);
    EXPECT_GT(robot["pose_samples"].get<int>(), 50);
    EXPECT_EQ(robot["watchdog_stops"], 0);
  }
  // The Fast DDS robots are where the plan ends, and the last command they heard is a stop.
  const auto poses = final_poses(slurp(robots_out));
  ASSERT_EQ(poses.size(), 2u) << slurp(robots_out);
  expect_at(poses.at("/robot_0"), 2, 3);
  expect_at(poses.at("/robot_1"), 3, 2);
  for (const auto& [ns, p] : poses) {
    EXPECT_GT(p.cmds, 20) << ns;
    EXPECT_EQ(p.last_v, 0.0) << ns;
    EXPECT_EQ(p.last_w, 0.0) << ns;
  }
  for (const auto& f : {robots_out, agent_out}) std::filesystem::remove(f);
  std::filesystem::remove_all(out);
}

// Odometry as a real base reports it: (0, 0, 0) where the robot was switched on. One transform
// file per robot (`--pose-transform DIR/robot_{id}.yaml`) puts each on the grid; robot 1 starts
// facing north, so its file rotates as well as shifts.
TEST(Ros2Backend, OdometryFromWhereEachRobotStartedIsPutOnTheGridByItsTransformFile) {
  Ros2Fleet fleet;
  const auto dir = temp_file("ros2_frames");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "robot_0.yaml") << "scale: 1\nyaw_rad: 0\ntranslation_m: [0, 0]\n";
  std::ofstream(dir / "robot_1.yaml") << "scale: 1\nyaw_rad: 1.5707963267948966\n"
                                         "translation_m: [0.9, 0.9]\n";
  const auto robots_out = temp_file("ros2_start_robots.out");
  const auto agent_out = temp_file("ros2_start_agent.out"), out = temp_file("ros2_start_run");
  auto robots = start_robots(
      kRos2OdomAtStart, "start",
      {start_pose("/robot_0", 0, 3, 0.0), start_pose("/robot_1", 3, 0, M_PI / 2)}, robots_out);
  auto agent = start_smart(
      {"agent", "--backend", "ros2", "--robot-ids", "0,1", "--pose", "odom", "--pose-transform",
       (dir / "robot_{id}.yaml").string(), "--domain", std::to_string(kRos2OdomAtStart)},
      agent_out);
  const auto r = run_smart(fleet.monitor(kRos2OdomAtStart, out), 60s, "ros2_start_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_EQ(agent.wait(10s).value_or(-1), 0);
  robots.terminate();
  EXPECT_TRUE(r.last_json()["success"].get<bool>()) << r.out << slurp(robots_out);
  EXPECT_EQ(r.last_json()["collisions"], 0);
  const auto poses = final_poses(slurp(robots_out));
  ASSERT_EQ(poses.size(), 2u) << slurp(robots_out);
  expect_at(poses.at("/robot_0"), 2, 3);
  expect_at(poses.at("/robot_1"), 3, 2);
  for (const auto& f : {robots_out, agent_out}) std::filesystem::remove(f);
  std::filesystem::remove_all(out);
  std::filesystem::remove_all(dir);
}

// `smart calibrate frame --pose odom`: three ROS 2 robots report poses in a frame rotated and
// shifted against the grid (as from a mocap relay); the fit finds that frame.
TEST(Ros2Calibrate, FrameFitFromThreeRobotsOdometry) {
  Ros2Fleet fleet;
  const auto robots_out = temp_file("ros2_frame_robots.out"), out = temp_file("ros2_frame.yaml");
  auto robots = start_robots(kRos2Calibrate, "frame:1,0.5,2.0,-1.0",
                             {start_pose("/robot_0", 0, 3, 0.0), start_pose("/robot_1", 3, 3, 1.0),
                              start_pose("/robot_2", 1, 0, 2.0)},
                             robots_out);
  const auto r =
      run_smart({"calibrate", "frame",  "--map",      fleet.map,  "--cell-m",
                 "0.3",       "--pose", "odom",       "--point",  "0:0,3",
                 "--point",   "1:3,3",  "--point",    "2:1,0",    "--record-s",
                 "0.3",       "--out",  out.string(), "--domain", std::to_string(kRos2Calibrate)},
                30s, "ros2_frame", true);
  robots.terminate();
  ASSERT_EQ(r.code, 0) << r.out;
  const auto t = geometry::load_frame_transform(out.string());
  EXPECT_NEAR(t.scale, 1.0, 1e-6);
  EXPECT_NEAR(t.yaw_rad, 0.5, 1e-4);
  EXPECT_NEAR(t.translation_m.x(), 2.0, 1e-4);
  EXPECT_NEAR(t.translation_m.y(), -1.0, 1e-4);
  for (const auto& f : {robots_out, out}) std::filesystem::remove(f);
}

// `smart calibrate trim --backend ros2`: a base whose right wheel delivers 85 %; the proposed
// `trim:` in the robot file makes it drive straight.
TEST(Ros2Calibrate, TrimFindsTheWeakWheelOfARos2Base) {
  const auto robots_out = temp_file("ros2_trim_robots.out");
  auto robots =
      start_robots(kRos2CalibrateTrim, "world", {"/robot_0:0.5,0.5,0,1.0,0.85"}, robots_out);
  auto trial = [&](const std::vector<std::string>& extra, const std::string& tag) {
    std::vector<std::string> args{"calibrate",
                                  "trim",
                                  "--backend",
                                  "ros2",
                                  "--robot-id",
                                  "0",
                                  "--yes",
                                  "--seconds",
                                  "3",
                                  "--domain",
                                  std::to_string(kRos2CalibrateTrim)};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_smart(args, 30s, tag, true);
    EXPECT_EQ(r.code, 0) << r.out;
    return last_json_line(r.out);
  };
  const auto t = trial({}, "ros2_trim");
  const double left = t["proposed"]["trim.left"].get<double>();
  EXPECT_NEAR(left, 0.85, 0.02);
  EXPECT_DOUBLE_EQ(t["proposed"]["trim.right"].get<double>(), 1.0);
  const auto file = temp_file("trimmed-burger.yaml");
  std::ifstream in(std::string(SMART_SOURCE_DIR) + "/config/robots/turtlebot3-burger.yaml");
  std::stringstream text;
  text << in.rdbuf() << "trim: {left: " << left << "}\n";
  std::ofstream(file) << text.str();
  const auto after = trial({"--config", file.string()}, "ros2_trim_after");
  EXPECT_LT(std::abs(after["turn_rate_radps"].get<double>()),
            0.2 * std::abs(t["turn_rate_radps"].get<double>()));
  robots.terminate();
  for (const auto& f : {robots_out, file}) std::filesystem::remove(f);
}

// `smart doctor --backend ros2` over two bases, robot 1's left wheel wired backwards.
TEST(Ros2Calibrate, DoctorChecksEachBasesOdometryAndWheels) {
  const auto robots_out = temp_file("ros2_doctor_robots.out");
  auto robots = start_robots(kRos2Doctor, "world",
                             {"/robot_0:0.5,0.5,0", "/robot_1:2.5,0.5,0,-1,1"}, robots_out);
  const auto r = run_smart({"doctor", "--backend", "ros2", "--robot-ids", "0-1", "--wheels",
                            "--yes", "--seconds", "1", "--domain", std::to_string(kRos2Doctor)},
                           60s, "ros2_doctor", true);
  robots.terminate();
  EXPECT_EQ(r.code, 1) << r.out;
  std::map<std::string, std::string> level;  // "robot/check" -> level
  const auto report = last_json_line(r.out);
  for (const auto& row : report["rows"]) {
    level[row["robot"].get<std::string>() + "/" + row["check"].get<std::string>()] =
        row["level"].get<std::string>();
  }
  for (const char* key : {"0/motor board", "0/pose stream", "0/left wheel", "0/right wheel",
                          "1/pose stream", "1/right wheel"}) {
    EXPECT_EQ(level[key], "OK") << key << "\n" << r.out;
  }
  EXPECT_EQ(level["1/left wheel"], "FAIL") << r.out;
  EXPECT_NE(r.out.find("fix the base's driver"), std::string::npos) << r.out;
  std::filesystem::remove(robots_out);
}

TEST(Ros2Backend, BadRobotListsAndMissingTransformFilesAreNamed) {
  const auto bad = run_smart({"agent", "--backend", "ros2", "--robot-ids", "3-1", "--domain",
                              std::to_string(kRos2BadRobotLists)},
                             20s, "ros2_bad_ids", true);
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.out.find("'3-1' is not ascending"), std::string::npos) << bad.out;
  const auto both = run_smart({"agent", "--backend", "jetbot", "--robot-ids", "0-1", "--domain",
                               std::to_string(kRos2BadRobotLists)},
                              20s, "ros2_jetbot_many", true);
  EXPECT_NE(both.code, 0);
  EXPECT_NE(both.out.find("one robot per process"), std::string::npos) << both.out;
  const auto missing =
      run_smart({"agent", "--backend", "ros2", "--robot-ids", "0", "--pose-transform",
                 "/nonexistent/robot_{id}.yaml", "--domain", std::to_string(kRos2BadRobotLists)},
                20s, "ros2_missing_transform", true);
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.out.find("/nonexistent/robot_0.yaml"), std::string::npos) << missing.out;
}

}  // namespace
}  // namespace smart::test
