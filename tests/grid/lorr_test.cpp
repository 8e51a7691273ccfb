#include "smart/grid/lorr.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "smart/grid/problem.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::grid {
namespace {

using ::testing::HasSubstr;

// 4 x 3:  row 0 "..@E", row 1 "....", row 2 "S@.."
Grid tiny() {
  return parse_map("type octile\nheight 3\nwidth 4\nmap\n..@E\n....\nS@..\n", "t.map",
                   MapDialect::kLorr);
}

template <typename F>
std::string lorr_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Found by fuzz_lorr: a number too large for JSON's number types escaped as nlohmann's
// out_of_range instead of an InputError naming the file.
TEST(Lorr, ANumberNoJsonTypeHoldsIsAnInputError) {
  const std::string huge = "{\"n_row\": " + std::string(400, '9') + "}";
  EXPECT_THAT(lorr_error_of([&] { parse_lsmart_map(huge, "big.json"); }),
              HasSubstr("big.json: cannot be read as JSON"));
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_spec(huge, "p.json"); }), HasSubstr("p.json"));
}

TEST(Lorr, MapDialectFreesEmittersAndServiceCellsAndMarksThem) {
  MapMarks marks;
  const auto g = parse_map("type octile\nheight 3\nwidth 4\nmap\n..@E\n....\nS@..\n", "t.map",
                           MapDialect::kLorr, &marks);
  EXPECT_FALSE(g.blocked({3, 0}));
  EXPECT_FALSE(g.blocked({0, 2}));
  EXPECT_TRUE(g.blocked({2, 0}));
  ASSERT_EQ(marks.workstations.size(), 1u);
  EXPECT_EQ(marks.workstations[0], (Cell{3, 0}));
  ASSERT_EQ(marks.endpoints.size(), 1u);
  EXPECT_EQ(marks.endpoints[0], (Cell{0, 2}));
  // The MovingAI dialect keeps refusing 'E' (it is not a MovingAI symbol).
  EXPECT_THAT(lorr_error_of([] { parse_map("type octile\nheight 1\nwidth 1\nmap\nE\n", "m.map"); }),
              HasSubstr("unknown map symbol 'E'"));
}

TEST(Lorr, AgentsAreLinearIdsRowTimesWidthPlusColumn) {
  const auto starts =
      parse_lorr_agents("# version for LoRR 2026\n2\n5\n11\n", "a.agents", tiny(), 2);
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_EQ(starts[0], (Cell{1, 1}));
  EXPECT_EQ(starts[1], (Cell{3, 2}));
}

TEST(Lorr, TeamSizeTakesTheFirstAgents) {
  EXPECT_EQ(parse_lorr_agents("3\n0\n1\n4\n", "a.agents", tiny(), 2).size(), 2u);
}

TEST(Lorr, AgentErrorsNameLineRobotAndFix) {
  const auto g = tiny();
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_agents("2\n2\n", "a.agents", g, 1); }),
              HasSubstr("the count says 2 agents but 1 lines follow"));
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_agents("1\n2\n", "a.agents", g, 1); }),
              HasSubstr("a.agents:2: robot 0: start cell 2 (x=2,y=0) is an obstacle"));
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_agents("1\n12\n", "a.agents", g, 1); }),
              HasSubstr("cell id '12' is not in 0..11"));
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_agents("2\n4\n4\n", "a.agents", g, 2); }),
              HasSubstr("robot 1: starts on 4 (x=0,y=1) like robot 0"));
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_agents("1\n4\n", "a.agents", g, 3); }),
              HasSubstr("teamSize is 3 but the file has only 1 agents"));
}

TEST(Lorr, TasksAreErrandSequences) {
  const auto tasks = parse_lorr_tasks("2\n3,8\n11\n", "t.tasks", tiny());
  ASSERT_EQ(tasks.size(), 2u);
  EXPECT_EQ(tasks[0].errands, (std::vector<Cell>{{3, 0}, {0, 2}}));
  EXPECT_EQ(tasks[1].line, 3);
  EXPECT_THAT(lorr_error_of([&] { parse_lorr_tasks("1\n3,9\n", "t.tasks", tiny()); }),
              HasSubstr("t.tasks:2: task 0 errand 2: cell 9 (x=1,y=2) is an obstacle"));
}

TEST(Lorr, UnreachableErrandIsNamed) {
  // Cell (0,0) is walled off from the start (1,1).
  const auto g =
      parse_map("type octile\nheight 2\nwidth 3\nmap\n.@.\n@..\n", "w.map", MapDialect::kLorr);
  const std::vector<Task> tasks{{0, 2, {{2, 1}}}, {1, 3, {{2, 0}, {0, 0}}}};
  const auto problems = check_tasks_reachable(g, {{1, 1}}, tasks, "w.tasks");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_THAT(problems[0].to_string(), HasSubstr("w.tasks:3: task 1 errand 2 at 0 (x=0,y=0)"));
}

TEST(Lorr, SpecReads2026Fields) {
  const auto s = parse_lorr_spec(
      R"({"mapFile":"m.map","agentFile":"a","taskFile":"t","teamSize":40,"numTasksReveal":1.5,
          "version":"2026 LoRR","agentCounter":3,"agentSize":1.0,
          "delayConfig":{"seed":0,"minDelay":5,"maxDelay":12,"eventModel":"bernoulli",
          "pDelay":0.0003,"durationModel":"gaussian","gaussMeanRatio":0.5,"gaussStdRatio":0.22}})",
      "p.json");
  EXPECT_EQ(s.version, 2026);
  EXPECT_EQ(s.team_size, 40u);
  EXPECT_DOUBLE_EQ(s.num_tasks_reveal, 1.5);
  EXPECT_EQ(s.agent_counter, 3);
  EXPECT_TRUE(s.delay.present);
  EXPECT_EQ(s.delay.max_delay_ticks, 12);
  EXPECT_EQ(s.delay.duration_model, "gaussian");
}

