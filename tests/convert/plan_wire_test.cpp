// convert/plan_wire.hpp: lifelong planning samples built and read back, and every reason a
// received one is refused.
#include "smart/convert/plan_wire.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

namespace smart::wire {
namespace {

using ::testing::HasSubstr;

// 4x3, one obstacle at (1,1).
grid::Grid tiny_grid() {
  std::vector<uint8_t> blocked(12, 0);
  blocked[1 * 4 + 1] = 1;
  return grid::Grid(4, 3, blocked);
}

smart_msg_PlannerInfo planner(uint64_t id, uint64_t started_ms, const char* name = "pibt") {
  smart_msg_PlannerInfo p{};
  p.planner_id = id;
  p.started_ms = started_ms;
  p.pid = 42;
  std::strcpy(p.name, name);
  std::strcpy(p.host, "lab-1");
  return p;
}

planning::WindowRequest two_robots() {
  planning::WindowRequest r;
  r.start = {{0, 0}, {3, 2}};
  r.goals = {{{2, 0}, {3, 0}}, {}};
  r.heading = {grid::Heading::kSouth, grid::Heading::kWest};
  r.steps = 2;
  r.time_s = 12.5;
  return r;
}

TEST(PlanWire, TheProblemCarriesTheMapAndTheChosenPlanner) {
  const auto g = tiny_grid();
  PlanProblemBuffer buf(7, planner(9, 100), g, 2, 10);
  const auto& p = buf.view();
  EXPECT_EQ(check_problem(p), "");
  EXPECT_EQ(p.planner.planner_id, 9u);
  EXPECT_EQ(p.robots, 2u);
  EXPECT_EQ(p.window_steps, 10u);
  const auto back = grid_of(p);
  ASSERT_EQ(back.width(), 4);
  ASSERT_EQ(back.height(), 3);
  for (int32_t y = 0; y < 3; ++y) {
    for (int32_t x = 0; x < 4; ++x) EXPECT_EQ(back.blocked({x, y}), g.blocked({x, y}));
  }
}

TEST(PlanWire, AProblemIsRefusedForEachBadField) {
  const auto g = tiny_grid();
  PlanProblemBuffer buf(7, planner(9, 100), g, 2, 10);
  auto p = buf.view();
  p.run_id = 0;
  EXPECT_THAT(check_problem(p), HasSubstr("run id 0"));
  p = buf.view();
  p.width = 5;
  EXPECT_THAT(check_problem(p), HasSubstr("blocked has 12 bytes for a 5x3 map"));
  p = buf.view();
  p.width = 1u << 16;
  p.height = 1u << 16;
  EXPECT_THAT(check_problem(p), HasSubstr("larger than MAX_PLAN_CELLS"));
  p = buf.view();
  p.blocked._buffer[3] = 2;
  EXPECT_THAT(check_problem(p), HasSubstr("blocked[3] is neither 0 nor 1"));
  p.blocked._buffer[3] = 0;
  p.robots = 0;
  EXPECT_THAT(check_problem(p), HasSubstr("robots 0"));
  p = buf.view();
  p.window_steps = 1001;
  EXPECT_THAT(check_problem(p), HasSubstr("window_steps 1001"));
  p = buf.view();
  p.planner.name[0] = '\x1b';
  EXPECT_THAT(check_problem(p), HasSubstr("planner: planner name has a non-printable byte"));
}

TEST(PlanWire, ARequestRoundTripsStartsHeadingsErrandsAndTime) {
  const auto g = tiny_grid();
  PlanRequestBuffer buf;
  buf.set(7, 9, 3, 0.25, two_robots());
  const auto& m = buf.view();
  EXPECT_EQ(m.window, 3u);
  EXPECT_EQ(m.planner_id, 9u);
  EXPECT_DOUBLE_EQ(m.budget_s, 0.25);
  ASSERT_EQ(check_request(m, g, 2), "");
  const auto r = request_of(m);
  const auto want = two_robots();
  EXPECT_EQ(r.start, want.start);
  EXPECT_EQ(r.goals, want.goals);
  EXPECT_EQ(r.heading, want.heading);
  EXPECT_EQ(r.steps, 2);
  EXPECT_DOUBLE_EQ(r.time_s, 12.5);
}

TEST(PlanWire, ARequestIsRefusedForEachBadField) {
  const auto g = tiny_grid();
  PlanRequestBuffer buf;
  buf.set(7, 9, 3, 0.25, two_robots());
  EXPECT_THAT(check_request(buf.view(), g, 3), HasSubstr("starts has 2 entries for 3 robots"));
  auto m = buf.view();
  m.window = 0;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("window 0"));
  m = buf.view();
  m.steps = 0;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("steps 0 is not 1..MAX_PLAN_STEPS"));
  m = buf.view();
  m.starts._buffer[1].x = 4;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("robot 1: start (x=4,y=2) is off the 4x3 map"));
  m.starts._buffer[1].x = 3;
  m.headings._buffer[0] = 4;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("robot 0: heading is not 0..3"));
  m.headings._buffer[0] = 3;
  m.errand_counts._buffer[1] = 1;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("errand_counts add up to 3 but errands has 2"));
  m.errand_counts._buffer[1] = 0;
  m.errands._buffer[1].y = -1;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("errands[1]: (x=3,y=-1) is off the 4x3 map"));
  m = buf.view();
  m.errand_counts._buffer[0] = 65;
  EXPECT_THAT(check_request(m, g, 2), HasSubstr("65 errands, over MAX_PLAN_ERRANDS"));
}

