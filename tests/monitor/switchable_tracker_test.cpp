// monitor/switchable_tracker.hpp: a delayed robot's passing place is taken by the robot that is
// ready (scripted, exact), and the proof obligations of switching as properties over seeded
// random plans and random delays, for both footprints: no two robots ever hold one location,
// every run finishes (switching never makes a cycle, never strands a robot), every switch is
// between a robot that was ready and one that had not been sent its entry.
#include "smart/monitor/switchable_tracker.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/execution_tracker.hpp"
#include "smart/planning/random_plan.hpp"

namespace smart::monitor {
namespace {

// Entries sent one action ahead: the most room to switch.
constexpr SwitchOptions kNear{.commit_actions = 1, .search_budget = 4096};

Plan tracker_plan_of(std::vector<std::vector<Cell>> paths) {
  Plan plan;
  for (auto& cells : paths) {
    grid::RobotPath p;
    p.robot = static_cast<int>(plan.paths.size());
    for (std::size_t t = 0; t < cells.size(); ++t) {
      p.steps.push_back({cells[t], static_cast<double>(t)});
    }
    plan.paths.push_back(std::move(p));
  }
  return plan;
}

// Finishes robot r's actions up to `seq` (all of them: -1) as far as enqueued.
int64_t run_robot(SwitchableTracker& t, uint32_t r, double time_s) {
  int64_t last = -1;
  while (t.enqueued(r) > t.finished(r)) {
    last = t.enqueued(r) - 1;
    EXPECT_EQ(t.on_progress(r, last, time_s).result, ProgressResult::kAdvanced);
  }
  return last;
}

// A 4 x 3 room: robot 0 crosses cell (2, 1) west to east at t = 2, robot 1 north to south at
// t = 3, so the plan has robot 0 pass first. Robot 0 stalls before its first move; robot 1,
// near (2, 1), takes its place: it crosses and finishes while robot 0 has done nothing, then
// robot 0 goes. Plain ADG keeps robot 1 at the cell's edge until robot 0 has passed.
Plan crossing(bool robot1_parks) {
  std::vector<Cell> one{{2, 0}, {2, 0}, {2, 0}, {2, 1}};
  if (!robot1_parks) one.push_back({2, 2});
  return tracker_plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}}, one});
}

TEST(SwitchableTracker, TheReadyRobotPassesFirstWhenTheOtherIsDelayed) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  std::vector<Problem> problems;
  const auto adg = build_adg(actions, grid, "test", problems);
  ASSERT_TRUE(problems.empty());
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));

  ExecutionTracker plain(actions, adg);
  SwitchableTracker t(actions, passing_orders(actions, grid), kNear);
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{0, 1}));
  // Robot 1: rotate to south (seq 0), half-move to the cell's edge (1); its entry (2) waits.
  EXPECT_EQ(plain.enqueued(1), 2u);
  EXPECT_EQ(t.enqueued(1), 2u);
  // Robot 0's entry into the cell (seq 3) is not sent before it is one action away.
  EXPECT_EQ(plain.enqueued(0), 6u);
  EXPECT_EQ(t.enqueued(0), 3u);

  t.on_progress(1, 0, 1.0);  // rotated: robot 1 is on its last action before the cell
  ASSERT_EQ(t.switches()->size(), 1u);
  EXPECT_EQ((*t.switches())[0].location, cell);
  EXPECT_EQ((*t.switches())[0].first, 1u);
  EXPECT_EQ((*t.switches())[0].second, 0u);
  EXPECT_DOUBLE_EQ((*t.switches())[0].time_s, 1.0);
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{1, 0}));
  EXPECT_EQ(t.enqueued(1), 5u);
  EXPECT_EQ(run_robot(t, 1, 2.0), 4);
  EXPECT_TRUE(t.robot_done(1));
  EXPECT_EQ(t.finished(0), 0u);
  // Robot 0 now goes: its entry waited only until robot 1 had left the cell.
  run_robot(t, 0, 3.0);
  EXPECT_TRUE(t.complete());
  EXPECT_EQ(t.switches()->size(), 1u);
  // Plain ADG: robot 1 cannot finish before robot 0 has passed.
  plain.on_progress(1, 1);
  EXPECT_EQ(plain.enqueued(1), 2u);
}

// The deadlock search walks back from robot 1's leaving of the cell for robot 0's entry: robot
// 1's entry, then its half-move to the cell's edge, sent already (it waits for finished actions
// alone) and ordered before robot 0's entry, so it cannot follow that entry. Regression: the
// search walked such actions too; behind a robot far from the location, all the way to its
// budget, and refused the switch (LaCAM's 1000-robot plan of random-64-64-10 under delays: 652
// searches gave up, 68 % of the search's visits; docs/execution.md, "Cost"). With a budget of
// two actions it used to give up here as well.
TEST(SwitchableTracker, TheDeadlockSearchSkipsActionsThatCannotFollowTheEntry) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      {.commit_actions = 1, .search_budget = 2});
  EXPECT_TRUE(t.order_holds());
  t.on_progress(1, 0, 1.0);  // rotated: robot 1 is ready, robot 0 not sent its entry
  ASSERT_EQ(t.switches()->size(), 1u);
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{1, 0}));
  EXPECT_EQ(t.search_visits(), 2u);
  // The order follows the switch: robot 1's leaving now comes before robot 0's entry.
  EXPECT_TRUE(t.order_holds());
  EXPECT_EQ(run_robot(t, 1, 2.0), 4);
  run_robot(t, 0, 3.0);
  EXPECT_TRUE(t.complete());
}

