// `smart check-plan` as a user runs it: a real process, JSON on stdout, exit code.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "smart/tools/child_process.hpp"
#include "support/dds_test_support.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::tools {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

struct Run {
  int code;
  std::string out;
};

Run run(const std::vector<std::string>& args) {
  const auto out = test::temp_file("check_plan.json");
  std::vector<std::string> argv{test::smart_exe().string(), "check-plan"};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess p(argv, out);
  const int code = p.wait(60s).value_or(-1);
  std::ifstream in(out);
  std::stringstream s;
  s << in.rdbuf();
  std::filesystem::remove(out);
  return {code, s.str()};
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto p = test::temp_file(name);
  std::ofstream(p) << text;
  return p.string();
}

TEST(CheckPlanCommand, ValidPlanPrintsReportAndExitsZero) {
  const auto b = test::benchmarks_dir();
  if (!std::filesystem::exists(b)) GTEST_SKIP() << "no benchmark data at " << b;
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

}  // namespace
}  // namespace smart::tools
