// The fault cases under DDS Security (label faults): every process of the run has an identity
// from `smart security init`; a participant without one sees nothing and changes nothing, even
// writing at the strongest ownership strength; a viewer identity reads but cannot publish
// actions; the run gives the same numbers as without security.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <fstream>
#include <memory>
#include <thread>

#include "smart/dds/action_window.hpp"
#include "smart/dds/error.hpp"
#include "smart/dds/participant_directory.hpp"
#include "smart/dds/wire.hpp"
#include "smart/security/keystore.hpp"
#include "smart/wire/run_proof.hpp"
#include "support/forged_samples.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

class SecureFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    keystore_ = new std::filesystem::path(temp_file("keystore"));
    std::filesystem::remove_all(*keystore_);
    const auto r = run_smart(
        {"security", "init", "--out", keystore_->string(), "--agent-ids", "0-1", "--days", "2"},
        60s, "security_init");
    ASSERT_EQ(r.code, 0) << r.out;
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*keystore_);
    delete keystore_;
  }
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
  }
  std::vector<std::string> args(std::string command, int domain, bool plan, bool secure) const {
    std::vector<std::string> a{std::move(command),
                               "--map",
                               (b_ / "maps/random-32-32-20.map").string(),
                               "--scen",
                               (b_ / "scens/random-32-32-20-random-1.scen").string(),
                               "--agents",
                               "20",
                               "--domain",
                               std::to_string(domain)};
    if (plan) {
      a.insert(a.end(), {"--plan", (b_ / "smart-examples/example_paths_xy.txt").string(), "--axis",
                         "xy", "--no-progress"});
    }
    if (secure) a.insert(a.end(), {"--security", keystore_->string()});
    return a;
  }
  static std::filesystem::path* keystore_;
  std::filesystem::path b_;
};
std::filesystem::path* SecureFaults::keystore_ = nullptr;

TEST_F(SecureFaults, KeystoreHoldsEveryRoleAndItsPermissionsAreSigned) {
  for (const char* id : {"monitor", "sim", "viewer", "agent-0", "agent-1"}) {
    EXPECT_NO_THROW((void)security::identity_files(*keystore_, id)) << id;
  }
  EXPECT_THROW((void)security::identity_files(*keystore_, "agent-7"), config::ConfigError);
  const auto p7s = slurp(*keystore_ / "viewer" / "permissions.p7s");
  EXPECT_THAT(p7s, ::testing::HasSubstr("application/x-pkcs7-signature"));
  EXPECT_THAT(p7s, ::testing::HasSubstr("<subject_name>CN=viewer,O=SMART-DDS</subject_name>"));
}

