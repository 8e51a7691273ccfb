// A mixed run, as on a lab floor but with the emulated JetBot: one `smart monitor` (real-time),
// a `smart sim` host for robots 0 and 1 that shows robot 2 at its published pose, and a
// `smart agent --backend jetbot --i2c emulated` process for robot 2 whose PCA9685 register
// writes drive a wheel model that streams its pose back as Vicon UDP datagrams.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <fstream>

#include "support/fleet_watcher.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

constexpr double kCellM = 0.4;

// A 6x6 open map; robot 2 drives from (4,0) down to (4,4) (a rotation and 4 moves as 8
// half-moves: 9 actions) while robots 0 and 1 move around it. Robot 2 is the JetBot.
class MixedRun : public ::testing::Test {
 protected:
  void plan_instance(const std::string& tag) {
    map_ = temp_file(tag + ".map").string();
    scen_ = temp_file(tag + ".scen").string();
    plan_ = temp_file(tag + ".plan").string();
    std::ofstream(map_) << "type octile\nheight 6\nwidth 6\nmap\n......\n......\n......\n"
                           "......\n......\n......\n";
    std::ofstream(scen_) << "version 1\n0\tm.map\t6\t6\t2\t2\t3\t0\t3\n"
                            "0\tm.map\t6\t6\t5\t5\t4\t5\t1\n0\tm.map\t6\t6\t4\t0\t4\t4\t4\n";
    ASSERT_EQ(run_smart({"plan", "--map", map_, "--scen", scen_, "--out", plan_}, 30s, tag).code,
              0);
  }
  void TearDown() override {
    for (const auto& f : {map_, scen_, plan_}) {
      if (!f.empty()) std::filesystem::remove(f);
    }
  }
  tools::ChildProcess start_sim(int domain) const {
    return start_smart(
        {"sim", "--map", map_, "--scen", scen_, "--agents", "3", "--clock", "realtime", "--cell-m",
         "0.4", "--robot", "jetbot", "--external-robots", "2", "--domain", std::to_string(domain)},
        "/dev/null");
  }
  // Robot 2's agent, its emulated JetBot starting at (x, y, yaw).
  static tools::ChildProcess start_agent(int domain, double x, double y, double yaw,
                                         const std::filesystem::path& out) {
    return start_smart({"agent", "--robot-id", "2", "--backend", "jetbot", "--config", "jetbot",
                        "--i2c", "emulated", "--emulate-pose",
                        std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(yaw),
                        "--vicon-port", "0", "--domain", std::to_string(domain)},
                       out);
  }
  std::vector<std::string> monitor_args(int domain) const {
    return {"monitor",
            "--map",
            map_,
            "--scen",
            scen_,
            "--plan",
            plan_,
            "--axis",
            "xy",
            "--clock",
            "realtime",
            "--cell-m",
            "0.4",
            "--robot",
            "jetbot",
            "--domain",
            std::to_string(domain),
            "--no-progress",
            "--timeout-s",
            "15"};
  }
  // The finished run: success with nothing lost, and the agent's own report.
  static void expect_complete(const nlohmann::json& summary, const std::filesystem::path& agent_out,
                              nlohmann::json* agent_report) {
    EXPECT_TRUE(summary["success"].get<bool>());
    EXPECT_EQ(summary["robots"], 3);
    EXPECT_EQ(summary["collisions"], 0);
    EXPECT_EQ(summary["finished_actions"], summary["total_actions"]);
    *agent_report = summary_in(slurp(agent_out));
    EXPECT_TRUE((*agent_report)["stopped_by_monitor"].get<bool>());
    EXPECT_EQ((*agent_report)["finished_seq"].get<int>() + 1, 9);
  }
  std::string map_, scen_, plan_;
};

TEST_F(MixedRun, EmulatedJetbotAgentAndSimulatedRobotsCompleteAPlanTogether) {
  plan_instance("mixed");
  const auto agent_out = temp_file("mixed_agent.out");
  auto sim = start_sim(kMixedRun);
  auto agent = start_agent(kMixedRun, 4 * kCellM, (6 - 1 - 0) * kCellM, 0.0, agent_out);
  const auto r = run_smart(monitor_args(kMixedRun), 90s, "mixed_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  // Both hosts stop when the monitor says the run is over.
  ASSERT_EQ(agent.wait(10s).value_or(-1), 0);
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0);
  nlohmann::json a;
  expect_complete(r.last_json(), agent_out, &a);
  EXPECT_GT(a["vicon"]["datagrams"].get<int>(), 100);
  EXPECT_EQ(a["vicon"]["malformed"], 0);
  std::filesystem::remove(agent_out);
}

// Robot 2's agent process is killed mid-run (SIGKILL, as in a crash) and started again where its
// robot stands: the run carries on from the monitor's window, nothing lost or repeated.
TEST_F(MixedRun, AKilledAndRestartedAgentResumesItsRobotsPlan) {
  plan_instance("restart");
  auto sim = start_sim(kMixedRestart);
  auto first = start_agent(kMixedRestart, 4 * kCellM, 5 * kCellM, 0.0, "/dev/null");
  const auto monitor_out = temp_file("restart_monitor.out");
  auto monitor = start_smart(monitor_args(kMixedRestart), monitor_out);
  // Kill robot 2's agent once it has finished a few actions.
  FleetWatcher watcher(kMixedRestart);
  ASSERT_GE(watcher.wait_for_finished(2, 60s, 2), 2) << "robot 2 did not get under way";
  first.signal(SIGKILL);
  ASSERT_TRUE(first.wait(5s).has_value());
  // Where the robot stands now: its last published state (a real robot would still be there).
  const auto pose = watcher.last_pose(2);
  ASSERT_TRUE(pose.has_value()) << "no state of robot 2 seen";
  const auto agent_out = temp_file("restart_agent.out");
  auto second = start_agent(kMixedRestart, pose->x_m, pose->y_m, pose->yaw_rad, agent_out);

  const auto rc = monitor.wait(90s);
  ASSERT_TRUE(rc.has_value()) << "the run did not end";
  const std::string text = slurp(monitor_out);
  ASSERT_EQ(*rc, 0) << text;
  ASSERT_EQ(second.wait(10s).value_or(-1), 0);
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0);
  const auto j = summary_in(text);
  EXPECT_EQ(j["rejected_progress"], 0);
  nlohmann::json a;
  expect_complete(j, agent_out, &a);
  std::filesystem::remove(agent_out);
  std::filesystem::remove(monitor_out);
}

}  // namespace
}  // namespace smart::test