// A resume's rebuild (run_supervisor.hpp resume()): on the orders a stopped monitor had
// reached, its switches replayed (apply_switches, by the stays' entries), a paused tracker fed
// the hosts' progress sends what that monitor had sent and switches nothing itself; unpaused,
// it switches again.
TEST(SwitchableTracker, APausedTrackerRebuildsTheOrdersReachedAndSwitchesOnlyOnceUnpaused) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker stopped(actions, passing_orders(actions, grid), kNear);
  stopped.on_progress(1, 0, 1.0);  // robot 1 passes robot 0 (as in the test above)
  ASSERT_EQ(stopped.switches()->size(), 1u);
  const PassingSwitch made = stopped.switches()->front();
  EXPECT_EQ(made.first_enter, actions.offset[1] + 2);  // robot 1's entry into the cell
  EXPECT_EQ(made.second_enter, actions.offset[0] + 3);

  auto orders = passing_orders(actions, grid);
  ASSERT_EQ(apply_switches(orders, {made}), 0u);
  SwitchableTracker rebuilt(actions, orders, kNear, true);
  EXPECT_EQ(rebuilt.order_at(cell), (std::vector<uint32_t>{1, 0}));
  rebuilt.on_progress(1, 0, 0.0);
  EXPECT_EQ(rebuilt.enqueued(1), stopped.enqueued(1));
  EXPECT_EQ(rebuilt.enqueued(0), stopped.enqueued(0));
  EXPECT_TRUE(rebuilt.switches()->empty());

  // The plan's orders, paused: robot 1 ready, robot 0 late, and no switch until unpaused.
  SwitchableTracker paused(actions, passing_orders(actions, grid), kNear, true);
  paused.on_progress(1, 0, 1.0);
  EXPECT_TRUE(paused.switches()->empty());
  EXPECT_EQ(paused.order_at(cell), (std::vector<uint32_t>{0, 1}));
  paused.unpause();
  paused.on_progress(1, 1, 1.5);
  ASSERT_EQ(paused.switches()->size(), 1u);
  EXPECT_EQ(paused.order_at(cell), (std::vector<uint32_t>{1, 0}));
}

// Robot 1 is ready while robot 0 was already sent its entry: no switch.
TEST(SwitchableTracker, ARobotThatWasSentItsEntryKeepsItsPlace) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  SwitchableTracker t(actions, passing_orders(actions, grid), kNear);
  t.on_progress(0, 1, 0.5);      // robot 0 on its half-move to the cell's edge: its entry is sent
  EXPECT_EQ(t.enqueued(0), 6u);  // its entry and the rest
  t.on_progress(1, 0, 1.0);
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.pending(actions.offset[1] + 2), 1u);
}

// A robot that parks for good on the location is never let in before the other: the other
// would be stranded behind it.
TEST(SwitchableTracker, NoSwitchBehindARobotThatParksThere) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(true), Heading::kEast);
  SwitchableTracker t(actions, passing_orders(actions, grid), kNear);
  run_robot(t, 1, 1.0);
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_FALSE(t.robot_done(1));
  run_robot(t, 0, 2.0);
  run_robot(t, 1, 3.0);
  EXPECT_TRUE(t.complete());
}

// Regression (found 2026-11-27, by the cost bench): robot 0's entry into (2, 1) came up
// while another robot reported (robot 1 left (1, 1), which robot 0 waited to enter), and it
// was tried only at robot 0's own next report, or when a switch elsewhere retried every robot
// ever refused. Robot 2, planned to cross (2, 1) first, stalls before its first action: robot
// 0 passes it at robot 1's report.
TEST(SwitchableTracker, ARobotWhoseNextEntryCameUpAtAnotherRobotsReportIsTriedThen) {
  const Grid grid(5, 4, std::vector<uint8_t>(20, 0));
  const auto actions =
      build_actions(tracker_plan_of({{{0, 1}, {0, 1}, {0, 1}, {1, 1}, {2, 1}, {3, 1}},
                                     {{1, 0}, {1, 1}, {1, 2}},
                                     {{3, 0}, {2, 0}, {2, 1}, {2, 2}}}),
                    Heading::kEast);
  SwitchableTracker t(actions, passing_orders(actions, grid), SwitchOptions{.commit_actions = 2});
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{2, 0}));
  t.on_progress(0, 0, 0.5);  // robot 0 at (1, 1)'s edge, waiting for robot 1 to leave it
  EXPECT_EQ(t.enqueued(0), 1u);
  run_robot(t, 1, 1.0);
  ASSERT_EQ(t.switches()->size(), 1u);
  EXPECT_DOUBLE_EQ((*t.switches())[0].time_s, 1.0);
  EXPECT_EQ((*t.switches())[0].first, 0u);
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{0, 2}));
  EXPECT_EQ(t.enqueued(0), t.known(0));  // nothing left to wait for
  EXPECT_EQ(t.finished(2), 0u);
  run_robot(t, 0, 2.0);
  run_robot(t, 2, 3.0);
  EXPECT_TRUE(t.complete());
}

// switchable-opt: before anything is sent, robot 0's entry into (2, 1) is within the commit
// distance and is decided. With every action expected to take 1 s (nothing learned yet), robot 0
// arrives at 3 s and leaves at 5 s, robot 1 (rotate, half-move) arrives at 2 s and leaves at 4 s:
// robot 0 first makes robot 1 wait 3 s, robot 1 first makes robot 0 wait 1 s. Robot 1 passes
// first (anticipated, at t = 0); plain switchable sends robot 0 its way in and keeps the order.
TEST(SwitchableTracker, AnticipationLetsTheRobotExpectedSoonerPassFirst) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker plain(actions, passing_orders(actions, grid), SwitchOptions{});
  EXPECT_TRUE(plain.switches()->empty());
  EXPECT_EQ(plain.enqueued(0), 6u);

  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.anticipate = true, .margin_s = 0.5});
  ASSERT_EQ(t.switches()->size(), 1u);
  const PassingSwitch& s = (*t.switches())[0];
  EXPECT_TRUE(s.anticipated);
  EXPECT_EQ(t.anticipated(), 1u);
  EXPECT_EQ(s.location, cell);
  EXPECT_EQ(s.first, 1u);
  EXPECT_EQ(s.second, 0u);
  EXPECT_DOUBLE_EQ(s.time_s, 0.0);
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{1, 0}));
  EXPECT_EQ(t.enqueued(0), 3u);  // waits at the cell's edge for robot 1
  EXPECT_EQ(t.enqueued(1), 5u);
  EXPECT_EQ(run_robot(t, 1, 4.0), 4);
  EXPECT_EQ(t.enqueued(0), 6u);  // robot 1 has left: robot 0 goes
  run_robot(t, 0, 8.0);
  EXPECT_TRUE(t.complete());
}

// The same crossing with entries sent two actions ahead: robot 0's entry is decided after its
// first half-move, reported at 0.5 s (moves now expected to take 0.5 s). Robot 1, still in its
// 1 s rotation, is expected at the cell at 1.5 s and out at 2.5 s, robot 0 the same: either
// order makes the other wait 1 s, no saving, so robot 0 keeps its place and is sent its way in.
TEST(SwitchableTracker, AnticipationKeepsTheOrderWhenNothingIsSaved) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.commit_actions = 2, .anticipate = true, .margin_s = 0.5});
  EXPECT_EQ(t.enqueued(0), 3u);  // its entry is three actions away: not decided yet
  t.on_progress(0, 0, 0.5);
  EXPECT_DOUBLE_EQ(t.durations().mean_s(ActionType::kMove), 0.5);
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.order_at(static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})))),
            (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(t.enqueued(0), 6u);  // decided: sent its way in, and the rest
}

