// `smart check-plan` as a user runs it: a real process, JSON on stdout, exit code.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::tools {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

// `smart check-plan args...`: exit code and stdout (with its error messages: with_stderr).
test::SmartRun run(std::vector<std::string> args, bool with_stderr = false) {
  args.insert(args.begin(), "check-plan");
  return test::run_smart(args, 60s, "check_plan", with_stderr);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto p = test::temp_file(name);
  std::ofstream(p) << text;
  return p.string();
}

TEST(CheckPlanCommand, ValidPlanPrintsReportAndExitsZero) {
  const auto b = test::benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  const auto r = run({"--map", (b / "maps/random-32-32-20.map").string(), "--scen",
                      (b / "scens/random-32-32-20-random-1.scen").string(), "--plan",
                      (b / "smart-examples/example_paths_xy.txt").string(), "--axis", "xy"});
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["valid"].get<bool>());
  EXPECT_EQ(j["robots"], 50);
  EXPECT_EQ(j["plan"]["soc"], 1241.0);
  EXPECT_EQ(j["plan"]["makespan"], 48.0);
  EXPECT_GT(j["adg"]["type2"].get<int>(), 0);
  EXPECT_GT(j["adg"]["type2_all_pairs"].get<int>(), j["adg"]["type2"].get<int>());
  EXPECT_TRUE(j["build_time_ms"].contains("adg_total"));
}

TEST(CheckPlanCommand, InvalidPlanListsEveryProblemAndExitsOne) {
  const auto map = write_temp("m.map", "type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n");
  const auto scen = write_temp("s.scen",
                               "version 1\n0\tm.map\t3\t2\t0\t0\t2\t0\t2\n"
                               "0\tm.map\t3\t2\t2\t0\t0\t0\t2\n");
  // Robot 0 steps into the obstacle; robots 0 and 1 swap along the top row.
  const auto plan = write_temp("p.txt",
                               "Agent 0:(0,0)->(1,1)->(2,0)->\n"
                               "Agent 1:(2,0)->(1,0)->(0,0)->\n");
  const auto r = run({"--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"});
  EXPECT_EQ(r.code, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["valid"].get<bool>());
  std::string all;
  for (const auto& p : j["problems"]) all += p["message"].get<std::string>() + "\n";
  EXPECT_THAT(all, HasSubstr("obstacle at (x=1,y=1)"));
  EXPECT_THAT(all, HasSubstr("jumps from (x=1,y=1) to (x=2,y=0)"));
  EXPECT_EQ(j["problems"][0]["robot"], 0);
  EXPECT_EQ(j["problems"][0]["line"], 1);
  // Issue 26: the JSON buried stderr's hint; on a terminal the problems now come last.
  const auto both = run({"--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"}, true);
  EXPECT_EQ(both.code, 1);
  const auto json_end = both.out.find("\n}\n");
  const auto said = both.out.find("obstacle at (x=1,y=1)", json_end);
  ASSERT_NE(json_end, std::string::npos) << both.out;
  EXPECT_NE(said, std::string::npos) << "the problems must follow the JSON:\n" << both.out;
  EXPECT_THAT(both.out, ::testing::EndsWith("problem(s) found\n"));
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

TEST(CheckPlanCommand, MissingAxisAndBadArgumentsAreRejected) {
  const auto map = write_temp("m2.map", "type octile\nheight 1\nwidth 2\nmap\n..\n");
  const auto scen = write_temp("s2.scen", "version 1\n0\tm.map\t2\t1\t0\t0\t1\t0\t1\n");
  const auto plan = write_temp("p2.txt", "Agent 0:(0,0)->(1,0)->\n");
  const auto r = run({"--map", map, "--scen", scen, "--plan", plan});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.out, HasSubstr("pass --axis xy or --axis rowcol"));
  EXPECT_NE(run({"--map", map, "--scen", scen, "--plan", plan, "--axis", "diagonal"}).code, 0);
  EXPECT_EQ(run({"--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"}).code, 0);
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

// Issue 26: a missing file made check-plan exit 1 (an invalid plan) where `smart run` exits 2
// (input to fix); both now say 2, naming the file.
TEST(CheckPlanCommand, AFileThatCannotBeReadIsBadInputExitTwo) {
  const auto map = write_temp("m3.map", "type octile\nheight 1\nwidth 2\nmap\n..\n");
  const auto scen = write_temp("s3.scen", "version 1\n0\tm.map\t2\t1\t0\t0\t1\t0\t1\n");
  const auto missing = test::temp_file("no_such_plan.txt").string();
  const auto r = run({"--map", map, "--scen", scen, "--plan", missing, "--axis", "xy"}, true);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr(missing + ": cannot open the plan file; check the path"));
  const auto via_run = test::run_smart(
      {"run", "--map", map, "--scen", scen, "--plan", missing, "--axis", "xy"}, 60s, "run_missing");
  EXPECT_EQ(via_run.code, 2);
  for (const auto& f : {map, scen}) std::filesystem::remove(f);
}