TEST(Lorr, Spec2024HasNoDelaysAndOneTickActions) {
  const auto s = parse_lorr_spec(
      R"({"mapFile":"m.map","agentFile":"a","taskFile":"t","teamSize":4,"numTasksReveal":1})",
      "p.json");
  EXPECT_EQ(s.version, 2024);
  EXPECT_EQ(s.agent_counter, 1);
  EXPECT_FALSE(s.delay.present);
}

TEST(Lorr, SpecErrorsNameTheFieldAndTheFix) {
  EXPECT_THAT(lorr_error_of([] { parse_lorr_spec(R"({"mapFile":"m"})", "p.json"); }),
              HasSubstr("missing \"agentFile\""));
  EXPECT_THAT(lorr_error_of([] {
                parse_lorr_spec(
                    R"({"mapFile":"m","agentFile":"a","taskFile":"t","teamSize":"many"})",
                    "p.json");
              }),
              HasSubstr("\"teamSize\" is \"many\"; it must be the number of robots"));
  EXPECT_THAT(lorr_error_of([] { parse_lorr_spec("{\n\"mapFile\": ,\n}", "p.json"); }),
              HasSubstr("p.json:2: not valid JSON"));
  EXPECT_THAT(lorr_error_of([] {
                parse_lorr_spec(R"({"mapFile":"m","agentFile":"a","taskFile":"t","teamSize":2,
                  "delayConfig":{"minDelay":5,"maxDelay":2,"pDelay":0.1,"eventModel":"often"}})",
                                "p.json");
              }),
              ::testing::AllOf(HasSubstr("minDelay 5 and maxDelay 2"),
                               HasSubstr("eventModel \"often\" is unknown")));
}

// libFuzzer (fuzz_lorr): a "seed" of 7.8e24 was cast to an integer, undefined behaviour.
TEST(Lorr, RegressionAWholeNumberPastItsTypeIsAProblemNotACast) {
  const auto spec = [](const std::string& team, const std::string& seed) {
    return parse_lorr_spec(R"({"mapFile":"m","agentFile":"a","taskFile":"t","teamSize":)" + team +
                               R"(,"delayConfig":{"seed":)" + seed +
                               R"(,"minDelay":1,"maxDelay":2,"pDelay":0.1}})",
                           "p.json");
  };
  EXPECT_THAT(lorr_error_of([&] { spec("2", "7777777777777777777777777.0"); }),
              HasSubstr("\"seed\" is 7.777777777777778e+24; it must be a whole number"));
  EXPECT_THAT(lorr_error_of([&] { spec("2", "2.5"); }), HasSubstr("\"seed\" is 2.5"));
  EXPECT_THAT(lorr_error_of([&] { spec("-3", "1"); }), HasSubstr("teamSize -3 must be 1.."));
  EXPECT_THAT(lorr_error_of([&] { spec("1e300", "1"); }), HasSubstr("\"teamSize\" is 1e+300"));
  // A whole value written as a double is still that number.
  EXPECT_EQ(spec("2.0", "18446744073709551615").team_size, 2u);
}

TEST(Lorr, LsmartMapMarksWorkstationsAndEndpoints) {
  MapMarks marks;
  const auto g =
      parse_lsmart_map(R"({"n_row":3,"n_col":3,"layout":["@e@","...","@w@"]})", "s.json", &marks);
  EXPECT_EQ(g.width(), 3);
  EXPECT_TRUE(g.blocked({0, 0}));
  EXPECT_FALSE(g.blocked({1, 0}));
  EXPECT_EQ(marks.endpoints, (std::vector<Cell>{{1, 0}}));
  EXPECT_EQ(marks.workstations, (std::vector<Cell>{{1, 2}}));
  EXPECT_THAT(
      lorr_error_of([] { parse_lsmart_map(R"({"n_row":1,"n_col":2,"layout":["x."]})", "s.json"); }),
      HasSubstr("unknown symbol 'x'"));
}

TEST(Lorr, LoadsEveryLorr2026ExampleProblem) {
  const auto dir = test::benchmarks_dir() / "lorr-2026";
  std::size_t problems = 0;
  for (const auto& domain : std::filesystem::directory_iterator(dir)) {
    if (!domain.is_directory()) continue;
    for (const auto& f : std::filesystem::directory_iterator(domain.path())) {
      if (f.path().extension() != ".json") continue;
      SCOPED_TRACE(f.path().string());
      const auto p = load_lorr_problem(f.path());
      ++problems;
      EXPECT_EQ(p.spec.version, 2026);
      EXPECT_EQ(p.starts.size(), p.spec.team_size);
      EXPECT_FALSE(p.tasks.empty());
      for (const Cell s : p.starts) EXPECT_TRUE(p.grid.free(s));
    }
  }
  EXPECT_EQ(problems, 7u);  // the Start-Kit's seven example problems (PROVENANCE.md)
}

TEST(Lorr, LoadNamesTheMissingFile) {
  const auto dir = std::filesystem::temp_directory_path() / "smart_lorr_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "p.json")
      << R"({"mapFile":"nope.map","agentFile":"a","taskFile":"t","teamSize":1})";
  EXPECT_THAT(lorr_error_of([&] { load_lorr_problem(dir / "p.json"); }), HasSubstr("nope.map"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace smart::grid
