#include "smart/lifelong/plan_protocol.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace smart::lifelong {
namespace {

using grid::Cell;
using Paths = std::vector<std::vector<Cell>>;
using Kind = PlanReply::Kind;

// 4 x 3, an obstacle at (1, 1).
grid::Grid small_map() {
  std::vector<uint8_t> blocked(12, 0);
  blocked[1 * 4 + 1] = 1;
  return {4, 3, blocked};
}

planning::WindowRequest two_robots() {
  planning::WindowRequest r{{{0, 0}, {3, 0}}, {{{3, 0}}, {}}, 2};
  r.heading = {grid::Heading::kEast, grid::Heading::kNorth};
  r.time_s = 12.5;
  return r;
}

TEST(PlanProtocol, TheStartLineCarriesTheMapAsRowsOfFreeAndBlockedCells) {
  const auto j = nlohmann::json::parse(encode_start(small_map(), 2, 10));
  EXPECT_EQ(j["type"], "start");
  EXPECT_EQ(j["protocol"], "smart-plan/1");
  EXPECT_EQ(j["map"]["width"], 4);
  EXPECT_EQ(j["map"]["height"], 3);
  EXPECT_EQ(j["map"]["rows"], nlohmann::json::array({"....", ".@..", "...."}));
  EXPECT_EQ(j["robots"], 2);
  EXPECT_EQ(j["window_steps"], 10);
}

TEST(PlanProtocol, ARequestCarriesEachRobotsCutStateAndErrands) {
  const std::string line = encode_request(7, 12.5, 0.25, two_robots());
  EXPECT_EQ(line.find('\n'), std::string::npos);  // one line
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(j["type"], "request");
  EXPECT_EQ(j["window"], 7);
  EXPECT_EQ(j["time_s"], 12.5);
  EXPECT_EQ(j["budget_s"], 0.25);
  EXPECT_EQ(j["steps"], 2);
  ASSERT_EQ(j["robots"].size(), 2u);
  EXPECT_EQ(j["robots"][0]["cell"], nlohmann::json::array({0, 0}));
  EXPECT_EQ(j["robots"][0]["heading"], "east");
  EXPECT_EQ(j["robots"][0]["errands"], nlohmann::json::parse("[[3,0]]"));
  EXPECT_EQ(j["robots"][1]["heading"], "north");
  EXPECT_TRUE(j["robots"][1]["errands"].empty());
}

TEST(PlanProtocol, TheReadyLineMayNameThePlanner) {
  EXPECT_EQ(decode_ready(R"({"type":"ready","name":"greedy"})").name, "greedy");
  EXPECT_TRUE(decode_ready(R"({"type":"ready"})").ok);
  const auto wrong = decode_ready(R"({"window":1,"paths":[]})");
  EXPECT_FALSE(wrong.ok);
  EXPECT_NE(wrong.reason.find("the first line a planner writes is {\"type\": \"ready\"}"),
            std::string::npos)
      << wrong.reason;
  EXPECT_FALSE(decode_ready("hello").ok);
}

TEST(PlanProtocol, AReplyToTheWindowGivesItsPaths) {
  const auto r = decode_reply(R"({"window":3,"paths":[[[0,0],[1,0]],[[3,0],[3,0]]]})", 3, 2);
  ASSERT_EQ(r.kind, Kind::kWindow) << r.reason;
  EXPECT_EQ(r.paths, (Paths{{{0, 0}, {1, 0}}, {{3, 0}, {3, 0}}}));
}

TEST(PlanProtocol, AReplyToAnEarlierWindowIsStale) {
  EXPECT_EQ(decode_reply(R"({"window":2,"paths":[]})", 3, 2).kind, Kind::kStale);
}

TEST(PlanProtocol, ThePlannersOwnErrorIsPassedOn) {
  const auto r = decode_reply(R"({"window":3,"error":"no path for robot 1"})", 3, 2);
  EXPECT_EQ(r.kind, Kind::kPlannerError);
  EXPECT_EQ(r.reason, "the planner could not plan: no path for robot 1");
}

TEST(PlanProtocol, MalformedRepliesSayWhatIsWrong) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"not json", "not JSON"},
      {"[1,2]", "not a JSON object"},
      {R"({"paths":[]})", "no \"window\" number"},
      {R"({"window":-1})", "no \"window\" number"},
      {R"({"window":9,"paths":[]})", "\"window\" 9 was never requested"},
      {R"({"window":3})", "no \"paths\" array"},
      {R"({"window":3,"paths":[[]]})", "1 paths for 2 robots"},
      {R"({"window":3,"paths":[[[0,0]],{"x":1}]})", "paths[1] is not an array"},
      {R"({"window":3,"paths":[[[0,0]],[[3,0],[3]]]})", "robot 1 step 1: a cell is [x, y]"},
      {R"({"window":3,"paths":[[[0,0]],[[3,0.5]]]})", "robot 1 step 0: a cell is [x, y]"},
      {R"({"window":3,"paths":[[[0,0]],[[99999999999,0]]]})",
       "robot 1 step 0: cell [99999999999, 0] is far off the map"},
  };
  for (const auto& [line, why] : cases) {
    const auto r = decode_reply(line, 3, 2);
    EXPECT_EQ(r.kind, Kind::kMalformed) << line;
    EXPECT_NE(r.reason.find("malformed reply: " + why), std::string::npos)
        << line << " -> " << r.reason;
  }
}

TEST(PlanProtocol, AValidWindowPassesTheCheck) {
  EXPECT_EQ(
      check_window(small_map(), two_robots(), {{{0, 0}, {1, 0}, {2, 0}}, {{3, 0}, {3, 1}, {3, 2}}}),
      "");
}

TEST(PlanProtocol, AWindowThatBreaksARuleIsRefusedNamingRobotStepAndCell) {
  const std::vector<std::pair<Paths, std::string>> cases{
      {{{{0, 0}, {1, 0}}, {{3, 0}, {3, 1}, {3, 2}}},
       "robot 0 has 2 cells; a window is 3 (the cut cell and one per step)"},
      {{{{0, 1}, {0, 0}, {0, 0}}, {{3, 0}, {3, 0}, {3, 0}}},
       "robot 0 starts at (x=0,y=1), not at its cut cell (x=0,y=0)"},
      {{{{0, 0}, {-1, 0}, {0, 0}}, {{3, 0}, {3, 0}, {3, 0}}},
       "robot 0 step 1 leaves the map at (x=-1,y=0)"},
      {{{{0, 0}, {0, 1}, {1, 1}}, {{3, 0}, {3, 0}, {3, 0}}},
       "robot 0 step 2 enters an obstacle at (x=1,y=1)"},
      {{{{0, 0}, {2, 0}, {2, 0}}, {{3, 0}, {3, 0}, {3, 0}}},
       "robot 0 step 1 jumps from (x=0,y=0) to (x=2,y=0) (one cell a step at most)"},
      {{{{0, 0}, {1, 0}, {2, 0}}, {{3, 0}, {2, 0}, {2, 0}}},
       "robots 0 and 1 collide at (x=2,y=0) at step 2"},
      {{{{0, 0}, {1, 0}, {2, 0}}, {{3, 0}, {2, 0}, {1, 0}}},
       "robots 0 and 1 swap cells (x=1,y=0) and (x=2,y=0) at step 2"},
      {{{{0, 0}, {1, 0}, {2, 0}}}, "1 paths for 2 robots"},
  };
  for (const auto& [paths, why] : cases) {
    EXPECT_EQ(check_window(small_map(), two_robots(), paths), why);
  }
}

}  // namespace
}  // namespace smart::lifelong