TEST(PlanWire, AReplyRoundTripsPathsOrAnError) {
  const std::vector<std::vector<grid::Cell>> paths{{{0, 0}, {1, 0}, {2, 0}},
                                                   {{3, 2}, {3, 2}, {2, 2}}};
  PlanReplyBuffer buf;
  buf.set_paths(9, 7, 3, paths);
  EXPECT_EQ(check_reply(buf.view(), 2, 2), "");
  EXPECT_EQ(buf.view().window, 3u);
  EXPECT_EQ(paths_of(buf.view()), paths);
  buf.set_error(9, 7, 4, "no path for robot 1 \xe2\x80\x94 goal walled in");
  const auto& e = buf.view();
  EXPECT_EQ(check_reply(e, 2, 2), "");
  EXPECT_STREQ(e.error, "no path for robot 1 ??? goal walled in");  // printable on the wire
  EXPECT_TRUE(paths_of(e).empty());
}

TEST(PlanWire, AReplyIsRefusedForEachBadField) {
  PlanReplyBuffer buf;
  buf.set_paths(9, 7, 3, {{{0, 0}, {1, 0}, {2, 0}}, {{3, 2}, {3, 2}, {2, 2}}});
  EXPECT_THAT(check_reply(buf.view(), 2, 3), HasSubstr("steps 2 where the request asked for 3"));
  EXPECT_THAT(check_reply(buf.view(), 3, 2),
              HasSubstr("cells has 6 entries, not 3 robots x 3 steps"));
  auto m = buf.view();
  std::strcpy(m.error, "bad\x07");
  EXPECT_THAT(check_reply(m, 2, 2), HasSubstr("error has a non-printable byte (7 at 3)"));
  std::strcpy(m.error, "oops");
  EXPECT_THAT(check_reply(m, 2, 2), HasSubstr("an error and cells in one reply"));
}

TEST(PlanWire, TheEarliestStartedPlannerIsChosenThenTheSmallestId) {
  EXPECT_EQ(choose_planner({planner(5, 200), planner(9, 100), planner(3, 300)}), 1u);
  EXPECT_EQ(choose_planner({planner(9, 100), planner(4, 100)}), 1u);
}

TEST(PlanWire, AnnouncementsAreRefusedWithoutIdPidOrPrintableNames) {
  EXPECT_EQ(check_planner_info(planner(5, 1)), "");
  EXPECT_THAT(check_planner_info(planner(0, 1)), HasSubstr("planner id 0"));
  auto p = planner(5, 1);
  p.pid = 0;
  EXPECT_THAT(check_planner_info(p), HasSubstr("pid 0 is not a process id"));
  p = planner(5, 1, "\x1b[2J");
  EXPECT_THAT(check_planner_info(p), HasSubstr("planner name has a non-printable byte (27 at 0)"));
  EXPECT_EQ(describe_planner(planner(5, 1)), "planner 'pibt' (pid 42 on lab-1)");
}

}  // namespace
}  // namespace smart::wire
