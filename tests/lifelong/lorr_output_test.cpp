// lifelong/lorr_output.hpp: a scripted run written as the LoRR output JSON, checked field by
// field against the LoRR 2026 Start-Kit's Input_Output_Format.md, "Output File" (the table of
// properties, "Path string format" and "Delay interval format").
#include "smart/lifelong/lorr_output.hpp"

#include <gtest/gtest.h>

namespace smart::lifelong {
namespace {

using grid::ActionType;
using grid::Cell;
using grid::HalfCell;
using grid::Heading;

// Every property the document's "Output File" table lists.
const char* const kDocumentedProperties[] = {
    "actionModel",     "teamSize",       "agentMaxCounter",  "outputSegmentSize",
    "delayIntervals",  "start",          "numTaskFinished",  "sumOfCost",
    "makespan",        "actualPaths",    "plannerPaths",     "plannerTimes",
    "errors",          "actualSchedule", "plannerSchedule",  "events",
    "scheduleErrors",  "tasks",          "numPlannerErrors", "numScheduleErrors",
    "numEntryTimeouts"};

grid::Action move(uint32_t seq, Heading h, HalfCell from, HalfCell to) {
  return {0, seq, ActionType::kMove, h, from, to, 0, 0};
}
grid::Action turn(uint32_t seq, Heading h, HalfCell at) {
  return {0, seq, ActionType::kRotate, h, at, at, 0, 0};
}
results::EventRow event(double t, const char* what, std::optional<uint64_t> task,
                        std::optional<uint32_t> robot, std::optional<uint32_t> errand,
                        std::string detail = {}) {
  return {t, what, task, robot, errand, std::move(detail)};
}

// 4x3 open map; robot 0 at (x=0,y=0), robot 1 at (x=3,y=2), both facing east; 2 s = 20 ticks
// in segments of 10.
nlohmann::ordered_json scripted_run() {
  const grid::Grid g(4, 3, std::vector<uint8_t>(12, 0));
  std::vector<grid::Task> source{{0, 1, {{2, 1}, {0, 2}}}, {1, 2, {{3, 0}}}};
  LorrOutput out(g, {{0, 0}, {3, 2}}, Heading::kEast, source, 10);
  // Robot 0: east into (1,0) (its half-move to the midpoint is no LoRR action), a clockwise
  // quarter turn to the south, south into (1,1).
  out.executed(0, move(0, Heading::kEast, {0, 0}, {1, 0}), 0.35);
  out.executed(0, move(1, Heading::kEast, {1, 0}, {2, 0}), 0.5);
  out.executed(0, turn(2, Heading::kSouth, {2, 0}), 0.9);
  out.executed(0, move(3, Heading::kSouth, {2, 0}, {2, 1}), 1.2);
  out.executed(0, move(4, Heading::kSouth, {2, 1}, {2, 2}), 1.4);
  // Robot 1: a half turn (two quarter turns), then west into (2,2) in the same tick as the
  // second quarter turn: it moves to the next tick.
  out.executed(1, turn(0, Heading::kWest, {6, 4}), 0.2);
  out.executed(1, move(1, Heading::kWest, {6, 4}, {5, 4}), 0.25);
  out.executed(1, move(2, Heading::kWest, {5, 4}, {4, 4}), 0.3);
  // Planned, robot 0: a window appended at 0.1 s, then one at 1.0 s replacing it from seq 3.
  out.planned(0, move(0, Heading::kEast, {0, 0}, {1, 0}), 0.1, 0.5);
  out.planned(0, move(1, Heading::kEast, {1, 0}, {2, 0}), 0.1, 1);
  out.planned(0, turn(2, Heading::kSouth, {2, 0}), 0.1, 1);
  out.planned(0, move(3, Heading::kSouth, {2, 0}, {2, 1}), 0.1, 1.5);
  out.planned(0, move(4, Heading::kSouth, {2, 1}, {2, 2}), 0.1, 2);
  out.planned(0, turn(3, Heading::kEast, {2, 0}), 1.0, 0);
  out.planned(0, move(4, Heading::kEast, {2, 0}, {3, 0}), 1.0, 0.5);
  out.planned(0, move(5, Heading::kEast, {3, 0}, {4, 0}), 1.0, 1);
  for (const auto& e :
       {event(0, "revealed", 0, {}, {}), event(0, "revealed", 1, {}, {}),
        event(0.05, "assigned", 0, 0, {}), event(1.0, "opened", 0, 0, 0),
        event(1.5, "finished", 0, 0, 1), event(1.52, "assigned", 1, 0, {}),
        event(1.6, "refused", {}, {}, {}, "--planner-cmd window 3 refused: late: no reply"),
        event(1.7, "refused", {}, {}, {}, "robots 0 and 1 collide at (x=1,y=0) at step 2")}) {
    out.on_event(e);
  }
  out.on_planner_call({1.0, 0, 0, 2.5, 0, 1});
  out.on_planner_call({2.0, 1, 1, 1.0, 0, 1});
  LorrRunEnd end;
  end.duration_s = 2.0;
  end.tasks_finished = 1;
  end.delay_intervals = {{{3, 5}}, {}};
  end.collisions = {{0, 1, 1.23}};
  return out.json(end);
}

TEST(LorrOutput, HasEveryDocumentedPropertyWithItsType) {
  const auto j = scripted_run();
  for (const char* key : kDocumentedProperties) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["actionModel"], "MAPF_T");  // "this value is always MAPF_T"
  for (const char* key :
       {"teamSize", "agentMaxCounter", "outputSegmentSize", "numTaskFinished", "sumOfCost",
        "makespan", "numPlannerErrors", "numScheduleErrors", "numEntryTimeouts"}) {
    EXPECT_TRUE(j[key].is_number_integer()) << key;
  }
  for (const char* key : {"delayIntervals", "start", "actualPaths", "plannerPaths",
                          "actualSchedule", "plannerSchedule"}) {
    ASSERT_TRUE(j[key].is_array()) << key;
    EXPECT_EQ(j[key].size(), 2u) << key << ": one entry per robot";
  }
  EXPECT_EQ(j["discretisation"]["tick_s"], 0.1);  // and it says it was discretised
}

TEST(LorrOutput, CountsAndTimeAreInTicks) {
  const auto j = scripted_run();
  EXPECT_EQ(j["teamSize"], 2);
  EXPECT_EQ(j["agentMaxCounter"], 1);  // one tick per action
  EXPECT_EQ(j["outputSegmentSize"], 10);
  EXPECT_EQ(j["makespan"], 20);  // 2 s of 0.1 s ticks
  EXPECT_EQ(j["numTaskFinished"], 1);
  EXPECT_EQ(j["sumOfCost"], 6);  // robot 0: F R F, robot 1: R R F
  EXPECT_EQ(j["numPlannerErrors"], 1);
  EXPECT_EQ(j["numEntryTimeouts"], 1);  // the late window
  EXPECT_EQ(j["numScheduleErrors"], 0);
  EXPECT_EQ(j["plannerTimes"], nlohmann::ordered_json::array({0.0025, 0.001}));  // seconds
}

// "Path string format": segments [(t,row,col,ori,counter):(A d,...)], each opening with the
// robot's state at its first tick; orientation 0 east, 1 south, 2 west, 3 north.
TEST(LorrOutput, PathsAreSegmentsOfRunLengthActionsWithTheirStartState) {
  const auto j = scripted_run();
  EXPECT_EQ(j["actualPaths"][0], "[(0,0,0,0,0):(W 5,F 1,W 3,R 1)][(10,0,1,1,0):(W 4,F 1,W 5)]");
  EXPECT_EQ(j["actualPaths"][1], "[(0,2,3,0,0):(W 2,R 2,F 1,W 5)][(10,2,2,2,0):(W 10)]");
  // Window 1 at tick 1: F at step 1 (tick 2), the turn also at step 1 (to tick 3); window 2 at
  // tick 10 replaced its move south (seq 4) with a counter-clockwise turn and a move east.
  EXPECT_EQ(j["plannerPaths"][0], "[(0,0,0,0,0):(W 2,F 1,R 1,W 6)][(10,0,1,1,0):(C 1,F 1,W 8)]");
  EXPECT_EQ(j["plannerPaths"][1], "[(0,2,3,0,0):(W 10)][(10,2,3,0,0):(W 10)]");
}

TEST(LorrOutput, StartsTasksEventsSchedulesDelaysAndErrorsAsDocumented) {
  const auto j = scripted_run();
  // start: [row, col, orientation letter] per robot.
  EXPECT_EQ(j["start"], nlohmann::ordered_json::parse(R"([[0, 0, "E"], [2, 3, "E"]])"));
  // tasks: [id, release time, [row, col, row, col, ...]] in errand order.
  EXPECT_EQ(j["tasks"], nlohmann::ordered_json::parse(R"([[0, 0, [1, 2, 2, 0]], [1, 0, [0, 3]]])"));
  // events: [timestep, agent, task, errands done] at each errand reached.
  EXPECT_EQ(j["events"], nlohmann::ordered_json::parse("[[10, 0, 0, 1], [15, 0, 0, 2]]"));
  // schedules: "t:task" at each change, the last of a tick kept ("15:-1" then "15:1": "15:1").
  EXPECT_EQ(j["actualSchedule"], nlohmann::ordered_json::parse(R"(["0:0,15:1", ""])"));
  EXPECT_EQ(j["plannerSchedule"], j["actualSchedule"]);
  // delayIntervals: per robot [[start, end], ...].
  EXPECT_EQ(j["delayIntervals"], nlohmann::ordered_json::parse("[[[3, 5]], []]"));
  // errors: [task_id, robot1, robot2, timestep, description].
  ASSERT_EQ(j["errors"].size(), 1u);
  EXPECT_EQ(j["errors"][0][0], -1);
  EXPECT_EQ(j["errors"][0][1], 0);
  EXPECT_EQ(j["errors"][0][2], 1);
  EXPECT_EQ(j["errors"][0][3], 12);
  EXPECT_TRUE(j["errors"][0][4].is_string());
  EXPECT_EQ(j["scheduleErrors"], nlohmann::ordered_json::array());
}

TEST(LorrOutput, TicksHoldTheirTenthOfASecond) {
  EXPECT_EQ(lorr_tick(0), 0);
  EXPECT_EQ(lorr_tick(0.3), 3);  // 0.3 / 0.1 is 2.9999999999999996 in doubles
  EXPECT_EQ(lorr_tick(0.39), 3);
  EXPECT_EQ(lorr_tick(600), 6000);
}

}  // namespace
}  // namespace smart::lifelong
