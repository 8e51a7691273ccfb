#include "smart/monitor/plan_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/grid/problem.hpp"
#include "smart/grid/text_file.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using ::testing::HasSubstr;

PlanReadOptions xy() { return {PlanFormat::kAuto, AxisOrder::kXY}; }
PlanReadOptions rowcol() { return {PlanFormat::kAuto, AxisOrder::kRowCol}; }

std::string error_of(const std::string& text, PlanReadOptions o = xy()) {
  try {
    parse_plan(text, "p.txt", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PlanReader, SmartTimedKeepsNonIntegerTimes) {
  const auto p = parse_plan("Agent 0:(1,2,0)->(2,2,1.5)->\nAgent 1:(5,5,0)->\n", "p.txt", xy());
  EXPECT_EQ(p.format, PlanFormat::kSmart);
  EXPECT_TRUE(p.timed);
  ASSERT_EQ(p.paths.size(), 2u);
  ASSERT_EQ(p.paths[0].steps.size(), 2u);
  EXPECT_EQ(p.paths[0].steps[1].cell, (Cell{2, 2}));
  EXPECT_DOUBLE_EQ(p.paths[0].steps[1].time, 1.5);
  EXPECT_EQ(p.paths[1].steps[0].line, 2);
}

TEST(PlanReader, SmartUntimedRowColIsStepIndexAndSwapsAxes) {
  const auto p = parse_plan("Agent 0: (57,143)->(57,142)->(56,142)->", "p.txt", rowcol());
  EXPECT_FALSE(p.timed);
  ASSERT_EQ(p.paths[0].steps.size(), 3u);
  EXPECT_EQ(p.paths[0].steps[0].cell, (Cell{143, 57}));  // x = column
  EXPECT_EQ(p.paths[0].steps[2].cell, (Cell{142, 56}));
  EXPECT_DOUBLE_EQ(p.paths[0].steps[2].time, 2.0);
}

TEST(PlanReader, LacamResult) {
  const std::string text =
      "agents=2\nmap_file=m.map\nsolver=LaCAM\nsolved=1\nsoc=3\nstarts=(0,0),(2,0),\n"
      "goals=(1,0),(2,1),\nsolution=\n0:(0,0),(2,0),\n1:(1,0),(2,1),\n";
  const auto p = parse_plan(text, "result.txt", {});
  EXPECT_EQ(p.format, PlanFormat::kLacam);
  EXPECT_EQ(p.axis, AxisOrder::kXY);
  ASSERT_EQ(p.paths.size(), 2u);
  EXPECT_EQ(p.paths[1].steps[1].cell, (Cell{2, 1}));
  EXPECT_DOUBLE_EQ(p.paths[1].steps[1].time, 1.0);
}

TEST(PlanReader, LibMultiRobotPlanningYaml) {
  const std::string text =
      "statistics:\n  cost: 2\nschedule:\n  agent1:\n    - x: 3\n      y: 4\n      t: 0\n"
      "  agent0:\n    - {x: 0, y: 1, t: 0}\n    - {x: 1, y: 1, t: 1}\n";
  const auto p = parse_plan(text, "out.yaml", {});
  EXPECT_EQ(p.format, PlanFormat::kYaml);
  ASSERT_EQ(p.paths.size(), 2u);
  EXPECT_EQ(p.paths[0].steps[1].cell, (Cell{1, 1}));
  EXPECT_EQ(p.paths[1].steps[0].cell, (Cell{3, 4}));
  EXPECT_EQ(p.paths[1].steps[0].line, 5);
}

TEST(PlanReader, FormatDetectionAndOverride) {
  EXPECT_EQ(detect_plan_format("Agent 0:(1,1)->"), PlanFormat::kSmart);
  EXPECT_EQ(detect_plan_format("agents=3\n"), PlanFormat::kLacam);
  EXPECT_EQ(detect_plan_format("0:(1,1),\n"), PlanFormat::kLacam);
  EXPECT_EQ(detect_plan_format("schedule:\n"), PlanFormat::kYaml);
  EXPECT_EQ(detect_plan_format("hello"), PlanFormat::kAuto);
  EXPECT_THAT(error_of("hello world\n"), HasSubstr("pass --format smart, lacam or yaml"));
  const auto p = parse_plan("0:(1,1),\n", "p", {PlanFormat::kLacam, AxisOrder::kRowCol});
  EXPECT_EQ(p.paths[0].steps[0].cell, (Cell{1, 1}));
  EXPECT_EQ(parse_plan_format("lns2"), PlanFormat::kSmart);
  EXPECT_THROW(parse_axis_order("colrow"), std::invalid_argument);
}

TEST(PlanReaderErrors, SmartNeedsAnExplicitAxis) {
  EXPECT_THAT(error_of("Agent 0:(1,1)->", {}), HasSubstr("pass --axis xy or --axis rowcol"));
}

// `smart plan` writes "# axis: xy" first: its plans read back without --axis; a contradicting
// --axis is an error, not a silent choice.
TEST(PlanReader, ADeclaredAxisIsReadWithoutAxisAndAContradictionIsAnError) {
  const auto p = parse_plan("# axis: rowcol\nAgent 0:(1,2)->(1,3)->\n", "p.txt", {});
  EXPECT_EQ(p.axis, AxisOrder::kRowCol);
  EXPECT_EQ(p.paths[0].steps[0].cell, (Cell{2, 1}));  // (row 1, col 2): x = 2, y = 1
  EXPECT_THAT(error_of("# axis: rowcol\nAgent 0:(1,2)->\n", xy()),
              HasSubstr("p.txt:1: the file declares '# axis: rowcol' but --axis xy was given"));
  EXPECT_EQ(error_of("# a note\nAgent 0:(1,1)->\n# another\n"), "(no error)");
}

TEST(PlanReaderErrors, TruncatedLinesAndBadNumbers) {
  EXPECT_THAT(error_of("Agent 0:(1,1,0)->(1,2,"),
              HasSubstr("p.txt:1: robot 0: step 1: missing ')'; the line may be truncated"));
  EXPECT_THAT(error_of("Agent 0:(1,1)->(a,2)->"),
              HasSubstr("robot 0: step 1: '(a,2)': cell coordinates must be whole numbers"));
  EXPECT_THAT(error_of("Agent 0:(1,1,x)->"), HasSubstr("time must be a number"));
  EXPECT_THAT(error_of("Agent 0:(1,1,0)->(1,2)->"),
              HasSubstr("step 1 has 2 numbers but earlier steps have 3"));
  EXPECT_THAT(error_of("Agent 0:(1,1)(1,2)"), HasSubstr("expected '->' between steps"));
  EXPECT_THAT(error_of("Agent 0:(1,1)->\nRobot 1:(1,1)->"),
              HasSubstr("p.txt:2: expected 'Agent <i>:(...)->"));
  EXPECT_THAT(error_of("Agent x:(1,1)->"), HasSubstr("expected a robot number"));
  EXPECT_THAT(error_of("Agent 0:(1)->"), HasSubstr("must hold 2 numbers (a,b) or 3"));
}

TEST(PlanReaderErrors, RobotNumbering) {
  EXPECT_THAT(error_of("Agent 0:(1,1)->\nAgent 0:(2,2)->\n"),
              HasSubstr("p.txt:2: robot 0: robot 0 appears twice (first on line 1)"));
  EXPECT_THAT(error_of("Agent 0:(1,1)->\nAgent 3:(2,2)->\n"),
              HasSubstr("robot 1 to 2 are missing"));
  EXPECT_THAT(error_of("Agent 0:\n"), HasSubstr("robot 0: path has no steps"));
  EXPECT_THAT(error_of("\n\n"), HasSubstr("cannot tell the plan format"));
}

TEST(PlanReaderErrors, EveryProblemIsReported) {
  try {
    parse_plan("Agent 0:(1,x)->\nAgent 1:(1,1)->(2\nAgent 1:(3,3)->\n", "p.txt", xy());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().size(), 3u);
  }
}

// Regressions from fuzzing the readers: numbers past 32 bits wrapped into valid-looking values
// (4294967303 read as 7, agent4294967296 became robot 0) and YAML took `t: .inf` and a repeated
// `t:` key.
TEST(PlanReaderErrors, NumbersThatWouldWrapAreRejected) {
  EXPECT_THAT(error_of("Agent 0:(4294967303,1)->"),
              HasSubstr("cell coordinates must be between -100000 and 100000"));
  EXPECT_THAT(error_of("Agent 4294967296:(1,1)->"), HasSubstr("expected a robot number"));
  EXPECT_THAT(error_of("solution=\n0:(1,4294967297),\n", {}),
              HasSubstr("cell coordinates must be between"));
  EXPECT_THAT(error_of("schedule:\n  agent4294967296:\n    - {x: 1, y: 1, t: 0}\n", {}),
              HasSubstr("robot number too large"));
  EXPECT_THAT(error_of("schedule:\n  agent0:\n    - {x: 4294967297, y: 1, t: 0}\n", {}),
              HasSubstr("x must be between"));
}

TEST(PlanReaderErrors, YamlTimesMustBeFiniteAndKeysUnique) {
  EXPECT_THAT(error_of("schedule:\n  agent0:\n    - {x: 1, y: 1, t: .inf}\n", {}),
              HasSubstr("t must be a finite number"));
  EXPECT_THAT(error_of("schedule:\n  agent0:\n    - {x: 1, y: 1, t: 0, t: 5}\n", {}),
              HasSubstr("key 't' appears twice in one step"));
}

// Found by fuzzing (tests/fuzz/corpus/plan/regression_non_scalar_agent_name.yaml): an agent
// name that is not a plain word escaped as YAML::BadConversion instead of a plan problem.
TEST(PlanReaderErrors, YamlAgentNameThatIsNotAWordIsAProblemNotABadConversion) {
  EXPECT_THAT(error_of("schedule:\n  [agent0]:\n    - {x: 1, y: 1, t: 0}\n", {}),
              HasSubstr("an agent name must be a plain word"));
}

TEST(PlanReaderErrors, LacamAndYaml) {
  EXPECT_THAT(error_of("solution=\n0:(1,1),(2,2),\n1:(1,2),\n", {}),
              HasSubstr("timestep 1 lists 1 robots but timestep 0 lists 2"));
  EXPECT_THAT(error_of("solution=\n0:(1,1),\n2:(1,2),\n", {}),
              HasSubstr("timesteps must be consecutive"));
  EXPECT_THAT(error_of("agents=3\nsolved=0\nsolution=\n", {}), HasSubstr("unsolved"));
  EXPECT_THAT(error_of("schedule:\n  agent0:\n    - {x: 1, t: 0}\n", {}),
              HasSubstr("p.txt:3: robot 0: each step needs whole numbers x, y"));
  EXPECT_THAT(error_of("schedule: [1, 2\n", {PlanFormat::kYaml, std::nullopt}),
              HasSubstr("YAML syntax error"));
}

TEST(PlanReader, ReadsEverySmartExample) {
  const auto dir = test::benchmarks_dir() / "smart-examples";
  ASSERT_TRUE(std::filesystem::exists(dir)) << smart::test::no_benchmarks(dir);
  struct Case {
    const char* file;
    AxisOrder axis;
    std::size_t robots;
    bool timed;
    Cell robot0_start;
  };
  const Case cases[] = {
      {"example_paths_xy.txt", AxisOrder::kXY, 50, true, {5, 16}},
      {"example_paths_yx.txt", AxisOrder::kRowCol, 50, true, {5, 16}},
      {"scen_1_paths.txt", AxisOrder::kRowCol, 500, false, {143, 57}},
      {"scen_1_1000_paths.txt", AxisOrder::kRowCol, 1000, false, {143, 57}},
  };
  for (const auto& c : cases) {
    const auto p =
        parse_plan(read_text_file(dir / c.file, "plan"), c.file, {PlanFormat::kAuto, c.axis});
    EXPECT_EQ(p.paths.size(), c.robots) << c.file;
    EXPECT_EQ(p.timed, c.timed) << c.file;
    EXPECT_EQ(p.paths[0].steps[0].cell, c.robot0_start) << c.file;
  }
}

}  // namespace
}  // namespace smart::monitor