// Anticipation times an action from its start: its robot's previous finish, or its sending when
// later (a robot that waited at a location's edge). The crossing run by a tiny executor: every
// robot runs its sent actions back to back, moves 0.5 s and rotations 1 s, each reported when
// done, in 0.25 s steps. Robot 1 waits at the cell's edge for robot 0 (its entry is sent after
// its previous action finished), yet the means are the durations exactly; timed from the
// previous finish, the wait would count as moving. (The start is kept per robot since
// 2026-12-03, where it was read per action: docs/execution.md, "A robot's next actions read
// together".)
TEST(SwitchableTracker, AnActionSentAfterItsRobotWaitedIsTimedFromItsSending) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.commit_actions = 2, .anticipate = true, .margin_s = 0.5});
  const auto duration_s = [&](uint32_t r) {
    const auto type = actions.actions[actions.offset[r] + t.finished(r)].type;
    return type == ActionType::kMove ? 0.5 : 1.0;
  };
  std::vector<double> start_s(2, 0.0);
  std::vector<bool> running{t.enqueued(0) > 0, t.enqueued(1) > 0};
  double waited_s = 0;
  const auto start_sent = [&](double now_s) {  // a robot standing that was sent an action
    for (uint32_t r = 0; r < 2; ++r) {
      if (running[r] || t.enqueued(r) == t.finished(r)) continue;
      waited_s += now_s - start_s[r];
      running[r] = true;
      start_s[r] = now_s;
    }
  };
  for (double now_s = 0.25; !t.complete() && now_s < 100; now_s += 0.25) {
    for (uint32_t r = 0; r < 2; ++r) {
      if (!running[r] || now_s < start_s[r] + duration_s(r)) continue;
      ASSERT_EQ(t.on_progress(r, t.finished(r), now_s).result, ProgressResult::kAdvanced);
      start_s[r] = now_s;
      running[r] = t.enqueued(r) > t.finished(r);
      start_sent(now_s);
    }
  }
  ASSERT_TRUE(t.complete());
  EXPECT_GT(waited_s, 0.0);  // a robot did wait for a sending
  EXPECT_DOUBLE_EQ(t.durations().mean_s(ActionType::kMove), 0.5);
  EXPECT_DOUBLE_EQ(t.durations().mean_s(ActionType::kRotate), 1.0);
}

// Regression (found 2026-11-27, 800-1000 robots on random-64-64-10 without delays: switchable-opt
// without anticipation 1.5 % AET behind plain ADG): robot 2 crosses (2, 1) first, robot 0 (from the
// north) is next, robot 1 (from the east) waits at the cell's edge. When robot 2 leaves, robot 0's
// entry is due (two actions away), and anticipation keeps the order (its expected saving is under
// the 10 s margin). First come, first served then took robot 0's due entry for robot 1 on the
// saving alone, before robot 0 was sent it; plain switchable had sent it. Now it is committed.
TEST(SwitchableTracker, AnEntryDueNowIsNotTakenByFirstComeFirstServed) {
  const Grid grid(5, 4, std::vector<uint8_t>(20, 0));
  const auto actions = build_actions(
      tracker_plan_of({{{2, 0}, {2, 0}, {2, 0}, {2, 1}, {1, 1}},
                       {{3, 1}, {3, 1}, {3, 1}, {3, 1}, {3, 1}, {3, 1}, {2, 1}, {2, 2}},
                       {{1, 1}, {2, 1}, {2, 2}, {2, 3}}}),
      Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.anticipate = true, .margin_s = 10.0});
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{2, 0, 1}));
  t.on_progress(1, 0, 1.0);  // robot 1 turned west
  t.on_progress(1, 1, 2.0);  // and stands at the cell's edge
  EXPECT_FALSE(t.robot_done(1));
  const uint32_t entry0 = t.enqueued(0);
  for (int64_t seq = 0; seq < 7; ++seq) t.on_progress(2, seq, 1.0 + seq);  // crossed, left
  EXPECT_TRUE(t.robot_done(2));
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{2, 0, 1}));
  EXPECT_GT(t.enqueued(0), entry0);  // sent its way in
  run_robot(t, 0, 6.0);
  run_robot(t, 1, 8.0);
  EXPECT_TRUE(t.complete());
  EXPECT_TRUE(t.switches()->empty());
}

// switchable-lookahead: the crossing of the tests above, robot 0 coming from farther west and
// going on east to (8, 1), where robots 2, 3 and 4, waiting south of (5, 1), (6, 1) and (7, 1),
// are planned to cross its row right after it. Every action expected to take 1 s: at (2, 1)
// robot 1 passing first saves itself 3 s and costs robot 0 1 s (the queue at the location: a
// saving of 2 s, anticipated by switchable-opt with a 0.5 s margin), but robot 0's second later
// holds robots 2, 3 and 4 a second each: the lookahead sees -1 s and keeps the order.
Plan crossing_with_followers(int32_t first_follower = 5) {
  std::vector<Cell> zero;
  for (int32_t x = 0; x <= 8; ++x) zero.push_back({x, 1});
  std::vector<std::vector<Cell>> paths{zero, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}};
  for (int32_t x = first_follower; x <= 7; ++x) {
    std::vector<Cell> up(static_cast<std::size_t>(x + 1), Cell{x, 2});
    up.push_back({x, 1});
    up.push_back({x, 0});
    paths.push_back(up);
  }
  return tracker_plan_of(paths);
}

TEST(SwitchableTracker, LookaheadKeepsTheOrderWhenThePassedRobotHoldsUpOthersLater) {
  const Grid grid(9, 3, std::vector<uint8_t>(27, 0));
  const auto actions = build_actions(crossing_with_followers(), Heading::kEast);
  std::vector<Problem> problems;
  const auto adg = build_adg(actions, grid, "test", problems);
  ASSERT_TRUE(problems.empty());
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker local(actions, passing_orders(actions, grid),
                          SwitchOptions{.anticipate = true, .margin_s = 0.5});
  ASSERT_EQ(local.switches()->size(), 1u);
  EXPECT_EQ(local.order_at(cell), (std::vector<uint32_t>{1, 0}));

  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.anticipate = true, .lookahead_actions = 24});
  EXPECT_EQ(t.lookahead_comparisons(), 1u);
  EXPECT_EQ(t.lookahead_widened(), 1u);  // its first 16 actions do not show the loss
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{0, 1}));
  EXPECT_GT(t.enqueued(0), 3u);  // decided: sent its way in (seq 3)
  EXPECT_EQ(t.enqueued(1), 2u);  // robot 1 waits at the cell's edge
  for (int round = 0; round < 10 && !t.complete(); ++round) {
    for (uint32_t r = 0; r < 5; ++r) run_robot(t, r, 1.0 + round);
  }
  EXPECT_TRUE(t.complete());
}

