// Issue 25, the attacks of an intruder that reads the protocol (tests/support/intruder.hpp): it
// writes to the "smart.run.*" wildcard or to a run's exact partition, with the strongest
// ownership there is. Each case asserts the exact outcome: the run succeeds and the intruder is
// ignored, or the run fails naming it; never a false success, never a misleading cause.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
    if (!std::filesystem::exists(b_)) GTEST_SKIP() << "no benchmark data at " << b_;
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
  EXPECT_THAT(r.out, HasSubstr("ignored: written to partitions other than exactly this run's "
                               "'smart.run.named'"));
  EXPECT_THAT(r.out, HasSubstr(guid_of(wildcard)));
  EXPECT_THAT(r.out, Not(HasSubstr("refused")));
}

// The same announcement, repeated as a live monitor would, mid-run: the run's monitor owns the
// run and keeps it.
TEST_F(Intrusion, AClaimThatAppearsMidRunNeverStopsTheRunItsMonitorOwns) {
  const int d = kIntruderMidRun;
  dds::Domain domain(d, loopback());
  Intruder in(domain, "owned");
  dds::WireWriter<smart_msg_MonitorInfo> claims(in.participant(), in.qos(), 0);
  in.start([&](Intruder& i) {
    if (const auto run = i.run_id()) claims.write(claim(13, run));
  });
  const auto r = run_smart(args("run", d, {"--run", "owned", "--real-time-factor", "40"}), 120s,
                           "intruder_midrun", true);
  in.stop();
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(last_json_line(r.out)["success"].get<bool>());
  EXPECT_THAT(r.out, HasSubstr("a second monitor on host intruder (pid 4242"));
  EXPECT_THAT(r.out, HasSubstr("joined run 'owned'; it is refused, this monitor keeps the fleet"));
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

}  // namespace
}  // namespace smart::test
