// Real processes, real DDS traffic on loopback: the `smart` executable on the other side.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "smart/common/child_process.hpp"
#include "smart/dds/action_window.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/dds/writer.hpp"
#include "support/dds_test_support.hpp"

namespace smart::dds {
namespace {

using namespace std::chrono_literals;
using common::ChildProcess;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CrossProcess, EchoAnswersEveryTopicType) {
  const int domain_id = test::kCrossProcessEcho;
  ChildProcess echo({test::smart_exe().string(), "dds-echo", "--domain", std::to_string(domain_id),
                     "--duration-s", "60"});
  Domain domain(domain_id, test::loopback());
  Participant p(domain);
  const auto profile = find_qos_profile("lan");
  WireWriter<smart_msg_ActionWindow> actions(p, profile);
  WireWriter<smart_msg_Clock> clock_out(p, profile);
  WireReader<smart_msg_Progress> progress(p, profile);
  WireReader<smart_msg_RobotState> states(p, profile);
  WireReader<smart_msg_Clock> clocks(p, profile);
  ASSERT_TRUE(actions.wait_for_readers(1, 10s)) << "dds-echo did not join domain " << domain_id;
  ASSERT_TRUE(clock_out.wait_for_readers(2, 10s));  // our own reader and the echo's
  ASSERT_TRUE(states.wait_for_writers(1, 10s));

  constexpr uint32_t kRobots = 20;
  for (uint32_t robot = 0; robot < kRobots; ++robot) {
    ActionWindowBuffer w(robot, 5, 8);
    for (uint32_t k = 0; k < 2; ++k) {
      smart_msg_ActionStep s{};
      s.seq = k;
      s.to.x_m = robot + 0.5 * k;
      s.heading_rad = 0.25;
      w.steps().push_back(s);
    }
    actions.write(w.view());
  }
  clock_out.write(smart_msg_Clock{0, 5, 17, 1.7, 0, false});

  std::set<uint32_t> progressed, stated;
  bool clock_answered = false;
  WaitSet ws(p);
  ws.attach_status(progress.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  ws.attach_status(states.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  ws.attach_status(clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 3);
  const auto deadline = std::chrono::steady_clock::now() + 15s;
  while ((progressed.size() < kRobots || !clock_answered) &&
         std::chrono::steady_clock::now() < deadline) {
    ws.wait(100ms);
    progress.take_each([&](const smart_msg_Progress& m) {
      EXPECT_EQ(m.run_id, 5u);
      EXPECT_EQ(m.finished_seq, 1);
      progressed.insert(m.robot_id);
    });
    states.take_each([&](const smart_msg_RobotState& m) {
      EXPECT_DOUBLE_EQ(m.pose.x_m, m.robot_id + 0.5);
      EXPECT_DOUBLE_EQ(m.pose.yaw_rad, 0.25);
      stated.insert(m.robot_id);
    });
    clocks.take_each([&](const smart_msg_Clock& c) {
      if (c.source_id == 1 && c.tick == 17) clock_answered = true;
    });
  }
  EXPECT_EQ(progressed.size(), kRobots);
  EXPECT_TRUE(clock_answered);
  EXPECT_GT(stated.size(), 0u);  // best effort: most, not necessarily all
  EXPECT_TRUE(echo.running());
  EXPECT_EQ(echo.terminate(), 0) << "dds-echo must exit cleanly on SIGTERM";
}

TEST(CrossProcess, PingWithSpawnedEchoReportsRoundTrips) {
  const auto out = test::temp_file("ping.json");
  ChildProcess ping({test::smart_exe().string(), "dds-ping", "--spawn-echo", "--robots", "200",
                     "--rounds", "5", "--domain", std::to_string(test::kCrossProcessPing)},
                    out);
  const auto rc = ping.wait(60s);
  ASSERT_TRUE(rc.has_value()) << "dds-ping hung";
  ASSERT_EQ(*rc, 0) << slurp(out);
  const auto j = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(j["robots"], 200);
  EXPECT_EQ(j["rounds"], 5);
  EXPECT_EQ(j["clock_replies"], 5);
  EXPECT_GE(j["progress_samples"].get<int>(), 200 * 5);
  EXPECT_GT(j["round_trip_ms"]["median"].get<double>(), 0.0);
  std::filesystem::remove(out);
}

// Receives `dds-send` bursts from a process whose profile drops 20 % of its sent packets.
std::set<uint32_t> receive_lossy_burst(int domain_id, const std::string& reliability,
                                       uint32_t count, int* exit_code) {
  const auto out = test::temp_file("send_" + reliability + ".json");
  Domain domain(domain_id, test::loopback());
  Participant p(domain);
  Topic<smart_msg_Progress> t(p, std::string(kProgressTopic));
  TopicQos q = default_qos_profile().progress;
  q.reliability = reliability == "reliable" ? Reliability::kReliable : Reliability::kBestEffort;
  q.history = HistoryKind::kKeepAll;
  Reader<smart_msg_Progress> r(p, t, q.to_dds().partition(p.run_partition()));
  ChildProcess sender({test::smart_exe().string(), "dds-send", "--qos", "protocol-loss-test", "--domain",
                       std::to_string(domain_id), "--reliability", reliability, "--count",
                       std::to_string(count), "--interval-ms", "2"},
                      out);
  std::set<uint32_t> got;
  WaitSet ws(p);
  ws.attach_status(r.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  std::optional<int> rc;
  const auto deadline = std::chrono::steady_clock::now() + 40s;
  while (std::chrono::steady_clock::now() < deadline) {
    ws.wait(50ms);
    r.take_each([&](const smart_msg_Progress& m) { got.insert(m.robot_id); });
    if (!rc) rc = sender.wait(0ms);
    if (rc && got.size() == count) break;
    if (rc) {  // sender finished: drain what is still in flight, then stop
      ws.wait(300ms);
      r.take_each([&](const smart_msg_Progress& m) { got.insert(m.robot_id); });
      break;
    }
  }
  *exit_code = rc.value_or(-1);
  std::filesystem::remove(out);
  return got;
}

// Regression: with loopback discovery only 61 processes of a domain fitted on one host (each
// takes a participant index, Cyclone's MaxAutoParticipantIndex was 60); the 62nd failed to
// create its domain, so a fleet of 100 agent processes on one machine could not join a run.
TEST(CrossProcess, AHundredProcessesJoinOneDomainOnOneHost) {
  std::vector<ChildProcess> echoes;
  for (int i = 0; i < 100; ++i) {
    echoes.emplace_back(
        std::vector<std::string>{test::smart_exe().string(), "dds-echo", "--domain",
                                 std::to_string(test::kManyProcesses), "--duration-s", "4"},
        "/dev/null");
  }
  int failed = 0;
  for (auto& e : echoes) failed += e.wait(60s * test::kSlowdown).value_or(-1) != 0;
  EXPECT_EQ(failed, 0) << "processes that could not join the domain";
}

TEST(LossyLink, ReliableDeliversEverySampleUnderTwentyPercentLoss) {
  int rc = -1;
  const auto got = receive_lossy_burst(test::kLossyReliable, "reliable", 400, &rc);
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(got.size(), 400u);
}

TEST(LossyLink, BestEffortLosesSamplesUnderTwentyPercentLoss) {
  int rc = -1;
  const auto got = receive_lossy_burst(test::kLossyBestEffort, "best_effort", 400, &rc);
  EXPECT_EQ(rc, 0);
  // 20 % of packets dropped and one sample per packet (2 ms apart): expect about 320. The bounds
  // are many standard deviations (sd = 8) wide so the test is not flaky, yet fail if the loss
  // model is off (400) or broken (0).
  EXPECT_LT(got.size(), 380u);
  EXPECT_GT(got.size(), 240u);
}

}  // namespace
}  // namespace smart::dds