// The window search (SwitchOptions::window_pairs): the crossing above, where the lookahead
// keeps robot 0 first at (2, 1) because robot 0 later holds robots 2, 3 and 4 up at their
// crossings. Those three pairs may switch too (robot 0 not sent its entries there; each follower
// leaves again): with them in the window, the best setting has the followers pass robot 0 where
// they are ready long before it, and then robot 1 passing first at (2, 1) costs nobody behind:
// robot 1 passes. One pair's window is 2^3 settings.
TEST(SwitchableTracker, WindowSearchSwitchesWhenThePairsAfterItMaySwitchToo) {
  const Grid grid(9, 3, std::vector<uint8_t>(27, 0));
  const auto actions = build_actions(crossing_with_followers(), Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  for (const uint32_t pairs : {0u, 3u}) {
    SwitchableTracker t(
        actions, passing_orders(actions, grid),
        SwitchOptions{.anticipate = true, .lookahead_actions = 24, .window_pairs = pairs});
    EXPECT_EQ(t.lookahead_widened(), 1u) << pairs;
    EXPECT_EQ(t.lookahead_windowed(), pairs == 0 ? 0u : 1u);
    EXPECT_EQ(t.window_settings(), pairs == 0 ? 0u : 8u);
    EXPECT_EQ(t.order_at(cell),
              (pairs == 0 ? std::vector<uint32_t>{0, 1} : std::vector<uint32_t>{1, 0}));
    EXPECT_TRUE(t.order_holds());
    EXPECT_TRUE(t.neighbours_hold());
    for (int round = 0; round < 12 && !t.complete(); ++round) {
      for (uint32_t r = 0; r < 5; ++r) run_robot(t, r, 1.0 + round);
    }
    EXPECT_TRUE(t.complete()) << pairs;
  }
}

// Without the followers the lookahead agrees with the location's queue: robot 1 passes first.
TEST(SwitchableTracker, LookaheadLetsTheRobotExpectedSoonerPassFirst) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(crossing(false), Heading::kEast);
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.anticipate = true, .lookahead_actions = 24});
  ASSERT_EQ(t.switches()->size(), 1u);
  EXPECT_EQ(t.lookahead_widened(), 1u);
  EXPECT_TRUE((*t.switches())[0].anticipated);
  EXPECT_EQ((*t.switches())[0].first, 1u);
  EXPECT_EQ(t.order_at(static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})))),
            (std::vector<uint32_t>{1, 0}));
  EXPECT_EQ(run_robot(t, 1, 4.0), 4);
  run_robot(t, 0, 8.0);
  EXPECT_TRUE(t.complete());
}

// A pair whose swap loses more than one move's expected duration over the first
// lookahead_first_nodes of its cone is not compared over the rest. Four followers (x = 4..7): the
// queue at (2, 1) still expects robot 1 passing first to save 2 s, but robot 0's second later
// holds the four up a second each. A first cone of 32 actions reaches them: the order is kept
// without widening. A first cone of 16 does not: the whole cone is compared, with the same answer.
TEST(SwitchableTracker, LookaheadStopsAtTheFirstActionsWhenTheyLoseMoreThanAMove) {
  const Grid grid(9, 3, std::vector<uint8_t>(27, 0));
  const auto actions = build_actions(crossing_with_followers(4), Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  for (const std::size_t first : {std::size_t{32}, std::size_t{16}}) {
    SwitchableTracker t(
        actions, passing_orders(actions, grid),
        SwitchOptions{.anticipate = true, .lookahead_actions = 24, .lookahead_first_nodes = first});
    EXPECT_EQ(t.lookahead_comparisons(), 1u);
    EXPECT_EQ(t.lookahead_widened(), first == 32 ? 0u : 1u) << first;
    EXPECT_TRUE(t.switches()->empty());
    EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{0, 1}));
    for (int round = 0; round < 10 && !t.complete(); ++round) {
      for (uint32_t r = 0; r < 6; ++r) run_robot(t, r, 1.0 + round);
    }
    EXPECT_TRUE(t.complete());
  }
}

// The lookahead is not asked when the location's queue expects the swap to cost more than one
// move's expected duration. Robot 0 crosses (2, 1) west to east first, robot 1 enters it from
// the north next and turns back north inside it. Every action expected to take 1 s: robot 0
// arrives at 1 s and leaves at 3 s; robot 1 arrives at 2 s and stays 4 s (two quarter turns in
// the cell). Robot 1 first would save itself 1 s and cost robot 0 5 s: a loss of 4 s, over a
// move's 1 s, so the order stands without a cone being walked; robot 1 still waits for robot 0
// (it would not wait at all if it arrived after 3 s, the other case the lookahead is skipped).
TEST(SwitchableTracker, LookaheadIsNotAskedWhenTheLocationLosesMoreThanAMove) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions = build_actions(
      tracker_plan_of({{{1, 1}, {2, 1}, {3, 1}}, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 0}}}),
      Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.anticipate = true, .lookahead_actions = 24});
  EXPECT_EQ(t.lookahead_comparisons(), 0u);
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(run_robot(t, 0, 3.0), static_cast<int64_t>(actions.count(0)) - 1);
  run_robot(t, 1, 8.0);
  EXPECT_TRUE(t.complete());
  EXPECT_EQ(t.lookahead_comparisons(), 0u);
}

