// Issue 25, the attacks of an intruder that reads the protocol (tests/support/intruder.hpp): it
// writes to the "smart.run.*" wildcard or to a run's exact partition, with the strongest
// ownership there is. Each case asserts the exact outcome: the run succeeds and the intruder is
// ignored, or the run fails naming it; never a false success, never a misleading cause.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>

#include "smart/dds/participant_directory.hpp"
#include "smart/dds/wire.hpp"
#include "support/intruder.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;
using ::testing::Not;

class Intrusion : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
  }
  // `smart COMMAND` on the 20-robot example, with its log in the output.
  std::vector<std::string> args(const std::string& command, int domain,
                                std::vector<std::string> extra = {}) const {
    std::vector<std::string> a = {command,
                                  "--map",
                                  (b_ / "maps/random-32-32-20.map").string(),
                                  "--scen",
                                  (b_ / "scens/random-32-32-20-random-1.scen").string(),
                                  "--domain",
                                  std::to_string(domain)};
    if (command != "sim") {
      a.insert(a.end(), {"--plan", (b_ / "smart-examples/example_paths_xy.txt").string(), "--axis",
                         "xy", "--no-progress"});
    }
    if (std::find(extra.begin(), extra.end(), "--agents") == extra.end()) {
      a.insert(a.end(), {"--agents", "20"});
    }
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  static std::string guid_of(const Intruder& in) {
    dds_guid_t g;
    EXPECT_EQ(dds_get_guid(in.participant().handle(), &g), DDS_RETCODE_OK);
    return dds::guid_prefix(g);
  }
  static smart_msg_MonitorInfo claim(uint64_t monitor_id, uint64_t run_id) {
    smart_msg_MonitorInfo m{};
    m.monitor_id = monitor_id;
    m.run_id = run_id;
    std::snprintf(m.host, sizeof(m.host), "%s", "intruder");
    m.pid = 4242;
    m.strength = smart_msg_MONITOR_STRENGTH_RESUME - 1;  // outranks any monitor started later
    return m;
  }
  std::filesystem::path b_;
};

// A stronger SimStatus writer hid the sim's status, and the run ended `success: true` while the
// sim's own report counted 7 robot and 1 wall collisions. Now the monitor hears the sim host's
// status alone (a writer admission): the run gets the sim's word and names the intruder.
TEST_F(Intrusion, AStrongerSimStatusWriterHidesNothingAndIsNamed) {
  const int d = kIntruderSimStatus;
  dds::Domain domain(d, loopback());
  Intruder in(domain);
  dds::WireWriter<smart_msg_SimStatus> status(in.participant(), in.qos(), Intruder::kStrongest);
  in.start([&](Intruder& i) {
    status.write(
        smart_msg_SimStatus{dds::kSimClockSource, i.run_id(), 1.0, 20, 7, 1, 0.5, 0.1, 10.0, 2, 3});
  });
  const auto r = run_smart(args("run", d), 120s, "intruder_status", true);
  in.stop();
  EXPECT_EQ(r.code, 0) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
  EXPECT_TRUE(j["sim_status_received"].get<bool>());
  EXPECT_EQ(j["collisions"], 0);  // the sim's count, not the intruder's 7
  EXPECT_EQ(j["wall_contacts"], 0);
  ASSERT_EQ(j["suspected_intruders"].size(), 1u) << j.dump();
  EXPECT_THAT(j["suspected_intruders"][0]["sender"].get<std::string>(), HasSubstr(guid_of(in)));
  EXPECT_GT(j["suspected_intruders"][0]["samples"]["sim_status"].get<int>(), 0);
  EXPECT_THAT(j["suspected_intruders"][0]["first_reason"].get<std::string>(),
              HasSubstr("not this run's sim host"));
}

// One MonitorInfo written once into the wildcard partition, before any run, made every run on
// the domain refuse itself; written once into a run's own partition it is no monitor either.
TEST_F(Intrusion, OneMonitorAnnouncementInTheWildcardOrWrittenOnceRefusesNoRun) {
  const int d = kIntruderMonitorInfo;
  dds::Domain domain(d, loopback());
  Intruder wildcard(domain), exact(domain, "named");
  dds::WireWriter<smart_msg_MonitorInfo> everywhere(wildcard.participant(), wildcard.qos(), 0);
  dds::WireWriter<smart_msg_MonitorInfo> once(exact.participant(), exact.qos(), 0);
  everywhere.write(claim(11, 1));
  once.write(claim(12, 1));
  const auto r = run_smart(args("run", d, {"--run", "named"}), 120s, "intruder_info", true);
  EXPECT_EQ(r.code, 0) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
  // `smart run` keys its run: neither announcement is a member's, both are named and ignored.
  for (const auto* who : {&wildcard, &exact}) {
    EXPECT_THAT(r.out, HasSubstr("on run 'named' from participant " + guid_of(*who)));
  }
  EXPECT_THAT(r.out, HasSubstr("ignored: not a member of this run"));
  EXPECT_THAT(r.out, Not(HasSubstr("refused, this monitor keeps")));
  EXPECT_THAT(r.out, Not(HasSubstr("is already owned by")));
}

