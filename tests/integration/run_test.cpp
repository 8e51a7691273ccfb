// `smart run`, `smart monitor` and `smart sim` as users run them: real processes, real DDS
// traffic on loopback, each test in its own domain.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <thread>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

class Run : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
  }
  std::vector<std::string> example_args(int domain, const std::string& agents = "50") {
    return {"--map",        (b_ / "maps/random-32-32-20.map").string(),
            "--scen",       (b_ / "scens/random-32-32-20-random-1.scen").string(),
            "--plan",       (b_ / "smart-examples/example_paths_xy.txt").string(),
            "--axis",       "xy",
            "--agents",     agents,
            "--domain",     std::to_string(domain),
            "--no-progress"};
  }
  // 100 robots of SMART's warehouse plan: ~540 s of sim time. Unpaced it can now end in under
  // 4 s, so the tests that kill a process once its first action has finished pace the sim to 20x
  // real time (about 27 s): the process dies mid-run however fast the machine.
  std::vector<std::string> long_run_args(int domain) {
    return {"--map",        (b_ / "maps/warehouse-10-20-10-2-1.map").string(),
            "--scen",       (b_ / "scens/warehouse-10-20-10-2-1-random-1.scen").string(),
            "--plan",       (b_ / "smart-examples/scen_1_paths.txt").string(),
            "--axis",       "rowcol",
            "--agents",     "100",
            "--domain",     std::to_string(domain),
            "--no-progress"};
  }
  // 20 robots of the example with extra flags; the summary.
  nlohmann::json seeded_run(int domain, const std::vector<std::string>& flags,
                            const std::string& tag) {
    auto args = example_args(domain, "20");
    args.insert(args.begin(), "run");
    args.insert(args.end(), flags.begin(), flags.end());
    const auto r = run_smart(args, 120s, tag);
    EXPECT_EQ(r.code, 0) << r.out;
    return r.last_json();
  }
  std::filesystem::path b_;
};