// A ready robot the comparison declined is tried again once the time it was expected to lose has
// passed (at least 2 s): until then, reports elsewhere that change the expected times do not try
// it. Robot 0 crosses (2, 1) west to east first and stalls at its start; robot 1 enters (2, 1)
// from the north and turns back inside it (one half turn); robot 2 moves alone in row 2.
// Rotations are learned to take 8 s, moves 1 s: robot 1, ready at 9 s, would hold the cell 10 s
// while robot 0 is expected in 3 s and through 2 s later: robot 1 would save itself 5 s of
// waiting and cost robot 0 7 s (declined). Robot 2's slow moves (10 s and 2 s) make every move
// expected slower, so robot 0 later: at 10 s the retry is not due, at 12 s it is, and robot 1
// passes.
TEST(SwitchableTracker, ADeclinedRobotIsTriedAgainWhenTheTimeItWouldLoseHasPassed) {
  const Grid grid(4, 3, std::vector<uint8_t>(12, 0));
  const auto actions =
      build_actions(tracker_plan_of({{{0, 1}, {1, 1}, {2, 1}, {3, 1}},
                                     {{2, 0}, {2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 0}},
                                     {{0, 2}, {1, 2}}}),
                    Heading::kEast);
  const auto cell = static_cast<uint32_t>(grid.half_index(HalfCell::of({2, 1})));
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      SwitchOptions{.commit_actions = 2, .anticipate = true});
  ASSERT_EQ(t.order_at(cell), (std::vector<uint32_t>{0, 1}));
  t.on_progress(1, 0, 8.0);  // its turn south: 8 s
  t.on_progress(1, 1, 9.0);  // at the cell's edge: declined
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.enqueued(1), 2u);
  t.on_progress(2, 0, 10.0);  // moves now expected slower, but the retry is due at 11 s
  EXPECT_TRUE(t.switches()->empty());
  EXPECT_EQ(t.enqueued(1), 2u);
  t.on_progress(2, 1, 12.0);
  ASSERT_EQ(t.switches()->size(), 1u);
  const PassingSwitch& s = (*t.switches())[0];
  EXPECT_DOUBLE_EQ(s.time_s, 12.0);
  EXPECT_EQ(s.first, 1u);
  EXPECT_EQ(s.second, 0u);
  EXPECT_FALSE(s.anticipated);
  EXPECT_EQ(t.order_at(cell), (std::vector<uint32_t>{1, 0}));
  EXPECT_GT(t.enqueued(1), 2u);
  run_robot(t, 1, 20.0);
  run_robot(t, 0, 25.0);
  run_robot(t, 2, 25.0);
  EXPECT_TRUE(t.complete());
}

// The following case of the chain tests below: robot 0 goes north from (0, 2) and east along
// row 1; robot 1 waits at (1, 0), then goes south into (1, 1), east to (2, 1) and south, planned
// behind robot 0 at (1, 1), the midpoint (1.5, 1) and (2, 1).
struct Following {
  Grid grid{4, 3, std::vector<uint8_t>(12, 0)};
  ActionPlan actions =
      build_actions(tracker_plan_of({{{0, 2}, {0, 1}, {1, 1}, {2, 1}, {3, 1}},
                                     {{1, 0}, {1, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}}}),
                    Heading::kEast);
  bool builds() const {
    std::vector<Problem> problems;
    build_adg(actions, grid, "test", problems);
    return problems.empty();
  }
};

// Following: robot 1 comes down into (1, 1) after robot 0 has crossed it eastwards and follows it
// east into (2, 1), then turns south to (2, 2); robot 0 goes on to (3, 1). Robot 0 stalls at its
// start, far from (1, 1). Passing it at (1, 1) alone would close a cycle: to leave (1, 1)
// eastwards robot 1 must wait for robot 0 to pass the edge midpoint (1.5, 1) and (2, 1) ahead of
// it, which robot 0 reaches only through (1, 1). Passing it at (1, 1), the midpoint and (2, 1)
// at once closes none: robot 1 goes through while robot 0 has done nothing, then robot 0 goes.
TEST(SwitchableTracker, AReadyRobotPassesARobotThatGoesOnAheadAtEveryLocationTheyShare) {
  const Following f;
  ASSERT_TRUE(f.builds());
  const Grid& grid = f.grid;
  const ActionPlan& actions = f.actions;
  SwitchableTracker one(actions, passing_orders(actions, grid),
                        SwitchOptions{.commit_actions = 1, .chain_locations = 1});
  SwitchableTracker t(actions, passing_orders(actions, grid), kNear);
  for (auto* x : {&one, &t}) x->on_progress(1, 0, 1.0);  // rotated south: at the cell's edge
  EXPECT_TRUE(one.switches()->empty());
  ASSERT_EQ(t.switches()->size(), 3u);
  EXPECT_EQ(t.chained(), 3u);
  const auto at = [&](HalfCell h) { return static_cast<uint32_t>(grid.half_index(h)); };
  EXPECT_EQ((*t.switches())[0].location, at(HalfCell::of({1, 1})));
  EXPECT_EQ((*t.switches())[1].location, at({3, 2}));  // the midpoint (1.5, 1)
  EXPECT_EQ((*t.switches())[2].location, at(HalfCell::of({2, 1})));
  for (const auto& s : *t.switches()) {
    EXPECT_EQ(s.first, 1u);
    EXPECT_EQ(s.second, 0u);
  }
  run_robot(t, 1, 2.0);
  EXPECT_TRUE(t.robot_done(1));
  EXPECT_EQ(t.finished(0), 0u);
  run_robot(t, 0, 3.0);
  while (!t.complete() && !t.deadlocked()) run_robot(t, 0, 4.0);
  EXPECT_TRUE(t.complete());
}

// The lookahead compares a pair's two orders over the actions they affect. Passing robot 0 at
// the cell alone closes a cycle inside those actions (robot 0 goes on ahead of robot 1 along
// row 1), which costs for ever: before the chain was compared as a whole, the lookahead never
// reached a chain here (no switch). Now the order with robot 1 passing at all three locations
// is compared with the plan's over the same actions, and saves: robot 0 has not moved for 5 s.
TEST(SwitchableTracker, TheLookaheadComparesAChainAsAWholeWhereOneLocationClosesACycle) {
  const Following f;
  ASSERT_TRUE(f.builds());
  const Grid& grid = f.grid;
  const ActionPlan& actions = f.actions;
  const SwitchOptions look{.commit_actions = 1, .anticipate = true, .lookahead_actions = 24};
  SwitchOptions one_location = look;
  one_location.chain_locations = 1;
  SwitchableTracker one(actions, passing_orders(actions, grid), one_location);
  SwitchableTracker t(actions, passing_orders(actions, grid), look);
  for (auto* x : {&one, &t}) x->on_progress(1, 0, 5.0);  // rotated south: at the cell's edge
  EXPECT_TRUE(one.switches()->empty());
  ASSERT_EQ(t.switches()->size(), 3u);
  EXPECT_EQ(t.chained(), 3u);
  for (const auto& s : *t.switches()) {
    EXPECT_EQ(s.first, 1u);
    EXPECT_EQ(s.second, 0u);
    EXPECT_FALSE(s.anticipated);
  }
  run_robot(t, 1, 6.0);
  EXPECT_TRUE(t.robot_done(1));
  EXPECT_EQ(t.finished(0), 0u);
  while (!t.complete() && !t.deadlocked()) run_robot(t, 0, 7.0);
  EXPECT_TRUE(t.complete());
}

