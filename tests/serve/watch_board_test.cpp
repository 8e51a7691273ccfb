// What `smart serve --watch` shows, from scripted samples: no DDS, no clock.
#include "smart/serve/watch_board.hpp"

#include <gtest/gtest.h>

namespace smart::serve {
namespace {

WatchedState state(uint32_t robot, uint64_t run, double x, double v = 0) {
  WatchedState s;
  s.robot = robot, s.run_id = run, s.x_m = x, s.y_m = 2, s.linear_mps = v, s.sim_time_s = x;
  s.queue = robot + 1;
  return s;
}

TEST(WatchBoard, ShowsTheRunHeardOfMostRecentlyWithEveryRobotsStatus) {
  WatchBoard b(3.0);
  b.on_state(state(0, 7, 1.0, 0.5), 0.0);
  b.on_state(state(1, 7, 2.0), 0.0);
  b.on_progress({1, 7, 4, 5}, 0.1);
  b.on_monitor({7, "lab-pc", 1234, "lab-morning"}, 0.1);
  auto j = b.snapshot(0.2);
  EXPECT_EQ(j["run_id"], 7);
  EXPECT_EQ(j["name"], "lab-morning");
  EXPECT_EQ(j["runs"][0]["name"], "lab-morning");
  EXPECT_EQ(j["monitor"]["host"], "lab-pc");
  ASSERT_EQ(j["robots"].size(), 2u);
  EXPECT_EQ(j["robots"][0]["status"], "waiting");  // queued, no action executing
  EXPECT_EQ(j["robots"][1]["status"], "moving");   // executing action 5
  EXPECT_EQ(j["robots"][1]["finished_seq"], 4);
  EXPECT_EQ(j["robots"][1]["executing_seq"], 5);
  EXPECT_EQ(j["robots"][1]["queue"], 2);
  EXPECT_DOUBLE_EQ(j["t_s"].get<double>(), 2.0);
  // Another run starts: it is shown; the first can still be asked for.
  b.on_state(state(0, 9, 5.0), 1.0);
  EXPECT_EQ(b.snapshot(1.0)["run_id"], 9);
  EXPECT_EQ(b.snapshot(1.0, 7)["robots"].size(), 2u);
  EXPECT_EQ(b.snapshot(1.0)["runs"].size(), 2u);
  EXPECT_TRUE(b.snapshot(1.0)["monitor"].is_null());
  EXPECT_EQ(b.snapshot(1.0)["name"], "");  // its monitor not heard yet
  // Nothing heard of run 9's robot for longer than stale_s.
  EXPECT_EQ(b.snapshot(4.5)["robots"][0]["status"], "stale");
}

// Issue 26: a JetBot's Vicon noise (a few degrees a second) showed every robot "moving" at
// 0 m/s; the status now comes from what the host says it does.
TEST(WatchBoard, ARobotIsMovingWhenItExecutesNotWhenItsPoseJitters) {
  WatchBoard b(3.0);
  auto jitter = state(0, 7, 1.0);
  jitter.angular_radps = 0.35;
  jitter.queue = 0;
  b.on_state(jitter, 0.0);
  b.on_progress({0, 7, 9, -1}, 0.0);
  EXPECT_EQ(b.snapshot(0.1)["robots"][0]["status"], "idle");
  jitter.queue = 3;
  b.on_state(jitter, 0.2);
  EXPECT_EQ(b.snapshot(0.3)["robots"][0]["status"], "waiting");
  b.on_progress({0, 7, 9, 10}, 0.4);
  EXPECT_EQ(b.snapshot(0.5)["robots"][0]["status"], "moving");
}

TEST(WatchBoard, AFloodOfMadeUpIdsAndRunsStaysBounded) {
  WatchBoard b;
  for (uint32_t i = 0; i < WatchBoard::kMaxRobots + 50; ++i) b.on_state(state(i, 1, 0), 0);
  EXPECT_EQ(b.snapshot(0)["robots"].size(), WatchBoard::kMaxRobots);
  for (uint64_t run = 2; run < 2 + 2 * WatchBoard::kMaxRuns; ++run) {
    b.on_monitor({run, "x", 1, "r"}, double(run));
  }
  EXPECT_EQ(b.snapshot(100)["runs"].size(), WatchBoard::kMaxRuns);
  b.on_state(state(5, 99, 1.0), 200);  // robots of dropped runs are counted out again
  EXPECT_EQ(b.snapshot(200)["robots"].size(), 1u);
}

}  // namespace
}  // namespace smart::serve
