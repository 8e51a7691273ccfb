// A mixed run, as on a lab floor but with the emulated JetBot: one `smart monitor` (real-time),
// a `smart sim` host for robots 0 and 1 that shows robot 2 at its published pose, and a
// `smart agent --backend jetbot --i2c emulated` process for robot 2 whose PCA9685 register
// writes drive a wheel model that streams its pose back as Vicon UDP datagrams.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <thread>

#include "smart/dds/qos_profile.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

TEST(MixedRun, EmulatedJetbotAgentAndSimulatedRobotsCompleteAPlanTogether) {
  const auto map = temp_file("mixed.map").string();
  const auto scen = temp_file("mixed.scen").string();
  const auto plan = temp_file("mixed.plan").string();
  // Robot 2 drives from (4,0) down to (4,4); robots 0 and 1 move around it.
  std::ofstream(map) << "type octile\nheight 6\nwidth 6\nmap\n......\n......\n......\n"
                        "......\n......\n......\n";
  std::ofstream(scen) << "version 1\n0\tm.map\t6\t6\t2\t2\t3\t0\t3\n"
                         "0\tm.map\t6\t6\t5\t5\t4\t5\t1\n0\tm.map\t6\t6\t4\t0\t4\t4\t4\n";
  ASSERT_EQ(
      run_smart({"plan", "--map", map, "--scen", scen, "--out", plan}, 30s, "mixed_plan").code, 0);
  const std::string domain = std::to_string(kMixedRun);
  const double cell = 0.4;
  const auto start_x = std::to_string(4 * cell), start_y = std::to_string((6 - 1 - 0) * cell);
  const auto agent_out = temp_file("mixed_agent.out");
  tools::ChildProcess sim({smart_exe().string(), "sim", "--map", map, "--scen", scen, "--agents",
                           "3", "--clock", "realtime", "--cell-m", "0.4", "--robot", "jetbot",
                           "--external-robots", "2", "--domain", domain},
                          "/dev/null");
  tools::ChildProcess agent(
      {smart_exe().string(), "agent", "--robot-id", "2", "--backend", "jetbot", "--config",
       "jetbot", "--i2c", "emulated", "--emulate-pose", start_x + "," + start_y + ",0",
       "--vicon-port", "0", "--domain", domain},
      agent_out);
  const auto r = run_smart(
      {"monitor", "--map",    map,       "--scen",        scen,          "--plan", plan,
       "--axis",  "xy",       "--clock", "realtime",      "--cell-m",    "0.4",    "--robot",
       "jetbot",  "--domain", domain,    "--no-progress", "--timeout-s", "15"},
      90s, "mixed_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["robots"], 3);
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["finished_actions"], j["total_actions"]);
  // Both hosts stop when the monitor says the run is over.
  ASSERT_EQ(agent.wait(10s).value_or(-1), 0);
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0);
  const std::string out = slurp(agent_out);
  const auto a = nlohmann::json::parse(out.substr(out.find('{')));
  EXPECT_TRUE(a["stopped_by_monitor"].get<bool>());
  EXPECT_EQ(a["finished_seq"].get<int>() + 1, 9);  // rotate + 4 moves as 8 half-moves
  EXPECT_GT(a["vicon"]["datagrams"].get<int>(), 100);
  EXPECT_EQ(a["vicon"]["malformed"], 0);
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
  std::filesystem::remove(agent_out);
}