// Anticipation compares a chain as a whole too. The same following case, entries sent 3
// actions ahead: robot 0's first move takes 5 s (every move is now expected to), so when its
// entry into (1,1) is to be sent robot 1, sent its turn towards (1,1) at t = 0, is expected
// through the three shared locations sooner. Passing at (1,1) alone closes a cycle; the chain saves
// more than the margin and is made at t = 6, anticipated, before robot 0 is sent its way in
// (without chains in anticipation: no switch, checked).
TEST(SwitchableTracker, TheLookaheadAnticipatesAChainWhereOneLocationClosesACycle) {
  const Following f;
  ASSERT_TRUE(f.builds());
  const Grid& grid = f.grid;
  const ActionPlan& actions = f.actions;
  SwitchableTracker t(actions, passing_orders(actions, grid),
                      {.commit_actions = 3, .anticipate = true, .lookahead_actions = 24});
  t.on_progress(0, 0, 1.0);
  EXPECT_TRUE(t.switches()->empty());
  t.on_progress(0, 1, 6.0);
  ASSERT_EQ(t.switches()->size(), 3u);
  EXPECT_EQ(t.chained(), 3u);
  EXPECT_EQ(t.anticipated(), 3u);
  for (const auto& s : *t.switches()) {
    EXPECT_EQ(s.first, 1u);
    EXPECT_EQ(s.second, 0u);
    EXPECT_TRUE(s.anticipated);
    EXPECT_EQ(s.time_s, 6.0);
  }
  run_robot(t, 1, 7.0);
  EXPECT_TRUE(t.robot_done(1));
  while (!t.complete() && !t.deadlocked()) run_robot(t, 0, 8.0);
  EXPECT_TRUE(t.complete());
}

// The locations a robot standing at `h` holds under `footprint` (adg.hpp): the half-cell itself,
// or the cells of it (both cells of an edge midpoint).
std::vector<HalfCell> held(HalfCell h, Footprint footprint) {
  if (footprint == Footprint::kHalfCells || h.is_cell()) return {h};
  if (h.x2 % 2 != 0) return {{h.x2 - 1, h.y2}, {h.x2 + 1, h.y2}};
  return {{h.x2, h.y2 - 1}, {h.x2, h.y2 + 1}};
}

struct Outcome {
  std::size_t switches = 0, anticipated = 0, chained = 0;
  std::size_t windowed = 0;  // comparisons searched over a window (SwitchOptions::window_pairs)
};

// One seeded random plan executed in a random order the tracker allows, a third of the robots
// delayed (chosen ten times less often): robots start only enqueued actions, claim what they
// enter when they start a move and release what they left when they finish it, report late.
// What wait_cause() must tell on half cells, as the orders are now: the blockers from the
// current edges (predecessors) and each blocker's actions walked back, as for plain ADG. The
// tracker keeps a waiting robot's stays while their locations' orders hold (2026-12-08); this
// reads everything afresh.
std::optional<WaitCause> walked_wait_cause(const SwitchableTracker& t, const ActionPlan& actions,
                                           uint32_t commit_actions, uint32_t r) {
  if (t.robot_done(r) || t.enqueued(r) > t.finished(r)) return std::nullopt;
  std::vector<uint32_t> leaves;
  t.predecessors(actions.offset[r] + t.enqueued(r), leaves);
  std::optional<WaitCause> cause;
  for (const uint32_t leave : leaves) {
    const Action& a = actions.actions[leave];
    if (a.seq < t.finished(a.robot)) continue;
    const auto c =
        half_cell_blocker_cause(a.seq, t.finished(a.robot), t.enqueued(a.robot), commit_actions,
                                [&](uint32_t s) { return actions.at(a.robot, s).type; });
    cause = std::max(cause.value_or(WaitCause::kAtLocation), c);
  }
  return cause.value_or(WaitCause::kHeld);
}

