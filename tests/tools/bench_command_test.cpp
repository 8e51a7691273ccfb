// `smart bench sim` and `smart bench run` as a user runs them (tiny sizes: this checks what
// they report, not how fast anything is).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

TEST(BenchCommand, SimReportsSpeedAwakeRobotsAndTheMachine) {
  const auto b = benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  const auto r = run_smart({"bench", "sim", "--map", (b / "maps/random-32-32-20.map").string(),
                            "--robots", "20", "--sim-seconds", "2", "--system-capacity", "8"},
                           60s, "bench_sim");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_EQ(j["robots"], 20);
  EXPECT_DOUBLE_EQ(j["sim_seconds"].get<double>(), 2.0);
  EXPECT_GT(j["sim_speed"].get<double>(), 0.0);
  EXPECT_GT(j["finished_actions"].get<int>(), 0);
  EXPECT_EQ(j["system_capacity"], 8);
  // Random walks never rest: (nearly) every robot is stepped by Simbody in every period.
  EXPECT_GT(j["mean_awake_robots"].get<double>(), 18.0);
  EXPECT_LE(j["mean_active_systems"].get<double>(), 3.0 + 1e-9);
  EXPECT_THAT(j["machine"].get<std::string>(), HasSubstr("cores"));
}

TEST(BenchCommand, RunPrintsALinePerFleetSizeThenATable) {
  const auto b = benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  const auto out = temp_file("bench_run_results");
  const auto r = run_smart(
      {"bench", "run", "--map", (b / "maps/random-32-32-20.map").string(), "--scen",
       (b / "scens/random-32-32-20-random-1.scen").string(), "--plan",
       (b / "smart-examples/example_paths_xy.txt").string(), "--axis", "xy", "--agents", "5,10",
       "--qos", "lan,sim-wifi", "--domain", std::to_string(kBenchRun), "--out", out.string()},
      120s, "bench_run");
  ASSERT_EQ(r.code, 0) << r.out;
  std::istringstream lines(r.out);
  std::vector<nlohmann::json> rows;
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] == '{') rows.push_back(nlohmann::json::parse(line));
  }
  // Each size over each profile, the first the reference (issue 26: a modelled link's cost).
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0]["robots"], 5);
  EXPECT_EQ(rows[0]["qos"], "lan");
  EXPECT_EQ(rows[0]["speed_vs_first_qos"], 1.0);
  EXPECT_EQ(rows[1]["robots"], 5);
  EXPECT_EQ(rows[1]["qos"], "sim-wifi");
  EXPECT_DOUBLE_EQ(rows[1]["speed_vs_first_qos"].get<double>(),
                   rows[1]["sim_speed"].get<double>() / rows[0]["sim_speed"].get<double>());
  EXPECT_EQ(rows[2]["robots"], 10);
  for (const auto& row : rows) {
    EXPECT_TRUE(row["success"].get<bool>());
    EXPECT_EQ(row["collisions"], 0);
    EXPECT_GT(row["monitor_peak_rss_mb"].get<double>(), 1.0);
    EXPECT_GT(row["sim_peak_rss_mb"].get<double>(), 1.0);
    EXPECT_GT(row["cpu_s_per_sim_s"].get<double>(), 0.0);
    EXPECT_GT(row["adg_build_ms"].get<double>(), 0.0);
    EXPECT_GT(row["first_report_wall_s"].get<double>(), 0.0);  // discovery and start-up
    EXPECT_LT(row["first_report_wall_s"].get<double>(), row["wall_time_s"].get<double>());
  }
  EXPECT_THAT(r.out, HasSubstr("| robots | qos | success | sim time |"));
  EXPECT_THAT(r.out, HasSubstr("\n| 5 | lan | yes | "));
  EXPECT_THAT(r.out, HasSubstr("\n| 10 | sim-wifi | yes | "));
  EXPECT_THAT(r.out, HasSubstr("machine: "));
  EXPECT_TRUE(std::filesystem::exists(out / "10-sim-wifi" / "summary.json"));
  std::filesystem::remove_all(out);
}

TEST(BenchCommand, RunNamesTheFailingSize) {
  const auto b = benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  // No --axis for a SMART path file: `smart run` refuses it (exit code 2).
  const auto r =
      run_smart({"bench", "run", "--map", (b / "maps/random-32-32-20.map").string(), "--scen",
                 (b / "scens/random-32-32-20-random-1.scen").string(), "--plan",
                 (b / "smart-examples/example_paths_xy.txt").string(), "--agents", "5", "--domain",
                 std::to_string(kBenchRunBadSize), "--out", temp_file("bench_run_bad").string()},
                60s, "bench_run_bad");
  EXPECT_EQ(r.code, 1);
  std::filesystem::remove_all(temp_file("bench_run_bad"));
}

}  // namespace
}  // namespace smart::test