TEST_F(Run, SmartExampleOnRandomMapSucceedsWithoutCollisionsAndWritesResults) {
  const auto out = temp_file("run_example");
  auto args = example_args(kRunExample);
  args.insert(args.begin(), "run");
  args.insert(args.end(), {"--out", out.string()});
  const auto r = run_smart(args, 120s, "run_example");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["robots"], 50);
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["finished_actions"], j["total_actions"]);
  // Success means success: every robot was seen at its goal after it finished.
  EXPECT_EQ(j["outcome"], "success");
  EXPECT_EQ(j["robots_off_goal"], nlohmann::json::array());
  EXPECT_EQ(j["robots_goal_unverified"], nlohmann::json::array());
  EXPECT_GT(j["aet_s"].get<double>(), 0);
  EXPECT_GE(j["makespan_s"].get<double>(), j["aet_s"].get<double>());
  EXPECT_GT(j["min_separation_m"].get<double>(), 0.0);
  EXPECT_EQ(j["plan"]["soc"], 1241.0);
  for (const char* key : {"sim_time_s", "wall_time_s", "sim_speed", "adg", "machine"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  // Both processes' peak memory: the monitor's own, the sim child's from wait4.
  EXPECT_GT(j["peak_rss_mb"]["monitor"].get<double>(), 5.0);
  EXPECT_GT(j["peak_rss_mb"]["sim"].get<double>(), 5.0);
  // CPU of both processes (the sim host is `smart run`'s child), for experiment figures.
  EXPECT_GT(j["cpu_s"]["monitor"].get<double>(), 0.0);
  EXPECT_GT(j["cpu_s"]["sim"].get<double>(), 0.0);
  EXPECT_GT(j["cpu_s_per_sim_s"].get<double>(), 0.0);
  // Files: the summary on disk equals the one printed; a SMART stats row; robot states.
  const auto disk = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(disk["aet_s"], j["aet_s"]);
  const auto stats = slurp(out / "stats.csv");
  EXPECT_THAT(stats, HasSubstr("steps finish sim,sum of steps finish sim,makespan sim s"));
  EXPECT_THAT(stats, HasSubstr(",50\n"));
  const auto states = slurp(out / "states.csv");
  EXPECT_THAT(states, HasSubstr("t_s,robot,x_m,y_m,yaw_rad"));
  EXPECT_GT(std::count(states.begin(), states.end(), '\n'), 50 * 10);
  const auto robots = slurp(out / "robots.csv");
  EXPECT_EQ(std::count(robots.begin(), robots.end(), '\n'), 51);  // header + 50 robots
  std::filesystem::remove_all(out);
}

// The second run is paced to 100x real time (--real-time-factor, to watch a run live): it takes
// at least the makespan / 100 of wall time (about 1.7 s; unpaced about 1 s) and gives the same
// numbers.
TEST_F(Run, LockStepRunsOfTheSamePlanGiveIdenticalNumbersPacedOrNot) {
  std::vector<nlohmann::json> results;
  for (int i = 0; i < 2; ++i) {
    auto args = example_args(kRunLockstep, "20");
    args.insert(args.begin(), "run");
    if (i == 1) args.insert(args.end(), {"--real-time-factor", "100"});
    const auto r = run_smart(args, 120s, "run_lockstep");
    ASSERT_EQ(r.code, 0) << r.out;
    results.push_back(r.last_json());
  }
  EXPECT_GE(results[1]["wall_time_s"].get<double>(), results[1]["makespan_s"].get<double>() / 100);
  for (const char* key : {"aet_s", "makespan_s", "sim_time_s", "collisions", "wall_contacts",
                          "min_separation_m", "stops", "waiting_time_s", "finished_actions"}) {
    EXPECT_EQ(results[0][key], results[1][key]) << key;
  }
}

TEST_F(Run, KillingTheSimHostMakesTheMonitorReportFailureInsteadOfHanging) {
  auto margs = long_run_args(kRunKillSim);
  margs.insert(margs.begin(), "monitor");
  const auto dir = temp_file("kill_monitor");
  margs.insert(margs.end(), {"--timeout-s", "3", "--out", dir.string()});
  const auto mout = temp_file("kill_monitor.out");
  auto monitor = start_smart(margs, mout);
  common::ChildProcess sim(
      {smart_exe().string(), "sim", "--map", (b_ / "maps/warehouse-10-20-10-2-1.map").string(),
       "--scen", (b_ / "scens/warehouse-10-20-10-2-1-random-1.scen").string(), "--agents", "100",
       "--domain", std::to_string(kRunKillSim), "--real-time-factor", "20"},
      "/dev/null");
  // The run is under way once an action has finished (a guessed 2.5 s before: on a loaded
  // machine the sim may not have joined by then).
  ASSERT_TRUE(wait_for_progress(monitor, dir)) << slurp(mout);
  ASSERT_TRUE(monitor.running());
  sim.signal(SIGKILL);
  const auto rc = monitor.wait(30s);
  ASSERT_TRUE(rc.has_value()) << "the monitor hung after the sim host died";
  EXPECT_EQ(*rc, 1);
  const auto j = summary_in(slurp(mout));
  EXPECT_FALSE(j["success"].get<bool>());
  EXPECT_TRUE(j["sim_lost"].get<bool>());
  EXPECT_THAT(j["error"].get<std::string>(), HasSubstr("sim host"));
  std::filesystem::remove(mout);
  std::filesystem::remove_all(dir);
}

// Regression: `smart run` noticed its own sim child had died only after --timeout-s of silence.
TEST_F(Run, SmartRunReportsItsDeadSimChildAtOnce) {
  auto args = long_run_args(kRunKillChild);
  args.insert(args.begin(), "run");
  const auto dir = temp_file("kill_child");
  args.insert(args.end(), {"--timeout-s", "60", "--real-time-factor", "20", "--out", dir.string()});
  const auto out = temp_file("kill_child.out");
  auto run = start_smart(args, out);
  ASSERT_TRUE(wait_for_progress(run, dir)) << slurp(out);  // under way: an action finished
  ASSERT_TRUE(run.running());
  // The sim is `smart run`'s only child.
  std::ifstream children("/proc/" + std::to_string(run.pid()) + "/task/" +
                         std::to_string(run.pid()) + "/children");
  pid_t sim = 0;
  ASSERT_TRUE(children >> sim) << "smart run has no child process";
  ASSERT_EQ(::kill(sim, SIGKILL), 0);
  const auto killed = std::chrono::steady_clock::now();
  const auto rc = run.wait(30s);
  ASSERT_TRUE(rc.has_value()) << "smart run hung after its sim child died";
  EXPECT_LT(std::chrono::steady_clock::now() - killed, 10s) << "not reported at once";
  EXPECT_EQ(*rc, 1);
  const auto j = summary_in(slurp(out));
  EXPECT_TRUE(j["sim_lost"].get<bool>());
  EXPECT_THAT(j["error"].get<std::string>(), HasSubstr("killed by signal 9"));
  std::filesystem::remove(out);
  std::filesystem::remove_all(dir);
}

// Regression: in a run short enough that the sim host's only status sample was its final one,
// read after the host had left, the monitor could not place that sample's writer and dropped
// it: no sim memory, no closest approach and, had there been one, no collision in the summary.
TEST_F(Run, AShortRunsOnlySimStatusIsTakenNotDropped) {
  auto args = example_args(kRunShortStatus, "2");
  args.insert(args.begin(), "run");
  const auto r = run_smart(args, 120s, "run_short_status");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_TRUE(j["peak_rss_mb"]["sim"].is_number()) << j.dump();
  EXPECT_TRUE(j["rejected_samples"].empty()) << j["rejected_samples"].dump();
}

// --state-rate-hz 0: no periodic states, yet every robot's final state verifies it at its goal;
// --stats FILE gains a row per run under one header.
TEST_F(Run, NoStatesButTheFinalOnesAndStatsAppendedPerRun) {
  const auto out = temp_file("run_no_states");
  const auto stats = temp_file("run_stats.csv");
  std::filesystem::remove_all(out);
  std::filesystem::remove(stats);
  for (int i = 0; i < 2; ++i) {
    auto args = example_args(kRunNoStates, "3");
    args.insert(args.begin(), "run");
    args.insert(args.end(),
                {"--state-rate-hz", "0", "--out", out.string(), "--stats", stats.string()});
    const auto r = run_smart(args, 120s, "run_no_states");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(r.last_json()["robots_goal_unverified"].empty()) << r.out;
  }
  std::ifstream states(out / "states.csv");
  std::size_t rows = 0;
  for (std::string line; std::getline(states, line);) ++rows;
  EXPECT_LE(rows, 1u + 3 * 2) << "header and the final state of each robot";
  const auto table = slurp(stats);
  EXPECT_EQ(table.find("steps finish sim,"), 0u);
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3) << table;
  EXPECT_NE(table.find("makespan sim s"), std::string::npos);
  std::filesystem::remove_all(out);
  std::filesystem::remove(stats);
}

