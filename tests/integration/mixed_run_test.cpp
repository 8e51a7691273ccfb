// A mixed run (support/mixed_fleet.hpp): one `smart monitor` (real time), a `smart sim` host for
// robots 0 and 1, and an emulated JetBot's `smart agent` for robot 2.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>

#include "support/fleet_watcher.hpp"
#include "support/mixed_fleet.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

constexpr double kCellM = MixedFleet::kCellM;

class MixedRun : public ::testing::Test {
 protected:
  void plan_instance(const std::string& tag) { fleet_.emplace(tag); }
  common::ChildProcess start_sim(int domain) const { return fleet_->start_sim(domain); }
  static common::ChildProcess start_agent(int domain, double x, double y, double yaw,
                                          const std::filesystem::path& out) {
    return MixedFleet::start_agent(domain, x, y, yaw, out);
  }
  std::vector<std::string> monitor_args(int domain) const { return fleet_->monitor_args(domain); }
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
  std::optional<MixedFleet> fleet_;
};

TEST_F(MixedRun, EmulatedJetbotAgentAndSimulatedRobotsCompleteAPlanTogether) {
  plan_instance("mixed");
  const auto agent_out = temp_file("mixed_agent.out");
  auto sim = start_sim(kMixedRun);
  auto agent = start_agent(kMixedRun, 4 * kCellM, (6 - 1 - 0) * kCellM, 0.0, agent_out);
  const auto out = temp_file("mixed_out");
  auto args = monitor_args(kMixedRun);
  args.insert(args.end(), {"--out", out.string()});
  const auto r = run_smart(args, 90s, "mixed_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  // Both hosts stop when the monitor says the run is over.
  ASSERT_EQ(agent.wait(10s).value_or(-1), 0);
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0);
  nlohmann::json a;
  expect_complete(r.last_json(), agent_out, &a);
  EXPECT_GT(a["vicon"]["datagrams"].get<int>(), 100);
  EXPECT_EQ(a["vicon"]["malformed"], 0);
  // states.csv has one time base (the monitor's run clock), JetBot rows and simulated alike:
  // the JetBot stamps its host's uptime, which must not leak into the file.
  std::ifstream states(out / "states.csv");
  std::string line;
  std::getline(states, line);
  double jetbot_max = -1, sim_max = -1;
  const double end_s = r.last_json()["sim_time_s"].get<double>();
  while (std::getline(states, line)) {
    const double t = std::stod(line.substr(0, line.find(',')));
    const int robot = std::stoi(line.substr(line.find(',') + 1));
    EXPECT_GE(t, 0.0) << line;
    EXPECT_LE(t, end_s + 1.0) << line;
    (robot == 2 ? jetbot_max : sim_max) = std::max(robot == 2 ? jetbot_max : sim_max, t);
  }
  EXPECT_GT(jetbot_max, 0.5 * end_s) << "JetBot rows along the whole run";
  EXPECT_GT(sim_max, 0.5 * end_s);
  std::filesystem::remove(agent_out);
  std::filesystem::remove_all(out);
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
