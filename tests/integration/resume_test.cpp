// A monitor that dies mid-run is replaced by `smart monitor --resume`: the run continues from the
// sim host's progress with no action lost or repeated, and in lock-step the fleet moves exactly
// as if nothing had happened.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <thread>

#include "support/fleet_watcher.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

class Resume : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
  }
  // 100 robots of SMART's warehouse plan: ~540 s of sim time, several seconds of wall time.
  std::vector<std::string> world_args() const {
    return {"--map",    (b_ / "maps/warehouse-10-20-10-2-1.map").string(),
            "--scen",   (b_ / "scens/warehouse-10-20-10-2-1-random-1.scen").string(),
            "--agents", "100"};
  }
  std::vector<std::string> monitor_args(int domain) const {
    auto a = world_args();
    a.insert(a.begin(), "monitor");
    a.insert(a.end(), {"--plan", (b_ / "smart-examples/scen_1_paths.txt").string(), "--axis",
                       "rowcol", "--domain", std::to_string(domain), "--no-progress"});
    return a;
  }
  std::filesystem::path b_;
};

TEST_F(Resume, AResumedMonitorFinishesTheRunExactlyAsAnUninterruptedOne) {
  // Reference: the same run without interruption.
  auto ref_args = monitor_args(kResumeReference);
  ref_args[0] = "run";
  const auto ref = run_smart(ref_args, 120s, "resume_reference");
  ASSERT_EQ(ref.code, 0) << ref.out;

  auto sim_args = world_args();
  sim_args.insert(sim_args.begin(), {smart_exe().string(), "sim"});
  sim_args.insert(sim_args.end(), {"--domain", std::to_string(kResume)});
  common::ChildProcess sim(sim_args, "/dev/null");
  auto first = start_smart(monitor_args(kResume), "/dev/null");
  // Kill the monitor once robots have progressed.
  FleetWatcher watcher(kResume);
  ASSERT_GE(watcher.wait_for_finished(20, 60s), 20) << "the run did not get under way";
  ASSERT_TRUE(first.running());
  first.signal(SIGKILL);
  ASSERT_TRUE(first.wait(5s).has_value());

  auto resume_args = monitor_args(kResume);
  resume_args.push_back("--resume");
  const auto r = run_smart(resume_args, 120s, "resume_second");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  const auto want = ref.last_json();
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["finished_actions"], j["total_actions"]);
  EXPECT_EQ(j["rejected_progress"], 0);
  EXPECT_EQ(j["collisions"], 0);
  ASSERT_TRUE(j.contains("resumed"));
  EXPECT_GT(j["resumed"]["finished_before"].get<int>(), 0);
  EXPECT_LT(j["resumed"]["finished_before"].get<int>(), j["total_actions"].get<int>());
  EXPECT_GT(j["resumed"]["at_s"].get<double>(), 0.0);
  // The sim waited for the new monitor and got the same windows: identical trajectories.
  EXPECT_EQ(j["sim_time_s"], want["sim_time_s"]);
  EXPECT_EQ(j["min_separation_m"], want["min_separation_m"]);
  // Finish times from before the resume are unknown: no AET if a robot was done by then; if
  // none was, every finish time is known and equal to the uninterrupted run's.
  if (j["resumed"]["robots_done_before"].get<int>() > 0) {
    EXPECT_TRUE(j["aet_s"].is_null());
  } else {
    EXPECT_EQ(j["aet_s"], want["aet_s"]);
  }
  ASSERT_EQ(sim.wait(10s).value_or(-1), 0) << "the sim host did not stop with the resumed run";
}

TEST_F(Resume, NothingToResumeIsAClearError) {
  auto args = monitor_args(kResumeNothing);
  args.insert(args.end(), {"--resume", "--timeout-s", "2"});
  const auto r = run_smart(args, 30s, "resume_nothing");
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.last_json()["error"].get<std::string>(), HasSubstr("cannot resume"));
}

}  // namespace
}  // namespace smart::test