// The same announcement, repeated as a live monitor would, mid-run: the run's monitor owns the
// run and keeps it.
TEST_F(Intrusion, AClaimThatAppearsMidRunNeverStopsTheRunItsMonitorOwns) {
  const int d = kIntruderMidRun;
  dds::Domain domain(d, loopback());
  Intruder in(domain, "owned");
  dds::WireWriter<smart_msg_MonitorInfo> claims(in.participant(), in.qos(), 0);
  std::atomic<int> claims_sent{0};
  in.start([&](Intruder& i) {
    if (const auto run = i.run_id()) {
      claims.write(claim(13, run));
      ++claims_sent;
    }
  });
  const auto r = run_smart(args("run", d, {"--run", "owned", "--real-time-factor", "40"}), 120s,
                           "intruder_midrun", true);
  in.stop();
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(last_json_line(r.out)["success"].get<bool>());
  EXPECT_GT(claims_sent.load(), 1) << "the intruder never claimed the run";
  EXPECT_THAT(r.out, HasSubstr("on run 'owned' from participant " + guid_of(in) +
                               " ignored: not a member of this run"));
}

// `smart monitor --resume` of another plan ended both runs.
TEST_F(Intrusion, AResumeWhileTheRunsMonitorLivesIsRefusedAndTheRunGoesOn) {
  const int d = kIntruderResume;
  dds::Domain domain(d, loopback());
  Intruder spy(domain, "default");
  const auto first_out = temp_file("intruder_resume_first.out");
  auto first = start_smart(args("monitor", d), first_out);
  auto sim = start_smart(args("sim", d, {"--real-time-factor", "40"}),
                         temp_file("intruder_resume_sim.out"));
  while (spy.run_id() == 0) {
    ASSERT_TRUE(first.running()) << slurp(first_out);
    std::this_thread::sleep_for(10ms);
  }
  const auto resume = run_smart(args("monitor", d, {"--resume", "--agents", "10"}), 60s,
                                "intruder_resume_second", true);
  EXPECT_EQ(resume.code, 1) << resume.out;
  EXPECT_EQ(last_json_line(resume.out)["outcome"], "refused");
  EXPECT_THAT(resume.out, HasSubstr("which is alive; --resume takes over only a run whose "
                                    "monitor stopped"));
  ASSERT_EQ(first.wait(120s).value_or(-1), 0) << slurp(first_out);
  EXPECT_TRUE(summary_in(slurp(first_out))["success"].get<bool>());
  EXPECT_EQ(sim.wait(30s).value_or(-1), 0);
}

// A tick from a second sim at the strongest strength took the clock's instance: the real sim
// went unheard and the run stalled, blamed on "the sim host went silent".
TEST_F(Intrusion, ASecondSimsStrongestTicksSilenceNothingAndAreNamed) {
  const int d = kIntruderTicks;
  dds::Domain domain(d, loopback());
  Intruder in(domain);
  dds::WireReader<smart_msg_Clock> answers(in.participant(), in.qos());
  dds::WireWriter<smart_msg_Clock> ticks(in.participant(), in.qos(), Intruder::kStrongest);
  bool answered = false;  // the monitor answered the real sim's first tick: it is the run's sim
  uint64_t tick = 1;
  in.start([&](Intruder& i) {
    answers.take_each([&](const smart_msg_Clock& c) {
      answered = answered || c.source_id == dds::kMonitorClockSource;
    });
    if (!answered) return;
    ticks.write(smart_msg_Clock{dds::kSimClockSource, i.run_id(), tick++, 0.1, 0, false});
  });
  const auto r =
      run_smart(args("run", d, {"--real-time-factor", "40"}), 120s, "intruder_ticks", true);
  in.stop();
  EXPECT_EQ(r.code, 0) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
  EXPECT_GT(tick, 1u) << "the intruder never ticked";
  ASSERT_EQ(j["suspected_intruders"].size(), 1u) << j.dump();
  EXPECT_THAT(j["suspected_intruders"][0]["sender"].get<std::string>(), HasSubstr(guid_of(in)));
  EXPECT_GT(j["suspected_intruders"][0]["samples"]["clock"].get<int>(), 0);
}