// --actions: where a run's waiting went (monitor/wait_causes.hpp), on the crossing of
// wait_causes_test with robot 0 late (its actions end at 4-9 s): robot 1 waits 6 s at the cell's
// edge, 4 s of it while robot 0 was on its way. A row naming an action the plan lacks: exit 2,
// naming the file and the line.
TEST(CheckPlanCommand, ARunsActionsSayWhereItsWaitingWent) {
  const auto map = write_temp("m6.map", "type octile\nheight 3\nwidth 4\nmap\n....\n....\n....\n");
  const auto scen = write_temp("s6.scen",
                               "version 1\n0\tm.map\t4\t3\t0\t1\t3\t1\t3\n"
                               "0\tm.map\t4\t3\t2\t0\t2\t2\t2\n");
  const auto plan = write_temp("p6.txt",
                               "Agent 0:(0,1)->(1,1)->(2,1)->(3,1)->\n"
                               "Agent 1:(2,0)->(2,0)->(2,0)->(2,1)->(2,2)->\n");
  std::string csv = "robot,action,type,finish_time_s\n";
  for (int k = 0; k < 6; ++k)
    csv += "0," + std::to_string(k) + ",move," + std::to_string(4 + k) + "\n";
  csv += "1,0,rotate,1\n1,1,move,2\n1,2,move,9\n1,3,move,10\n1,4,move,11\n";
  const auto actions = write_temp("a6.csv", csv);
  const std::vector<std::string> args{"--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"};
  auto with = args;
  with.insert(with.end(), {"--actions", actions});
  const auto r = run(with);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto w = nlohmann::json::parse(r.out)["waits"];
  EXPECT_EQ(w["waits"], 1);
  EXPECT_DOUBLE_EQ(w["total_s"].get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(w["on_its_way_s"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(w["at_location_s"].get<double>(), 1.0);

  const auto bad = write_temp("a6bad.csv", csv + "1,7,move,12\n");
  with.back() = bad;
  const auto b = run(with, true);
  EXPECT_EQ(b.code, 2) << b.out;
  EXPECT_THAT(b.out, HasSubstr(bad + ": actions.csv line 13: robot 1 action 7 is not an action"));
  for (const auto& f : {map, scen, plan, actions, bad}) std::filesystem::remove(f);
}

// Issue 26: `--agents` and `--robots` named one count in different commands; each takes both.
TEST(CheckPlanCommand, TheRobotCountIsNamedEitherWay) {
  const auto map = write_temp("m4.map", "type octile\nheight 1\nwidth 3\nmap\n...\n");
  const auto scen = write_temp("s4.scen",
                               "version 1\n0\tm.map\t3\t1\t0\t0\t1\t0\t1\n"
                               "0\tm.map\t3\t1\t2\t0\t2\t0\t0\n");
  const auto plan = write_temp("p4.txt", "Agent 0:(0,0)->(1,0)->\nAgent 1:(2,0)->(2,0)->\n");
  for (const char* flag : {"--agents", "--robots"}) {
    const auto r = run({"--map", map, "--scen", scen, "--plan", plan, "--axis", "xy", flag, "1"});
    ASSERT_EQ(r.code, 0) << flag << ": " << r.out;
    EXPECT_EQ(nlohmann::json::parse(r.out)["robots"], 1) << flag;
  }
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

// Four robots turning round a 2x2 block together: fine for footbots on 1 m cells (half-cell
// locations), a deadlock for JetBots on 0.3 m cells (a robot crossing an edge holds both cells),
// refused outright on cells less than two radii wide.
TEST(CheckPlanCommand, TheFootprintDecidesWhetherARotationLoopCanBeExecuted) {
  const auto map = write_temp("loop.map", "type octile\nheight 2\nwidth 2\nmap\n..\n..\n");
  const auto scen = write_temp("loop.scen",
                               "version 1\n0\tm.map\t2\t2\t0\t0\t1\t0\t1\n"
                               "0\tm.map\t2\t2\t1\t0\t1\t1\t1\n"
                               "0\tm.map\t2\t2\t1\t1\t0\t1\t1\n"
                               "0\tm.map\t2\t2\t0\t1\t0\t0\t1\n");
  const auto plan = write_temp("loop.txt",
                               "Agent 0:(0,0)->(1,0)->\nAgent 1:(1,0)->(1,1)->\n"
                               "Agent 2:(1,1)->(0,1)->\nAgent 3:(0,1)->(0,0)->\n");
  const std::vector<std::string> args{"--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"};
  EXPECT_EQ(run(args).code, 0);
  auto jetbots = args;
  jetbots.insert(jetbots.end(), {"--robot", "jetbot", "--cell-m", "0.3"});
  const auto loop = run(jetbots);
  EXPECT_EQ(loop.code, 1) << loop.out;
  EXPECT_THAT(loop.out, HasSubstr("cannot follow each other round a loop"));
  auto too_wide = args;
  too_wide.insert(too_wide.end(), {"--robot", "jetbot", "--cell-m", "0.18"});
  const auto refused = run(too_wide, true);
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_THAT(refused.out, HasSubstr("half a --cell-m 0.18 m cell wide"));
  EXPECT_THAT(refused.out, HasSubstr("use --cell-m 0.225"));
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

}  // namespace
}  // namespace smart::tools
