// Samples from a rogue participant on the run's domain and partition: malformed states and
// clocks are dropped at the monitor's edge, counted in summary.json, and never reach
// states.csv; the run still succeeds with the numbers it gives undisturbed. The rogue knows the
// protocol: its states of robot 3 outrank the sim host's (exclusive ownership, idl/smart.idl),
// so robot 3's real states are hidden; the verdict then says robot 3's final pose is
// unverified, never a false "at goal" (only DDS Security keeps such a rogue out).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "smart/dds/wire.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

TEST(UntrustedSamples, MalformedStatesAndClocksAreDroppedAndCounted) {
  const auto b = benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  const int d = kMonitorBadSamples;
  const std::vector<std::string> world{
      "--map",    (b / "maps/random-32-32-20.map").string(),
      "--scen",   (b / "scens/random-32-32-20-random-1.scen").string(),
      "--agents", "20",
      "--domain", std::to_string(d)};
  auto args = world;
  args.insert(args.begin(), "sim");
  auto sim = start_smart(args, temp_file("untrusted_sim.out"));

  dds::Domain domain(d, loopback());
  dds::Participant rogue_p(domain);
  const auto qos = dds::find_qos_profile("lan");  // the run's profile: its QoS is compatible
  dds::WireWriter<smart_msg_RobotState> states(rogue_p, qos, dds::kHostStrength + 1);
  dds::WireWriter<smart_msg_Clock> clocks(rogue_p, qos);
  std::atomic<bool> done{false};
  std::thread rogue([&] {
    while (!done) {
      smart_msg_RobotState s{};
      s.robot_id = 3;
      s.pose = {std::nan(""), 1.0, 0.0};
      states.write(s);
      s.robot_id = 4000;
      s.pose = {1.0, 1.0, 0.0};
      states.write(s);
      clocks.write(smart_msg_Clock{7, 0, 5, -std::numeric_limits<double>::infinity(), 0, false});
      std::this_thread::sleep_for(20ms);
    }
  });
  const auto out = temp_file("untrusted_results");
  args = world;
  args.insert(args.begin(), "monitor");
  args.insert(args.end(), {"--plan", (b / "smart-examples/example_paths_xy.txt").string(), "--axis",
                           "xy", "--out", out.string(), "--no-progress", "--state-rate-hz", "10"});
  const auto r = run_smart(args, 120s, "untrusted_monitor");
  done = true;
  rogue.join();
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_TRUE(j["success"].get<bool>());
  const auto rejected = j.value("rejected_samples", nlohmann::json::object());
  const auto count = [&](const char* topic, const char* reason) {
    return rejected.value(topic, nlohmann::json::object()).value(reason, 0);
  };
  EXPECT_GT(count("state", "not a finite number: pose.x_m"), 0) << rejected;
  EXPECT_GT(count("clock", "not a finite number: sim_time_s"), 0) << rejected;
  // Counted by reason class (a flood of distinct ids is one entry), with the first reasons kept.
  EXPECT_GT(count("state",
                  "robot # is not in this fleet of # robots (check --agents on every "
                  "process of the run)"),
            0)
      << rejected;
  EXPECT_THAT(j["rejected_examples"].dump(), HasSubstr("robot 4000 is not in this fleet of 20"));
  EXPECT_EQ(j["robots_goal_unverified"], nlohmann::json::array({3}));
  EXPECT_EQ(j["robots_off_goal"], nlohmann::json::array());
  const auto csv = slurp(out / "states.csv");
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  EXPECT_EQ(csv.find(",4000,"), std::string::npos);
  EXPECT_EQ(sim.wait(30s).value_or(-1), 0);
  std::filesystem::remove_all(out);  // it was left in the temporary folder after every run
}

}  // namespace
}  // namespace smart::test