// A strength-0 progress writer that matched and left ended a lock-step run ("the sim host
// left").
TEST_F(Intrusion, AWriterThatMatchesAndLeavesEndsNoLockstepRun) {
  const int d = kIntruderLeaves;
  dds::Domain domain(d, loopback());
  Intruder spy(domain);
  auto run =
      start_smart(args("run", d, {"--real-time-factor", "40"}), temp_file("intruder_leaves.out"));
  while (spy.run_id() == 0) {
    ASSERT_TRUE(run.running()) << "the run ended before its first window";
    std::this_thread::sleep_for(10ms);
  }
  {
    Intruder passer(domain);
    dds::WireWriter<smart_msg_Progress> writer(passer.participant(), passer.qos(), 0);
    ASSERT_TRUE(writer.wait_for_readers(1, 30s)) << "the monitor's progress reader never matched";
  }  // it leaves
  ASSERT_EQ(run.wait(120s).value_or(-1), 0) << slurp(temp_file("intruder_leaves.out"));
  const auto j = summary_in(slurp(temp_file("intruder_leaves.out")));
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
}

// Forged windows (every robot, a higher run id) and a clock stop with the run's id, from the
// strongest writer there is: a window with a higher run id reset the sim host's run, a window
// copy then a clock stop ended the sim. `smart run` keys its run (smart/wire/run_proof.hpp): the
// sim host hears windows and answers only from the run's proven monitor, and counts the rest.
TEST_F(Intrusion, ForgedWindowsAndAClockStopFromTheStrongestWriterMoveAndStopNothing) {
  const int d = kIntruderWindows;
  dds::Domain domain(d, loopback());
  Intruder in(domain);
  dds::WireWriter<smart_msg_ActionWindow> windows(in.participant(), in.qos(), Intruder::kStrongest);
  dds::WireWriter<smart_msg_Clock> stops(in.participant(), in.qos(), Intruder::kStrongest);
  std::atomic<int> sent{0};
  in.start([&](Intruder& i) {
    const auto run = i.run_id();
    if (run == 0) return;
    for (uint32_t r = 0; r < 20; ++r) windows.write(smart_msg_ActionWindow{r, run + 1, 1, {}});
    stops.write(smart_msg_Clock{dds::kMonitorClockSource, run, 1u << 30, 0.0, 0, true});
    ++sent;
  });
  const auto out = temp_file("intruder_windows");
  std::filesystem::remove_all(out);
  const auto r = run_smart(args("run", d, {"--real-time-factor", "40", "--out", out.string()}),
                           120s, "intruder_windows", true);
  in.stop();
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_GT(sent.load(), 1) << "the intruder never wrote";
  const auto j = last_json_line(r.out);
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
  EXPECT_TRUE(j["robots_off_goal"].empty()) << j["robots_off_goal"];
  const auto sim = nlohmann::json::parse(slurp(out / "sim-0.json"));
  EXPECT_TRUE(sim["ok"].get<bool>()) << sim.dump();
  for (const char* topic : {"action", "clock"}) {
    const auto& reasons = sim["rejected_samples"][topic];
    ASSERT_TRUE(reasons.is_object()) << topic << ": " << sim.dump();
    EXPECT_GT(reasons.value(dds::kNotRunMember, 0), 0) << topic << ": " << sim.dump();
  }
  std::filesystem::remove_all(out);
}

// Forged progress (every robot finished its whole plan) and states (every robot in one spot)
// from the strongest writer, written before the sim host's own: the sender gate took the first
// writer as a robot's source and the monitor obeyed it. Now only the run's proven hosts are
// heard: the run succeeds on the sim's word and the summary names the intruder.
TEST_F(Intrusion, ForgedProgressAndStatesFromTheFirstAndStrongestWriterAreNeverObeyed) {
  const int d = kIntruderProgress;
  dds::Domain domain(d, loopback());
  Intruder in(domain);
  dds::WireWriter<smart_msg_Progress> progress(in.participant(), in.qos(), Intruder::kStrongest);
  dds::WireWriter<smart_msg_RobotState> states(in.participant(), in.qos(), Intruder::kStrongest);
  in.start([&](Intruder& i) {
    for (uint32_t r = 0; r < 20; ++r) {
      progress.write(smart_msg_Progress{r, i.run_id(), 10000, -1});
      smart_msg_RobotState s{};
      s.robot_id = r;
      s.run_id = i.run_id();
      s.pose = {1.0, 1.0, 0.0};
      states.write(s);
    }
  });
  const auto r =
      run_smart(args("run", d, {"--real-time-factor", "40"}), 120s, "intruder_progress", true);
  in.stop();
  EXPECT_EQ(r.code, 0) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_TRUE(j["success"].get<bool>()) << j["error"];
  EXPECT_EQ(j["collisions"], 0);
  ASSERT_EQ(j["suspected_intruders"].size(), 1u) << j.dump();
  const auto& suspect = j["suspected_intruders"][0];
  EXPECT_THAT(suspect["sender"].get<std::string>(), HasSubstr(guid_of(in)));
  EXPECT_GT(suspect["samples"]["progress"].get<int>(), 0) << suspect.dump();
  EXPECT_GT(suspect["samples"]["state"].get<int>(), 0) << suspect.dump();
  EXPECT_THAT(suspect["first_reason"].get<std::string>(), HasSubstr("not a member of this run"));
}

}  // namespace
}  // namespace smart::test
