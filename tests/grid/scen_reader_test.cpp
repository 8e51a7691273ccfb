#include "smart/grid/scen_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::grid {
namespace {

using ::testing::HasSubstr;

const char* kScen =
    "version 1\n"
    "0\tm.map\t4\t3\t0\t0\t3\t2\t5.0\n"
    "0\tm.map\t4\t3\t1\t0\t2\t2\t3.4\n"
    "0\tm.map\t4\t3\t3\t0\t0\t2\t4.2\n";

std::string scen_error_of(const std::string& text, std::size_t k = 0) {
  try {
    parse_scen(text, "s.scen", k);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ScenReader, XIsColumnYIsRow) {
  const auto s = parse_scen(kScen, "s.scen");
  ASSERT_EQ(s.agents.size(), 3u);
  EXPECT_EQ(s.map_width, 4);
  EXPECT_EQ(s.map_height, 3);
  EXPECT_EQ(s.agents[1].start, (Cell{1, 0}));
  EXPECT_EQ(s.agents[1].goal, (Cell{2, 2}));
  EXPECT_EQ(s.agents[1].line, 3);
}

TEST(ScenReader, FirstKAgents) {
  EXPECT_EQ(parse_scen(kScen, "s.scen", 2).agents.size(), 2u);
  EXPECT_THAT(scen_error_of(kScen, 5), HasSubstr("asked for 5 agents but the file has 3"));
}

TEST(ScenReaderErrors, MalformedLines) {
  EXPECT_THAT(scen_error_of("0\tm.map\n"), HasSubstr("s.scen:1: missing 'version 1'"));
  EXPECT_THAT(scen_error_of("version 1\n0\tm.map\t4\t3\t0\t0\n"),
              HasSubstr("s.scen:2: expected 9 tab-separated fields"));
  EXPECT_THAT(scen_error_of("version 1\n0\tm.map\t4\t3\tx\t0\t3\t2\t5\n"),
              HasSubstr("s.scen:2: start_x is 'x'"));
  EXPECT_THAT(scen_error_of("version 1\n0\tm.map\t4\t3\t0\t0\t3\t-2\t5\n"),
              HasSubstr("goal_y is '-2'"));
  EXPECT_THAT(scen_error_of("version 1\n"), HasSubstr("lists no agents"));
}

// Regressions from fuzzing: 4294967303 was read as 7, and a later row could name another map.
TEST(ScenReaderErrors, CoordinatesThatWouldWrapAndMixedMapSizes) {
  EXPECT_THAT(scen_error_of("version 1\n0\tm.map\t4\t3\t4294967303\t0\t3\t2\t5\n"),
              HasSubstr("start_x is '4294967303'; it must be a whole number from 0 to 100000"));
  EXPECT_THAT(scen_error_of("version 1\n0\tm.map\t4\t3\t0\t0\t3\t2\t5\n"
                            "0\tm.map\t8\t3\t0\t1\t3\t1\t3\n"),
              HasSubstr("s.scen:3: map size 8x3 differs from the 4x3 of the first row"));
}

TEST(ScenReaderErrors, AgainstTheMap) {
  const auto grid = test::grid_of({"..@.", "....", "...."});
  auto s = parse_scen(
      "version 1\n0\tm.map\t4\t3\t2\t0\t3\t2\t5\n0\tm.map\t4\t3\t3\t0\t9\t2\t5\n"
      "0\tm.map\t4\t3\t3\t0\t0\t0\t5\n",
      "s.scen");
  const auto problems = check_scen_against_map(s, grid);
  std::string all;
  for (const auto& p : problems) all += p.to_string() + "\n";
  EXPECT_THAT(all, HasSubstr("s.scen:2: robot 0: start (x=2,y=0) is an obstacle"));
  EXPECT_THAT(all, HasSubstr("s.scen:3: robot 1: goal (x=9,y=2) is outside the 4x3 map"));
  EXPECT_THAT(all, HasSubstr("s.scen:4: robot 2: start (x=3,y=0) is also robot 1's start"));
  s.map_width = 5;
  EXPECT_THAT(check_scen_against_map(s, grid)[0].message, HasSubstr("pass the matching --map"));
}

TEST(ScenReader, ReadsEveryBenchmarkScenarioAgainstItsMap) {
  const auto dir = test::benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(dir / "scens")) << smart::test::no_benchmarks(dir);
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "scens")) {
    const auto name = entry.path().filename().string();
    const auto s = parse_scen(read_text_file(entry.path(), "scen"), name);
    const auto grid = parse_map(read_text_file(dir / "maps" / s.map_name, "map"), s.map_name);
    const auto problems = check_scen_against_map(s, grid);
    EXPECT_TRUE(problems.empty()) << name << ": " << problems.front().to_string();
    EXPECT_GE(s.agents.size(), 100u) << name;
    ++files;
  }
  EXPECT_EQ(files, 45u);
}

}  // namespace
}  // namespace smart::grid