// Robot 2's agent process is killed mid-run (SIGKILL, as in a crash) and started again where its
// robot stands: the run carries on from the monitor's window, nothing lost or repeated.
TEST(MixedRun, AKilledAndRestartedAgentResumesItsRobotsPlan) {
  const auto map = temp_file("restart.map").string();
  const auto scen = temp_file("restart.scen").string();
  const auto plan = temp_file("restart.plan").string();
  // Robot 2 drives from (4,0) down to (4,4); robots 0 and 1 move around it.
  std::ofstream(map) << "type octile\nheight 6\nwidth 6\nmap\n......\n......\n......\n"
                        "......\n......\n......\n";
  std::ofstream(scen) << "version 1\n0\tm.map\t6\t6\t2\t2\t3\t0\t3\n"
                         "0\tm.map\t6\t6\t5\t5\t4\t5\t1\n0\tm.map\t6\t6\t4\t0\t4\t4\t4\n";
  ASSERT_EQ(
      run_smart({"plan", "--map", map, "--scen", scen, "--out", plan}, 30s, "restart_plan").code,
      0);
  const std::string domain = std::to_string(kMixedRestart);
  const double cell = 0.4;
  tools::ChildProcess sim({smart_exe().string(), "sim", "--map", map, "--scen", scen, "--agents",
                           "3", "--clock", "realtime", "--cell-m", "0.4", "--robot", "jetbot",
                           "--external-robots", "2", "--domain", domain},
                          "/dev/null");
  auto agent_argv = [&](double x, double y, double yaw) {
    return std::vector<std::string>{
        smart_exe().string(),
        "agent",
        "--robot-id",
        "2",
        "--backend",
        "jetbot",
        "--config",
        "jetbot",
        "--i2c",
        "emulated",
        "--emulate-pose",
        std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(yaw),
        "--vicon-port",
        "0",
        "--domain",
        domain};
  };
  auto first =
      std::make_unique<tools::ChildProcess>(agent_argv(4 * cell, 5 * cell, 0.0), "/dev/null");
  const auto monitor_out = temp_file("restart_monitor.out");
  tools::ChildProcess monitor({smart_exe().string(),
                               "monitor",
                               "--map",
                               map,
                               "--scen",
                               scen,
                               "--plan",
                               plan,
                               "--axis",
                               "xy",
                               "--clock",
                               "realtime",
                               "--cell-m",
                               "0.4",
                               "--robot",
                               "jetbot",
                               "--domain",
                               domain,
                               "--no-progress",
                               "--timeout-s",
                               "15"},
                              monitor_out);
  // Watch robot 2 as any DDS tool would; kill its agent once it has finished a few actions.
  dds::Domain dds_domain(kMixedRestart, loopback());
  dds::Participant watcher(dds_domain);
  const auto qos = dds::default_qos_profile();
  dds::Topic<smart_msg_Progress> tp(watcher, std::string(dds::kProgressTopic));
  dds::Topic<smart_msg_RobotState> ts(watcher, std::string(dds::kStateTopic));
  dds::Reader<smart_msg_Progress> progress(watcher, tp, qos.progress.to_dds());
  dds::Reader<smart_msg_RobotState> states(watcher, ts, qos.state.to_dds());
  int64_t finished = -1;
  const auto give_up = std::chrono::steady_clock::now() + 60s;
  while (finished < 2 && std::chrono::steady_clock::now() < give_up) {
    progress.take_each([&](const smart_msg_Progress& p) {
      if (p.robot_id == 2) finished = std::max<int64_t>(finished, p.finished_seq);
    });
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_GE(finished, 2) << "robot 2 did not get under way";
  first->signal(SIGKILL);
  ASSERT_TRUE(first->wait(5s).has_value());
  // Where the robot stands now: its last published state (a real robot would still be there).
  std::optional<smart_msg_Pose2D> pose;
  states.take_each([&](const smart_msg_RobotState& s) {
    if (s.robot_id == 2) pose = s.pose;
  });
  ASSERT_TRUE(pose.has_value()) << "no state of robot 2 seen";
  const auto agent_out = temp_file("restart_agent.out");
  tools::ChildProcess second(agent_argv(pose->x_m, pose->y_m, pose->yaw_rad), agent_out);

  const auto rc = monitor.wait(90s);
  ASSERT_TRUE(rc.has_value()) << "the run did not end";
  const std::string text = slurp(monitor_out);
  ASSERT_EQ(*rc, 0) << text;
  const auto j = nlohmann::json::parse(text.substr(text.find('{')));
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["finished_actions"], j["total_actions"]);
  EXPECT_EQ(j["rejected_progress"], 0);
  EXPECT_EQ(j["collisions"], 0);
  ASSERT_EQ(second.wait(10s).value_or(-1), 0);
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0);
  const std::string out = slurp(agent_out);
  const auto a = nlohmann::json::parse(out.substr(out.find('{')));
  EXPECT_TRUE(a["stopped_by_monitor"].get<bool>());
  EXPECT_EQ(a["finished_seq"].get<int>() + 1, 9);  // rotate + 4 moves as 8 half-moves
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
  std::filesystem::remove(agent_out);
  std::filesystem::remove(monitor_out);
}

}  // namespace
}  // namespace smart::test