Outcome run_random(uint64_t seed, Footprint footprint, SwitchOptions options = kNear) {
  std::mt19937_64 rng(seed);
  const auto w = static_cast<int32_t>(6 + rng() % 8), h = static_cast<int32_t>(6 + rng() % 8);
  const auto grid = planning::generate_random_grid(w, h, 0.15, seed);
  const std::size_t n = std::min<std::size_t>(grid.free_cells() / 2, 4 + rng() % 24);
  const auto inst = planning::generate_random_plan(grid, {n, 10 + rng() % 25, seed, 0.7, 0.3});
  const auto actions = build_actions(inst.plan, static_cast<Heading>(seed % 4));
  std::vector<Problem> problems;
  const auto adg = build_adg(actions, grid, "random", problems, footprint);
  if (!problems.empty() || !check_acyclic(adg, actions, "random").empty()) return {};  // kCells
  SwitchableTracker t(actions, passing_orders(actions, grid, footprint), options);
  const auto robots = static_cast<uint32_t>(actions.robots());
  const uint32_t commit_actions = options.commit_actions;
  std::map<HalfCell, uint32_t> occupied;
  for (uint32_t r = 0; r < robots; ++r) {
    for (const auto c : held(actions.start[r], footprint)) occupied[c] = r;
  }
  std::vector<uint32_t> started(robots, 0), done(robots, 0), weight(robots, 10);
  std::vector<double> finish_s(actions.actions.size(), std::nan(""));
  for (uint32_t r = 0; r < robots; ++r) weight[r] = rng() % 3 == 0 ? 1 : 10;
  std::size_t steps = 0;
  double time_s = 0;
  while (!t.complete()) {
    EXPECT_FALSE(t.deadlocked()) << "seed " << seed;
    if (t.deadlocked()) return {};
    std::vector<std::pair<uint32_t, int>> options;
    for (uint32_t r = 0; r < robots; ++r) {
      for (uint32_t k = 0; k < weight[r]; ++k) {
        if (started[r] == done[r] && started[r] < t.enqueued(r)) options.emplace_back(r, 0);
        if (started[r] > done[r]) options.emplace_back(r, 1);
        if (done[r] > t.finished(r)) options.emplace_back(r, 2);
      }
    }
    EXPECT_FALSE(options.empty()) << "seed " << seed;
    if (options.empty()) return {};
    const auto [r, kind] = options[rng() % options.size()];
    // A report (kind 2) reads no action: done[r] may be past the robot's last (regression: the
    // sanitized build's checked vector caught the read).
    const Action no_action{};
    const Action& a = kind == 2 ? no_action : actions.at(r, kind == 0 ? started[r] : done[r]);
    if (kind == 0 && a.type == ActionType::kMove) {
      for (const auto c : held(a.to, footprint)) {
        const auto it = occupied.find(c);
        EXPECT_TRUE(it == occupied.end() || it->second == r)
            << "seed " << seed << ": robot " << r << " enters " << to_string(c) << " held by robot "
            << it->second;
        occupied[c] = r;
      }
    }
    if (kind == 1 && a.type == ActionType::kMove) {
      const auto now = held(a.to, footprint);
      for (const auto c : held(a.from, footprint)) {
        if (std::find(now.begin(), now.end(), c) == now.end()) occupied.erase(c);
      }
    }
    if (kind == 0) ++started[r];
    if (kind == 1) ++done[r];
    if (kind == 2) {
      for (uint32_t s = t.finished(r); s < done[r]; ++s) finish_s[actions.offset[r] + s] = time_s;
      const std::size_t switched = t.switches()->size();
      EXPECT_EQ(t.on_progress(r, done[r] - 1, time_s).result, ProgressResult::kAdvanced);
      // The deadlock search's topological order follows every switch (switchable_order.cpp).
      if (t.switches()->size() != switched && !t.order_holds()) {
        ADD_FAILURE() << "seed " << seed << ": the order does not hold after switch "
                      << t.switches()->size() << (t.ordered() ? "" : " (given up)");
        return {};
      }
      // So does each action's copy of its stays' neighbours (near_, read by the tries).
      if (t.switches()->size() != switched && !t.neighbours_hold()) {
        ADD_FAILURE() << "seed " << seed << ": an action's neighbours do not hold after switch "
                      << t.switches()->size();
        return {};
      }
      // And each waiting robot's kept stays (wait_cause).
      for (uint32_t q = 0; footprint == Footprint::kHalfCells && q < robots; ++q) {
        if (t.wait_cause(q) != walked_wait_cause(t, actions, commit_actions, q)) {
          ADD_FAILURE() << "seed " << seed << ": robot " << q << "'s wait cause after switch "
                        << t.switches()->size();
          return {};
        }
      }
    }
    time_s += 0.1;
    if (++steps > 1'000'000u) return {};
  }
  for (uint32_t r = 0; r < robots; ++r) {
    EXPECT_EQ(occupied.at(HalfCell::of(inst.scen.agents[r].goal)), r) << "seed " << seed;
  }
  for (const auto& s : *t.switches()) EXPECT_NE(s.first, s.second) << "seed " << seed;
  // The viewer's replay of switches.csv (adg.hpp apply_switches) ends with the tracker's orders,
  // and their edges are the ones the tracker ended with.
  auto replayed = passing_orders(actions, grid, footprint);
  EXPECT_EQ(apply_switches(replayed, *t.switches(), finish_s), 0u) << "seed " << seed;
  for (uint32_t loc = 0; loc + 1 < replayed.begin.size(); ++loc) {
    std::vector<uint32_t> order;
    for (uint32_t k = replayed.begin[loc]; k < replayed.begin[loc + 1]; ++k) {
      order.push_back(replayed.stays[k].robot);
    }
    EXPECT_EQ(order, t.order_at(loc)) << "seed " << seed << " location " << loc;
    if (order != t.order_at(loc)) return {};
  }
  const Adg ended = adg_of_orders(replayed, actions, footprint);
  for (uint32_t node = 0; node < actions.actions.size(); ++node) {
    std::vector<uint32_t> want,
        got(ended.in.begin() + ended.in_begin[node], ended.in.begin() + ended.in_begin[node + 1]);
    t.predecessors(node, want);
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << "seed " << seed << " node " << node;
    if (got != want) return {};
  }
  return {t.switches()->size(), t.anticipated(), t.chained(), t.lookahead_windowed()};
}

// A chain's cycle checks (switchable_chain.cpp) search a graph with the chain's new edges, which
// the topological order does not know yet; they ran unbounded by it, walked what must happen
// before the chain's entries and, past the budget, gave the chain up. Bounded by the order below
// the lowest of those entries (chain_floor), they find the same paths and finish. Regression,
// with a budget of 8 actions: seed 1's plan on half cells made 35 switches, none chained, and
// seed 8's on whole cells 8, none chained (on SMART's 1000-robot plan, 109 of 58 000 checks gave
// up; docs/execution.md, "A chain's cycle checks bounded by the order").
TEST(SwitchableTracker, AChainsCycleChecksSkipActionsOrderedBeforeItsEntries) {
  SwitchOptions options = kNear;
  options.search_budget = 8;
  const Outcome half = run_random(1, Footprint::kHalfCells, options);
  EXPECT_EQ(half.switches, 43u);
  EXPECT_EQ(half.chained, 8u);
  const Outcome whole = run_random(8, Footprint::kCells, options);
  EXPECT_EQ(whole.switches, 10u);
  EXPECT_EQ(whole.chained, 2u);
}

TEST(SwitchableTrackerProperty, RandomPlansWithDelaysNeverCollideAndAlwaysFinishOnHalfCells) {
  std::size_t switches = 0, chained = 0;
  for (uint64_t seed = 1; seed <= 150; ++seed) {
    const auto o = run_random(seed, Footprint::kHalfCells);
    switches += o.switches;
    chained += o.chained;
    if (HasFailure()) FAIL() << "seed " << seed;
  }
  EXPECT_GT(switches, 100u) << "the delays should make robots switch";
  EXPECT_GT(chained, 300u) << "robots should pass robots going on ahead of them";  // 582
}

