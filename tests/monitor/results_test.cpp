#include "smart/monitor/results.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "smart/monitor/plan_validator.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using ::testing::HasSubstr;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("smart_results_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(d);
  return d;
}

// Two robots crossing a 3x3 open map.
Instance tiny_instance() {
  Instance in;
  in.grid = test::grid_of({"...", "...", "..."});
  in.plan = test::plan_of({{{0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 0}, {1, 1}, {1, 2}}});
  in.scen = test::scen_of(in.plan, in.grid);
  in.stats = plan_stats(in.plan);
  in.actions = build_actions(in.plan, Heading::kEast);
  std::vector<Problem> problems;
  in.adg = build_adg(in.actions, in.grid, in.plan.source, problems);
  EXPECT_TRUE(problems.empty());
  return in;
}

MonitorResult finished_run(const Instance& in) {
  MonitorResult r;
  r.outcome = Outcome::kSuccess;
  r.sim_time_s = 12.5;
  r.wall_time_s = 0.5;
  r.total_actions = r.finished_actions = in.actions.offset.back();
  r.robots = {{8.0, 0.0, 0, 2}, {12.5, 3.0, 1, 3}};
  r.min_gap_m = 0.25;
  return r;
}

TEST(Results, SummaryHasTheKeysUsersReadAndTheRightAverages) {
  const auto in = tiny_instance();
  RunInfo info;
  info.monitor_peak_rss_mb = 21.5;
  info.machine = "test machine";
  const auto j = summary_json(in, finished_run(in), info);
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["robots"], 2);
  EXPECT_DOUBLE_EQ(j["aet_s"].get<double>(), (8.0 + 12.5) / 2);
  EXPECT_DOUBLE_EQ(j["makespan_s"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(j["sim_speed"].get<double>(), 25.0);
  EXPECT_DOUBLE_EQ(j["waiting_time_s"]["total"].get<double>(), 3.0);
  EXPECT_EQ(j["stops"], 1);
  EXPECT_DOUBLE_EQ(j["peak_rss_mb"]["monitor"].get<double>(), 21.5);
  EXPECT_TRUE(j["peak_rss_mb"]["sim"].is_null());  // not known: null, not 0
  EXPECT_EQ(j["machine"], "test machine");
  auto reported = finished_run(in);
  reported.host_peak_rss_mb = 42.0;  // from the sim host's status
  EXPECT_DOUBLE_EQ(summary_json(in, reported, info)["peak_rss_mb"]["sim"].get<double>(), 42.0);
  for (const char* key : {"collisions", "min_separation_m", "adg", "plan", "versions"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_TRUE(j["build_time_ms"].contains("adg_total"));
  EXPECT_TRUE(j.contains("first_report_wall_s"));
  EXPECT_EQ(j["pose_contacts"], 0);
  EXPECT_TRUE(j["pose_min_separation_m"].is_null());  // no poses compared: null, not 0
  EXPECT_TRUE(j["first_pose_contact"].is_null());
  reported.pose_contacts = 2;
  reported.pose_min_gap_m = -0.02;
  reported.first_pose_contact = PoseContact{1, 3, 12.5, -0.01};
  const auto c = summary_json(in, reported, info);
  EXPECT_EQ(c["pose_contacts"], 2);
  EXPECT_DOUBLE_EQ(c["pose_min_separation_m"].get<double>(), -0.02);
  EXPECT_EQ(c["first_pose_contact"]["robots"], nlohmann::json::array({1, 3}));
  EXPECT_DOUBLE_EQ(c["first_pose_contact"]["gap_m"].get<double>(), -0.01);
}

TEST(Results, TheWaitingIsSplitByCauseOnlyWhenTheExecutionTold) {
  const auto in = tiny_instance();
  auto r = finished_run(in);
  EXPECT_FALSE(summary_json(in, r, {})["waiting_time_s"].contains("by_cause"));
  r.waiting_by_cause_s.emplace();
  (*r.waiting_by_cause_s)[std::size_t(WaitCause::kAtLocation)] = 2.0;
  (*r.waiting_by_cause_s)[std::size_t(WaitCause::kNoAction)] = 1.0;
  const auto by_cause = summary_json(in, r, {})["waiting_time_s"]["by_cause"];
  EXPECT_EQ(by_cause, (nlohmann::json{{"at_location", 2.0},
                                      {"at_location_turning", 0.0},
                                      {"at_location_waiting", 0.0},
                                      {"entering", 0.0},
                                      {"on_its_way_near", 0.0},
                                      {"on_its_way_far", 0.0},
                                      {"on_its_way_waiting", 0.0},
                                      {"held", 0.0},
                                      {"no_action", 1.0}}));
}

TEST(Results, WritesSummaryStatsAndRobotFiles) {
  const auto in = tiny_instance();
  const auto dir = temp_dir("files");
  write_results(dir / "nested", in, finished_run(in), RunInfo{});
  const auto summary = nlohmann::json::parse(slurp(dir / "nested" / "summary.json"));
  EXPECT_DOUBLE_EQ(summary["aet_s"].get<double>(), 10.25);
  const auto stats = slurp(dir / "nested" / "stats.csv");
  // SMART's columns; steps at the 0.1 s control period: 125 steps max, 205 in all.
  EXPECT_THAT(stats, HasSubstr("steps finish sim,sum of steps finish sim"));
  EXPECT_THAT(stats, HasSubstr("\n125,205,12.5,20.5,"));
  EXPECT_EQ(slurp(dir / "nested" / "robots.csv"),
            "robot,finish_time_s,waiting_time_s,stops,actions,lower_bound_s\n0,8,0,0,2,\n"
            "1,12.5,3,1,3,\n");
  std::filesystem::remove_all(dir);
}

TEST(Results, ActionsCsvHasEveryActionAndItsFinishTimeEmptyWhenNotFinished) {
  const auto in = tiny_instance();
  auto r = finished_run(in);
  // Half-moves: robot 0 has four, robot 1 a rotation and four; robot 1's last never finished.
  r.action_finish_s = {1, 2, 3, 8, 2.5, 4, 5, 7.25, std::nan("")};
  const auto dir = temp_dir("actions");
  write_results(dir, in, r, RunInfo{});
  EXPECT_EQ(slurp(dir / "actions.csv"),
            "robot,action,type,finish_time_s\n0,0,move,1\n0,1,move,2\n0,2,move,3\n0,3,move,8\n"
            "1,0,rotate,2.5\n1,1,move,4\n1,2,move,5\n1,3,move,7.25\n1,4,move,\n");
  std::filesystem::remove_all(dir);
}

TEST(Results, MotionBoundPerRobotAndItsRatiosWhenTheLimitsAreKnown) {
  const auto in = tiny_instance();
  auto r = finished_run(in);
  RunInfo info;
  info.limits = MotionLimits{1.0, 0.5, 0.5, 1.0, 10.0};
  const auto bound = motion_lower_bounds_s(in.actions, info.cell_m, *info.limits);
  const auto j = summary_json(in, r, info)["motion_bound"];
  EXPECT_DOUBLE_EQ(j["aet_s"].get<double>(), (bound[0] + bound[1]) / 2);
  EXPECT_DOUBLE_EQ(j["finish_over_bound_max"].get<double>(),
                   std::max(8.0 / bound[0], 12.5 / bound[1]));
  // The limits themselves, with the model's name (issue 26: an upload's chosen limits appeared
  // nowhere after the run).
  info.robot_model = "footbot";
  const auto limits = summary_json(in, r, info)["limits"];
  EXPECT_EQ(limits["robot"], "footbot");
  EXPECT_DOUBLE_EQ(limits["max_speed_mps"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(limits["max_accel_mps2"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(limits["max_angular_accel_radps2"].get<double>(), 10.0);
  EXPECT_FALSE(summary_json(in, r, RunInfo{}).contains("limits"));
  // Robot 1's last action never finished: no finish time in robots.csv, its bound still there.
  r.action_finish_s = {1, 2, 3, 8, 2.5, 4, 5, 7.25, std::nan("")};
  const auto dir = temp_dir("bound");
  write_results(dir, in, r, info);
  const auto csv = slurp(dir / "robots.csv");
  EXPECT_THAT(csv, HasSubstr("\n1,,3,1,3," + nlohmann::json(bound[1]).dump().substr(0, 8)));
  EXPECT_THAT(csv, HasSubstr("\n0,8,0,0,2,"));
  std::filesystem::remove_all(dir);
}

// Regression: summary.json named the execution but not its knobs, so two switching runs with
// different --switch-* flags could not be told apart from their results.
TEST(Results, ASwitchingRunsSummaryNamesItsOptions) {
  const auto in = tiny_instance();
  const auto r = finished_run(in);
  EXPECT_FALSE(summary_json(in, r, RunInfo{})["execution"].contains("options"));
  RunInfo info;
  SwitchOptions o;
  o.anticipate = true;
  o.lookahead_actions = 24;
  o.window_pairs = 3;
  o.chain_locations = 2;
  o.lookahead_margin_s = 0.75;
  info.switching = o;
  const auto j = summary_json(in, r, info)["execution"]["options"];
  EXPECT_EQ(j["anticipate"], true);
  EXPECT_EQ(j["lookahead_actions"], 24);
  EXPECT_EQ(j["window_pairs"], 3);
  EXPECT_EQ(j["chain_locations"], 2);
  EXPECT_DOUBLE_EQ(j["lookahead_margin_s"].get<double>(), 0.75);
  EXPECT_EQ(j["commit_actions"], o.commit_actions);
  EXPECT_EQ(j["search_budget"], o.search_budget);
}

TEST(Results, AResumedRunWithRobotsDoneBeforeHasNoAetAndSaysSo) {
  const auto in = tiny_instance();
  auto r = finished_run(in);
  r.resumed = true;
  r.resumed_at_s = 4.0;
  r.finished_before_resume = 3;
  r.robots_done_before_resume = 1;
  r.robots[0].finish_time_s = std::nan("");  // done before the resume: unknown
  const auto j = summary_json(in, r, RunInfo{});
  EXPECT_TRUE(j["aet_s"].is_null());
  EXPECT_TRUE(j["makespan_s"].is_null());
  EXPECT_DOUBLE_EQ(j["resumed"]["at_s"].get<double>(), 4.0);
  EXPECT_EQ(j["resumed"]["finished_before"], 3);
  EXPECT_EQ(j["resumed"]["robots_done_before"], 1);
  const auto dir = temp_dir("resumed");
  write_results(dir, in, r, RunInfo{});
  // SMART's stats row counts the robots whose finish time is known.
  EXPECT_THAT(slurp(dir / "stats.csv"), HasSubstr("\n125,125,12.5,12.5,"));
  std::filesystem::remove_all(dir);
}

TEST(Results, StatesAreStreamedRowByRow) {
  const auto dir = temp_dir("states");
  {
    StatesCsvWriter w(dir);
    w.add({0.5, 3, 1.0, 2.0, 0.25, 0.1, 0.0, 0.1, 0.1, 4});
    w.add({1.0, 3, 1.05, 2.0, 0.25, 0.0, 0.0, 0.0, 0.0, 3});
    EXPECT_EQ(w.rows(), 2u);
  }
  EXPECT_EQ(slurp(dir / "states.csv"),
            "t_s,robot,x_m,y_m,yaw_rad,v_mps,omega_radps,left_mps,right_mps,queue\n"
            "0.5,3,1,2,0.25,0.1,0,0.1,0.1,4\n1,3,1.05,2,0.25,0,0,0,0,3\n");
  std::filesystem::remove_all(dir);
}

// Read while the run goes (a live view's progress): every row is on disk once added.
TEST(Results, ProgressIsFlushedRowByRowForLiveViews) {
  const auto dir = temp_dir("progress");
  ProgressCsvWriter w(dir);
  w.add({1.5, 3, 40});
  EXPECT_EQ(slurp(dir / "progress.csv"), "t_s,finished,total\n1.5,3,40\n");
  w.add({2.0, 5, 40});
  EXPECT_EQ(results::last_progress_row(slurp(dir / "progress.csv"))->finished, 5u);
  std::filesystem::remove_all(dir);
}

// switches.csv while a switchable run goes (what --resume-switches replays): each row on disk
// once added, its stays named by their entering actions' seqs, read back onto the same stays;
// a seq the robot does not have matches nothing.
TEST(Results, SwitchesAreFlushedAsMadeAndReadBackOntoTheirStays) {
  const auto in = tiny_instance();
  const auto orders = passing_orders(in.actions, in.grid);
  const auto loc = static_cast<uint32_t>(in.grid.half_index(HalfCell::of({1, 1})));
  const auto& a = orders.stays[orders.begin[loc]];
  const auto& b = orders.stays[orders.begin[loc] + 1];
  ASSERT_NE(a.robot, b.robot);
  const PassingSwitch made{2.5, loc, b.robot, a.robot, true, b.enter, a.enter};
  const auto dir = temp_dir("switches");
  SwitchesCsvWriter w(dir);
  w.add(switch_row(in.grid, &in.actions, made));
  const auto text = slurp(dir / "switches.csv");
  const auto seq = [&](uint32_t robot, uint32_t node) {
    return std::to_string(node - in.actions.offset[robot]);
  };
  EXPECT_EQ(text, "time_s,x,y,first,second,first_seq,second_seq,anticipated\n2.5,1,1," +
                      std::to_string(b.robot) + "," + std::to_string(a.robot) + "," +
                      seq(b.robot, b.enter) + "," + seq(a.robot, a.enter) + ",1\n");
  auto rows = results::parse_switches_csv(text);
  EXPECT_EQ(passing_switches(in.grid, in.actions, rows), std::vector<PassingSwitch>{made});
  auto replayed = orders;
  EXPECT_EQ(apply_switches(replayed, passing_switches(in.grid, in.actions, rows)), 0u);
  EXPECT_EQ(replayed.stays[orders.begin[loc]].robot, b.robot);
  rows[0].first_seq = 99;
  auto other = orders;
  EXPECT_EQ(apply_switches(other, passing_switches(in.grid, in.actions, rows)), 1u);
  std::filesystem::remove_all(dir);
}

TEST(Results, FinishedCountsAreReplacedWhole) {
  const auto dir = temp_dir("finished");
  std::filesystem::create_directories(dir);
  write_finished_csv(dir, {1, 2});
  write_finished_csv(dir, {4, 5});
  EXPECT_EQ(slurp(dir / "finished.csv"), "robot,finished\n0,4\n1,5\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "finished.csv.new"));
  std::filesystem::remove_all(dir);
}

TEST(Results, AnUnwritableFolderIsAnErrorNamingIt) {
  const auto file = temp_dir("plainfile");
  std::ofstream(file) << "x";
  try {
    StatesCsvWriter w(file / "out");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace smart::monitor