// Seeded randomness in lock-step (execution uncertainty, the link model): `run` with seed 1
// twice and seed 2 gives the same summary for the same seed, another AET for another seed, and
// no collision (the ADG orders who passes where, not when). Returns the first run's summary.
nlohmann::json expect_seeded_and_collision_free(
    const std::function<nlohmann::json(const std::string&)>& run) {
  const auto a = run("1"), b = run("1"), c = run("2");
  EXPECT_TRUE(a["success"].get<bool>());
  EXPECT_EQ(a["collisions"], 0);
  EXPECT_EQ(c["collisions"], 0);
  EXPECT_EQ(a["aet_s"], b["aet_s"]);
  EXPECT_EQ(a["makespan_s"], b["makespan_s"]);
  EXPECT_NE(a["aet_s"], c["aet_s"]);
  return a;
}

TEST_F(Run, StallsAreSeededAndTheAdgKeepsTheRunCollisionFree) {
  const auto flags = [](const std::string& seed) {
    return std::vector<std::string>{"--stall-probability", "0.3", "--stall-s", "4",
                                    "--speed-sigma",       "0.1", "--seed",    seed};
  };
  const auto a = expect_seeded_and_collision_free(
      [&](const std::string& seed) { return seeded_run(kRunStalls, flags(seed), "run_stalls"); });
  EXPECT_EQ(a["uncertainty"]["seed"], 1);
  EXPECT_DOUBLE_EQ(a["uncertainty"]["stall_probability"].get<double>(), 0.3);
}

// The link model: 500 ms +- 200 ms each way.
TEST_F(Run, ADelayedLinkIsSeededAndTheRunStaysCollisionFree) {
  const auto flags = [](const std::string& seed) {
    return std::vector<std::string>{"--link-delay-ms", "500", "--link-jitter-ms", "200",
                                    "--link-seed",     seed};
  };
  const auto a = expect_seeded_and_collision_free(
      [&](const std::string& seed) { return seeded_run(kRunLink, flags(seed), "run_link"); });
  EXPECT_DOUBLE_EQ(a["link"]["to_host"]["delay_ms"].get<double>(), 500);
  EXPECT_EQ(a["link"]["seed"], 1);
}

TEST_F(Run, BadPlanIsRejectedBeforeAnythingStarts) {
  const auto r = run_smart({"run", "--map", (b_ / "maps/random-32-32-20.map").string(), "--scen",
                            (b_ / "scens/random-32-32-20-random-1.scen").string(), "--plan",
                            (b_ / "smart-examples/example_paths_yx.txt").string(), "--axis", "xy",
                            "--domain", std::to_string(kRunBadPlan)},
                           30s, "run_bad");
  EXPECT_EQ(r.code, 2);
}

// Regression: JetBots (radius 0.09 m) on the SMART paper's 0.3 m lab grid collided 5 times in
// the lab plan: on half-cell locations a follower on an edge midpoint is 0.15 m from the robot
// ahead still on the next cell's centre. Robots wider than a quarter cell now hold both cells
// of an edge they cross (monitor/adg.hpp, Footprint::kCells).
TEST(RunWideRobots, JetbotsOnTheLabsPointThreeMetreCellsDoNotCollide) {
  const std::string lab = std::string(SMART_SOURCE_DIR) + "/examples/lab-7-jetbots/";
  const auto plan = temp_file("wide_robots.plan");
  ASSERT_EQ(run_smart({"plan", "--map", lab + "lab.map", "--scen", lab + "lab.scen", "--out",
                       plan.string()},
                      30s, "wide_plan")
                .code,
            0);
  const auto r = run_smart({"run", "--map", lab + "lab.map", "--scen", lab + "lab.scen", "--plan",
                            plan.string(), "--robot", lab + "jetbot-lab.yaml", "--cell-m", "0.3",
                            "--domain", std::to_string(kRunWideRobots), "--no-progress"},
                           60s, "wide_run", true);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("a robot crossing an edge holds both cells"));
  const auto s = last_json_line(r.out);
  EXPECT_TRUE(s["success"].get<bool>());
  EXPECT_EQ(s["collisions"], 0);
  EXPECT_EQ(s["finished_actions"], s["total_actions"]);
  std::filesystem::remove(plan);
}

}  // namespace
}  // namespace smart::test