// Until the first switch (entries sent as soon as they may be: commit_actions beyond any plan, so
// only a robot stuck before its entry is passed), the switchable tracker's wait causes, read from
// its stays, are plain ADG's, read from its edges (execution.hpp WaitCause; near and far are one
// class here: far needs a nearer commit).
TEST(SwitchableTrackerProperty, WaitCausesAreThoseOfPlainAdgWhenNothingSwitches) {
  const auto same = [](std::optional<WaitCause> c) {
    return c == WaitCause::kOnItsWayFar ? std::optional{WaitCause::kOnItsWayNear} : c;
  };
  std::map<WaitCause, std::size_t> seen;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    std::mt19937_64 rng(seed);
    const auto grid = planning::generate_random_grid(10, 10, 0.15, seed);
    const auto inst = planning::generate_random_plan(grid, {12, 25, seed, 0.7, 0.3});
    const auto actions = build_actions(inst.plan, Heading::kEast);
    std::vector<Problem> problems;
    const auto adg = build_adg(actions, grid, "random", problems);
    ASSERT_TRUE(problems.empty());
    ExecutionTracker plain(actions, adg);
    SwitchableTracker sw(actions, passing_orders(actions, grid), {.commit_actions = 100000});
    const auto robots = static_cast<uint32_t>(actions.robots());
    while (!plain.complete() && sw.switches()->empty()) {
      std::vector<uint32_t> ready;
      for (uint32_t r = 0; r < robots; ++r) {
        ASSERT_EQ(same(plain.wait_cause(r)), same(sw.wait_cause(r)))
            << "seed " << seed << " robot " << r;
        if (const auto c = plain.wait_cause(r)) ++seen[*c];
        if (plain.enqueued(r) > plain.finished(r)) ready.push_back(r);
      }
      ASSERT_FALSE(ready.empty()) << "seed " << seed;
      const uint32_t r = ready[rng() % ready.size()];
      plain.on_progress(r, plain.finished(r));
      sw.on_progress(r, plain.finished(r) - 1, 0.0);
      ASSERT_EQ(sw.finished(r), plain.finished(r));
    }
  }
  std::size_t waits = 0;
  for (const auto& [c, n] : seen) waits += n;
  EXPECT_GT(waits, 2000u) << "waits compared before the first switches";  // 5650
  for (const auto c :
       {WaitCause::kAtLocation, WaitCause::kAtLocationTurning, WaitCause::kAtLocationWaiting,
        WaitCause::kEntering, WaitCause::kOnItsWayNear, WaitCause::kOnItsWayWaiting}) {
    EXPECT_GT(seen[c], 0u) << to_string(c) << " never seen: the random plans should wait so";
  }
}

// One location at a time (BTPG's pairs): the same guarantees.
TEST(SwitchableTrackerProperty, OneLocationAtATimeNeverCollidesAndAlwaysFinishes) {
  std::size_t switches = 0;
  for (uint64_t seed = 1; seed <= 150; ++seed) {
    const auto o = run_random(seed, Footprint::kHalfCells,
                              SwitchOptions{.commit_actions = 1, .chain_locations = 1});
    switches += o.switches;
    EXPECT_EQ(o.chained, 0u);
    if (HasFailure()) FAIL() << "seed " << seed;
  }
  EXPECT_GT(switches, 100u) << "the delays should make robots switch";
}

TEST(SwitchableTrackerProperty, RandomPlansWithDelaysNeverCollideAndAlwaysFinishOnCells) {
  std::size_t switches = 0;
  for (uint64_t seed = 1; seed <= 150; ++seed) {
    switches += run_random(seed, Footprint::kCells).switches;
    if (HasFailure()) FAIL() << "seed " << seed;
  }
  EXPECT_GT(switches, 20u) << "the delays should make robots switch";
}

// The default: entries sent six actions ahead (fewer switches, the same guarantees).
TEST(SwitchableTrackerProperty, RandomPlansWithDelaysNeverCollideAndAlwaysFinishByDefault) {
  std::size_t switches = 0;
  for (uint64_t seed = 1; seed <= 150; ++seed) {
    switches += run_random(seed, Footprint::kHalfCells, SwitchOptions{}).switches;
    if (HasFailure()) FAIL() << "seed " << seed;
  }
  EXPECT_GT(switches, 10u) << "the delays should make robots switch";
}

// 100 random plans for each footprint and each commit distance (1 and 6 actions) with
// `options` (anticipating), their switches and anticipated switches summed.
Outcome run_anticipating(SwitchOptions options) {
  Outcome sum;
  for (const auto footprint : {Footprint::kHalfCells, Footprint::kCells}) {
    for (const uint32_t commit : {1u, 6u}) {
      options.commit_actions = commit;
      for (uint64_t seed = 1; seed <= 100; ++seed) {
        const auto o = run_random(seed, footprint, options);
        sum.switches += o.switches;
        sum.anticipated += o.anticipated;
        sum.chained += o.chained;
        sum.windowed += o.windowed;
        if (::testing::Test::HasFailure()) {
          ADD_FAILURE() << "seed " << seed << " commit " << commit;
          return sum;
        }
      }
    }
  }
  return sum;
}

// switchable-opt: entries about to be sent may also yield their place by expected times
// (anticipation); the same guarantees, on both footprints and both commit distances. The delayed
// robots make the expected times differ from the plan's, so anticipation does switch.
TEST(SwitchableTrackerProperty, AnticipatedSwitchesNeverCollideAndAlwaysFinish) {
  const auto o = run_anticipating({.anticipate = true, .margin_s = 0.05, .horizon_actions = 12});
  EXPECT_GT(o.anticipated, 200u) << "of " << o.switches << " switches";
  EXPECT_GT(o.switches, o.anticipated) << "first come, first served still switches too";
}

// switchable-lookahead: the same guarantees when orders are compared by the expected times of
// every action they affect (a swap that would close a cycle inside the compared actions is
// expected to take for ever, and the deadlock search still decides).
TEST(SwitchableTrackerProperty, LookaheadSwitchesNeverCollideAndAlwaysFinish) {
  const auto o =
      run_anticipating({.anticipate = true, .lookahead_actions = 24, .lookahead_margin_s = 0.05});
  EXPECT_GT(o.anticipated, 100u) << "of " << o.switches << " switches";
  EXPECT_GT(o.switches, o.anticipated) << "first come, first served still switches too";
  EXPECT_GT(o.chained, 100u) << "of " << o.switches << " switches";  // 484; 8 before
}

// The window search: every setting of a window's pairs is made on the orders and undone before
// anything is sent; only the compared pair may switch, through every check. The same guarantees,
// with the orders, their topological order and each action's copy of its neighbours checked
// after every switch (run_random), and the replayed switches ending in the tracker's orders.
TEST(SwitchableTrackerProperty, WindowSearchSwitchesNeverCollideAndAlwaysFinish) {
  const auto o = run_anticipating(
      {.anticipate = true, .lookahead_actions = 24, .lookahead_margin_s = 0.05, .window_pairs = 3});
  EXPECT_GT(o.windowed, 100u) << "of " << o.switches << " switches";
  EXPECT_GT(o.anticipated, 100u) << "of " << o.switches << " switches";
  EXPECT_GT(o.switches, o.anticipated) << "first come, first served still switches too";
}

}  // namespace
}  // namespace smart::monitor