// A rogue without an identity, writing at the strongest strength (which, without security,
// hides robot 3's states: untrusted_samples_test) states, stops, windows, progress for every
// robot and a collision report, and reading: it sees nothing, changes nothing, and the secured
// run's numbers equal the unsecured run's.
TEST_F(SecureFaults, AParticipantWithoutIdentitySeesNothingAndChangesNothing) {
  const int d = kSecureRogue;
  dds::Domain domain(d, loopback());
  dds::Participant rogue_p(domain);
  const auto qos = dds::find_qos_profile("lan");
  dds::WireWriter<smart_msg_RobotState> states(rogue_p, qos, dds::kMonitorStrengthResume);
  dds::WireWriter<smart_msg_Clock> clocks(rogue_p, qos, dds::kMonitorStrengthResume);
  dds::WireWriter<smart_msg_ActionWindow> windows(rogue_p, qos, dds::kMonitorStrengthResume);
  dds::WireWriter<smart_msg_Progress> progress(rogue_p, qos, dds::kMonitorStrengthResume);
  dds::WireWriter<smart_msg_SimStatus> status(rogue_p, qos, dds::kMonitorStrengthResume);
  dds::WireReader<smart_msg_RobotState> spy(rogue_p, qos);
  std::atomic<bool> done{false};
  std::atomic<std::size_t> seen{0};
  std::thread rogue([&] {
    while (!done) {
      smart_msg_RobotState s{};
      s.robot_id = 3;
      s.pose = {5.0, 5.0, 0.0};
      states.write(s);
      clocks.write(smart_msg_Clock{dds::kMonitorClockSource, 0, 0, 0.0, 0, true});
      auto w = forged_window(0);
      windows.write(w.view());
      for (uint32_t r = 0; r < 20; ++r) progress.write(smart_msg_Progress{r, 0, 1000, -1});
      status.write(smart_msg_SimStatus{dds::kSimClockSource, 0, 1.0, 20, 9, 0, 0.0, 0, 0, 1, 2});
      // Its own samples come back (local delivery); any other is the fleet's.
      spy.take_each([&](const smart_msg_RobotState& m) {
        if (m.robot_id != 3 || m.pose.x_m != 5.0) ++seen;
      });
      std::this_thread::sleep_for(10ms);
    }
  });
  auto sim = start_smart(args("sim", d, false, true), temp_file("secure_sim.out"));
  const auto r = run_smart(args("monitor", d, true, true), 120s, "secure_monitor");
  done = true;
  rogue.join();
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(sim.wait(30s).value_or(-1), 0);
  EXPECT_EQ(seen.load(), 0u) << "an unauthenticated participant read the fleet's states";
  const auto secured = r.last_json();
  EXPECT_EQ(secured["robots_goal_unverified"], nlohmann::json::array());
  const auto plain = run_smart(args("run", kSecurePlain, true, false), 120s, "secure_plain");
  ASSERT_EQ(plain.code, 0) << plain.out;
  for (const char* key : {"success", "aet_s", "makespan_s", "sim_time_s", "finished_actions",
                          "collisions", "stops", "waiting_time_s"}) {
    EXPECT_EQ(secured[key], plain.last_json()[key]) << key;
  }
}

