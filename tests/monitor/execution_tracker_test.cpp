#include "smart/monitor/execution_tracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <optional>
#include <random>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/planning/random_plan.hpp"
#include "support/following_fixture.hpp"

namespace smart::monitor {
namespace {

using R = ExecutionTracker::Result;

using test::Following;

TEST(ExecutionTracker, InitialEnqueueFollowsThePaperRule) {
  Following f;
  ExecutionTracker t(f.actions, f.adg);
  EXPECT_EQ(t.enqueued(0), 4u);
  EXPECT_EQ(t.enqueued(1), 1u);
  EXPECT_EQ(t.state(1, 0), ActionState::kEnqueued);
  EXPECT_EQ(t.state(1, 1), ActionState::kStaged);
  const auto w = t.window(0, 2);
  EXPECT_EQ(w.first, 0u);
  EXPECT_EQ(w.end, 2u);  // look-ahead cap
}

TEST(ExecutionTracker, FinishingReleasesTheOtherRobot) {
  Following f;
  ExecutionTracker t(f.actions, f.adg);
  auto u = t.on_progress(0, 0);
  EXPECT_EQ(u.result, R::kAdvanced);
  EXPECT_EQ(u.robots_changed, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(t.enqueued(1), 2u);
  EXPECT_EQ(t.state(0, 0), ActionState::kFinished);
  EXPECT_EQ(t.window(0, 10).first, 1u);
}

TEST(ExecutionTracker, AWaitingRobotIsToldWhatItsBlockerDoes) {
  Following f;
  ExecutionTracker t(f.actions, f.adg);
  EXPECT_EQ(t.wait_cause(1), std::nullopt) << "its first half-move is enqueued";
  t.on_progress(1, 0);
  // Robot 1 waits to enter (1,0), where robot 0 stands and is moving out.
  EXPECT_EQ(t.wait_cause(1), WaitCause::kAtLocation);
  t.on_progress(0, 0);
  EXPECT_EQ(t.wait_cause(1), std::nullopt);
  t.on_progress(0, 3);
  EXPECT_EQ(t.wait_cause(0), std::nullopt) << "done: it does not wait";
}

TEST(ExecutionTracker, ProgressIsCumulative) {
  Following f;
  ExecutionTracker t(f.actions, f.adg);
  EXPECT_EQ(t.on_progress(0, 3).result, R::kAdvanced);
  EXPECT_EQ(t.finished(0), 4u);
  EXPECT_TRUE(t.robot_done(0));
  EXPECT_EQ(t.enqueued(1), 4u);
  EXPECT_EQ(t.finished_total(), 4u);
  EXPECT_EQ(t.on_progress(1, 3).result, R::kAdvanced);
  EXPECT_TRUE(t.complete());
  EXPECT_FALSE(t.deadlocked());
}

TEST(ExecutionTracker, StaleOutOfRangeAndNeverEnqueuedChangeNothing) {
  Following f;
  ExecutionTracker t(f.actions, f.adg);
  ASSERT_EQ(t.on_progress(0, 1).result, R::kAdvanced);
  const auto before_enqueued = t.enqueued(1);
  auto stale = t.on_progress(0, 0);  // a duplicate or reordered old report
  EXPECT_EQ(stale.result, R::kStale);
  EXPECT_TRUE(stale.robots_changed.empty());
  EXPECT_EQ(t.on_progress(0, -1).result, R::kStale);
  auto never = t.on_progress(1, 3);
  EXPECT_EQ(never.result, R::kRejected);
  EXPECT_NE(never.reason.find("were enqueued"), std::string::npos);
  EXPECT_EQ(t.on_progress(0, 4).result, R::kRejected);
  EXPECT_EQ(t.on_progress(2, 0).result, R::kRejected);
  EXPECT_EQ(t.finished(0), 2u);
  EXPECT_EQ(t.finished(1), 0u);
  EXPECT_EQ(t.enqueued(1), before_enqueued);
  EXPECT_EQ(t.finished_total(), 2u);
}

TEST(ExecutionTracker, DeadlockWhenNothingIsEnqueuedButWorkRemains) {
  // A swap plan gives a cyclic ADG: nobody can start.
  const auto grid = test::grid_of({"..."});
  const auto actions = build_actions(test::plan_of({{{0, 0}, {1, 0}}, {{1, 0}, {0, 0}}}));
  std::vector<Problem> problems;
  const auto adg = build_adg(actions, grid, "p", problems);
  ExecutionTracker t(actions, adg);
  // Robot 0 may take its first half-move, robot 1 its rotation (it faces east, moves west);
  // after that each waits for the other.
  ASSERT_EQ(t.enqueued(0), 1u);
  ASSERT_EQ(t.enqueued(1), 1u);
  ASSERT_EQ(t.on_progress(0, 0).result, R::kAdvanced);
  ASSERT_EQ(t.on_progress(1, 0).result, R::kAdvanced);
  EXPECT_EQ(t.enqueued(0), 1u);
  EXPECT_EQ(t.enqueued(1), 1u);
  EXPECT_FALSE(t.complete());
  EXPECT_TRUE(t.deadlocked());
}

// wait_cause() reads each blocker from a per-node record and a per-robot turn flag kept on
// progress (2026-12-08: the walk back over the plan's actions took 6.7 % of the monitor's CPU
// under delays). On random plans, at every step of a random order of reports, it tells what
// half_cell_blocker_cause tells walking the actions, for every robot.
TEST(ExecutionTrackerProperty, WaitCausesFromTheRecordsAreThoseOfTheActionsWalked) {
  std::map<WaitCause, std::size_t> seen;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    const auto grid = planning::generate_random_grid(10, 10, 0.15, seed);
    const auto inst = planning::generate_random_plan(grid, {12, 25, seed, 0.7, 0.3});
    const auto actions = build_actions(inst.plan, grid::Heading::kEast);
    std::vector<grid::Problem> problems;
    const auto adg = build_adg(actions, grid, "random", problems);
    ASSERT_TRUE(problems.empty());
    ExecutionTracker t(actions, adg);
    const auto walked = [&](uint32_t r) -> std::optional<WaitCause> {
      if (t.robot_done(r) || t.enqueued(r) > t.finished(r)) return std::nullopt;
      const uint32_t node = actions.offset[r] + t.enqueued(r);
      std::optional<WaitCause> cause;
      for (uint32_t e = adg.in_begin[node]; e < adg.in_begin[node + 1]; ++e) {
        const grid::Action& leave = actions.actions[adg.in[e]];
        const uint32_t i = leave.robot;
        if (leave.seq < t.finished(i)) continue;
        const auto c = half_cell_blocker_cause(leave.seq, t.finished(i), t.enqueued(i),
                                               SwitchOptions{}.commit_actions,
                                               [&](uint32_t s) { return actions.at(i, s).type; });
        cause = std::max(cause.value_or(WaitCause::kAtLocation), c);
      }
      return cause.value_or(WaitCause::kHeld);
    };
    while (!t.complete()) {
      std::vector<uint32_t> ready;
      for (uint32_t r = 0; r < actions.robots(); ++r) {
        ASSERT_EQ(t.wait_cause(r), walked(r)) << "seed " << seed << " robot " << r;
        if (const auto c = t.wait_cause(r)) ++seen[*c];
        if (t.enqueued(r) > t.finished(r)) ready.push_back(r);
      }
      ASSERT_FALSE(ready.empty()) << "seed " << seed;
      const uint32_t r = ready[rng() % ready.size()];
      t.on_progress(r, t.finished(r));
    }
  }
  for (const auto c :
       {WaitCause::kAtLocation, WaitCause::kAtLocationTurning, WaitCause::kAtLocationWaiting,
        WaitCause::kEntering, WaitCause::kOnItsWayNear, WaitCause::kOnItsWayWaiting}) {
    EXPECT_GT(seen[c], 0u) << to_string(c) << " never seen: the random plans should wait so";
  }
}

}  // namespace
}  // namespace smart::monitor
