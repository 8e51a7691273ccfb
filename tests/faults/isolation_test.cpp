// Concurrent runs on one DDS domain never interfere: each run lives in its own partition
// (idl/smart.idl, "Runs"). Real processes on loopback.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

class Isolation : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
  }
  std::vector<std::string> random_map(int domain, const std::string& agents) const {
    return {"--map",        (b_ / "maps/random-32-32-20.map").string(),
            "--scen",       (b_ / "scens/random-32-32-20-random-1.scen").string(),
            "--plan",       (b_ / "smart-examples/example_paths_xy.txt").string(),
            "--axis",       "xy",
            "--agents",     agents,
            "--domain",     std::to_string(domain),
            "--no-progress"};
  }
  static std::vector<std::string> with(std::string command, std::vector<std::string> args) {
    args.insert(args.begin(), std::move(command));
    return args;
  }
  std::filesystem::path b_;
};

void expect_same_run(const nlohmann::json& a, const nlohmann::json& b) {
  for (const char* key : {"success", "robots", "aet_s", "makespan_s", "sim_time_s", "collisions",
                          "finished_actions", "min_separation_m", "rejected_progress"}) {
    EXPECT_EQ(a[key], b[key]) << key;
  }
}

TEST_F(Isolation, TwoRunsAtOnceOnOneDomainGiveWhatEachGivesAlone) {
  const int d = kIsolationTwoRuns;
  const auto alone_a = run_smart(with("run", random_map(d, "40")), 120s, "iso_alone_a");
  const auto alone_b = run_smart(with("run", random_map(d, "25")), 120s, "iso_alone_b");
  ASSERT_EQ(alone_a.code, 0) << alone_a.out;
  ASSERT_EQ(alone_b.code, 0) << alone_b.out;
  const auto out_a = temp_file("iso_a.out"), out_b = temp_file("iso_b.out");
  auto a = start_smart(with("run", random_map(d, "40")), out_a);
  auto b = start_smart(with("run", random_map(d, "25")), out_b);
  const auto rc_a = a.wait(120s), rc_b = b.wait(120s);
  const auto text_a = slurp(out_a), text_b = slurp(out_b);
  ASSERT_EQ(rc_a.value_or(-1), 0) << text_a;
  ASSERT_EQ(rc_b.value_or(-1), 0) << text_b;
  const auto ja = summary_in(text_a), jb = summary_in(text_b);
  expect_same_run(ja, alone_a.last_json());
  expect_same_run(jb, alone_b.last_json());
  EXPECT_NE(ja["run"], jb["run"]);
  EXPECT_THAT(ja["run"].get<std::string>(), HasSubstr("run-"));
}

TEST_F(Isolation, AMonitorAndASimOfDifferentRunsNeverMeet) {
  const int d = kIsolationNamedRuns;
  const auto sim_out = temp_file("iso_sim.out");
  auto sim = start_smart(
      with("sim", {"--map", (b_ / "maps/random-32-32-20.map").string(), "--scen",
                   (b_ / "scens/random-32-32-20-random-1.scen").string(), "--agents", "10",
                   "--domain", std::to_string(d), "--run", "experiment-b", "--timeout-s", "20"}),
      sim_out);
  auto args = with("monitor", random_map(d, "10"));
  args.insert(args.end(), {"--run", "experiment-a", "--timeout-s", "3"});
  const auto r = run_smart(args, 60s, "iso_monitor");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("\"sim_lost\": true"));
  // The same sim, joined under its own run name, serves a monitor of that run.
  args = with("monitor", random_map(d, "10"));
  args.insert(args.end(), {"--run", "experiment-b"});
  const auto ok = run_smart(args, 60s, "iso_monitor_b");
  EXPECT_EQ(ok.code, 0) << ok.out;
  EXPECT_EQ(ok.last_json()["run"], "experiment-b");
  EXPECT_EQ(sim.wait(30s).value_or(-1), 0);
}

TEST_F(Isolation, ARunNameOutsideTheAllowedCharactersIsBadInput) {
  auto args = with("run", random_map(kIsolationBadName, "5"));
  args.insert(args.end(), {"--run", "a b"});
  const auto r = run_smart(args, 30s, "iso_bad_name");
  EXPECT_EQ(r.code, 2);
}

}  // namespace
}  // namespace smart::test