TEST_F(SecureFaults, AViewerReadsTheFleetButCannotPublishActions) {
  const int d = kSecureViewer;
  auto config = loopback();
  config.security = security::identity_files(*keystore_, "viewer");
  dds::Domain domain(d, config);
  dds::Participant viewer(domain);
  const auto qos = dds::find_qos_profile("lan");
  EXPECT_THROW(dds::WireWriter<smart_msg_ActionWindow>(viewer, qos, dds::kMonitorStrengthResume),
               dds::Error);
  dds::WireReader<smart_msg_RobotState> states(viewer, qos);
  auto sim = start_smart(args("sim", d, false, true), temp_file("viewer_sim.out"));
  const auto r = run_smart(args("monitor", d, true, true), 120s, "viewer_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(r.last_json()["success"].get<bool>());
  EXPECT_GT(states.take_each([](const smart_msg_RobotState&) {}), 0u);
  EXPECT_EQ(sim.wait(30s).value_or(-1), 0);
}

// `smart serve --watch --security`: the watch's participant has the viewer identity and sees a
// secured run in its random partition; the run is undisturbed.
TEST_F(SecureFaults, TheWatchSeesASecuredRunAsTheViewer) {
  const int d = kSecureWatch;
  const auto out = temp_file("secure_watch.out");
  const auto data = temp_file("secure_watch_data");
  auto watch = start_smart({"serve", "--watch", "--port", "0", "--data", data.string(), "--domain",
                            std::to_string(d), "--security", keystore_->string()},
                           out);
  const int port = serve_port(watch, out);
  ASSERT_NE(port, 0) << slurp(out);
  auto run = args("run", d, true, true);
  run.insert(run.end(), {"--clock", "realtime", "--max-sim-time-s", "8"});
  auto monitor = start_smart(run, temp_file("secure_watch_run.out"));
  std::size_t seen = 0;
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(60, 0);
  // Until the watch sees the fleet or the run is over (a loaded machine may take longer than any
  // guessed bound to finish the secure handshakes); the deadline only catches a hang.
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (seen < 20 && monitor.running() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(100ms);
    const auto r = client.Get("/api/watch");
    if (r && r->status == 200) seen = nlohmann::json::parse(r->body)["robots"].size();
  }
  EXPECT_EQ(seen, 20u) << slurp(out);
  EXPECT_TRUE(monitor.wait(60s).has_value());
  std::filesystem::remove_all(data);
}

// Under --security the keystore's agent-1 identity drove the progress and states of every robot
// (7 collisions). Its permissions now grant robot 1's partition only: it cannot write in the
// run's own partition nor in another robot's, and what it writes in its own partition for other
// robots, at the strongest strength, is refused in the monitor's receive path without seizing
// their instances. It holds the run key too (an insider of a mixed run): nothing else stops it.
TEST_F(SecureFaults, AnAgentKeyWritesOnlyItsOwnRobotsProgressAndStates) {
  const int d = kSecureInsider;
  const auto key_file = temp_file("insider.key");
  std::ofstream(key_file) << "00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff\n";
  auto config = loopback();
  config.security = security::identity_files(*keystore_, "agent-1");
  dds::Domain domain(d, config);
  dds::Participant insider(domain, "insider");
  insider.prove(wire::parse_run_key(slurp(key_file), key_file.string()), "agent");
  const auto qos = dds::find_qos_profile("lan");
  EXPECT_THROW(dds::WireWriter<smart_msg_Progress>(insider, qos), dds::Error);
  EXPECT_THROW((dds::WireWriter<smart_msg_Progress>(insider, qos, std::vector<uint32_t>{0})),
               dds::Error);
  const auto own = [&](auto sample) {  // a writer in robot 1's partition, strongest
    using T = decltype(sample);
    auto q = dds::wire_qos<T>(insider, qos, 2147483647);
    q.partitions({insider.robot_partition(1)});
    return std::make_pair(
        std::make_unique<dds::Topic<T>>(insider, std::string(dds::WireTopic<T>::name)), q);
  };
  auto [progress_topic, progress_qos] = own(smart_msg_Progress{});
  dds::Writer<smart_msg_Progress> progress(insider, *progress_topic, progress_qos);
  auto [state_topic, state_qos] = own(smart_msg_RobotState{});
  dds::Writer<smart_msg_RobotState> states(insider, *state_topic, state_qos);
  std::atomic<bool> done{false};
  std::thread attack([&] {
    while (!done) {
      for (uint32_t r = 0; r < 20; ++r) {
        if (r == 1) continue;  // its own robot it may speak for
        progress.write(smart_msg_Progress{r, 0, 10000, -1});
        smart_msg_RobotState s{};
        s.robot_id = r;
        s.pose = {1.0, 1.0, 0.0};
        states.write(s);
      }
      std::this_thread::sleep_for(10ms);
    }
  });
  auto a = args("run", d, true, true);
  a.insert(a.end(),
           {"--run", "insider", "--run-key", key_file.string(), "--real-time-factor", "40"});
  const auto r = run_smart(a, 120s, "secure_insider", true);
  done = true;
  attack.join();
  std::filesystem::remove(key_file);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
  EXPECT_EQ(j["collisions"], 0);
  dds_guid_t g;
  ASSERT_EQ(dds_get_guid(insider.handle(), &g), DDS_RETCODE_OK);
  ASSERT_EQ(j["suspected_intruders"].size(), 1u) << j.dump();
  const auto& suspect = j["suspected_intruders"][0];
  EXPECT_THAT(suspect["sender"].get<std::string>(), HasSubstr(dds::guid_prefix(g)));
  EXPECT_GT(suspect["samples"]["progress"].get<int>(), 0) << suspect.dump();
  EXPECT_GT(suspect["samples"]["state"].get<int>(), 0) << suspect.dump();
  EXPECT_THAT(suspect["first_reason"].get<std::string>(), HasSubstr("robot(s) 1 only"));
}

}  // namespace
}  // namespace smart::test
