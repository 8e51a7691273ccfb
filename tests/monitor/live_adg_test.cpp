#include "smart/monitor/live_adg.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/pibt.hpp"
#include "smart/planning/task_generator.hpp"
#include "support/ideal_executor.hpp"

namespace smart::monitor {
namespace {

using ::testing::HasSubstr;
using Paths = std::vector<std::vector<Cell>>;

Grid open_map(int w, int h) { return planning::generate_empty_map(w, h); }

using Executor = test::IdealExecutor;

TEST(LiveAdg, ACrossingIsOrderedAndExecuted) {
  const auto g = open_map(3, 3);
  LiveAdg adg(g, {{0, 1}, {1, 0}}, Heading::kEast);
  // Robot 0 crosses (1,1) at t=1, robot 1 at t=2.
  ASSERT_TRUE(adg.append({{{0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 0}, {1, 1}, {1, 2}}}, 0).empty());
  EXPECT_EQ(adg.end(0), 4u);  // 2 moves = 4 half-moves
  EXPECT_EQ(adg.end(1), 5u);  // a rotation south first
  EXPECT_EQ(adg.enqueued(0), 4u);
  EXPECT_EQ(adg.enqueued(1), 2u);  // rotate + half-move to the midpoint above (1,1)
  const auto waits = adg.waits_for(1, 2);
  ASSERT_EQ(waits.size(), 1u);
  EXPECT_EQ(waits[0], (NodeRef{0, 2}));  // robot 0 leaving (1,1)
  EXPECT_EQ(adg.on_progress(0, 2, 0.0).robots_changed, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(adg.enqueued(1), 5u);
}

// Robot 1, above (5,1), waits for robot 0 to pass along row 1; robot 0 waits at (2,1) for robot
// 2 crossing it first. What robot 1 waits for changes as robot 0 comes (execution.hpp
// WaitCause): far, waiting itself, near, entering, at the location; then none.
TEST(LiveAdg, AWaitIsClassifiedByWhatItsBlockerDoes) {
  const auto g = open_map(7, 3);
  LiveAdg adg(g, {{0, 1}, {5, 0}, {2, 0}}, Heading::kEast);
  const Paths window{{{0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 1}, {6, 1}},
                     {{5, 0}, {5, 0}, {5, 0}, {5, 0}, {5, 0}, {5, 0}, {5, 0}, {5, 1}, {5, 2}},
                     {{2, 0}, {2, 1}, {2, 2}}};
  ASSERT_TRUE(adg.append(window, 0).empty());
  ASSERT_EQ(adg.waits_for(1, 2), (std::vector<NodeRef>{{0, 10}}));  // robot 0 leaving (5,1)
  ASSERT_EQ(adg.waits_for(0, 3), (std::vector<NodeRef>{{2, 3}}));   // robot 2 leaving (2,1)
  EXPECT_EQ(adg.wait_cause(1), std::nullopt) << "it has actions to execute";
  adg.on_progress(1, 1, 1.0);
  // Robot 0's entry (its half-move 9) is 9 actions away: more than the 6 a switchable entry is
  // sent ahead.
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kOnItsWayFar);
  adg.on_progress(0, 2, 2.0);  // robot 0 at the midpoint before (2,1), waiting for robot 2
  EXPECT_EQ(adg.wait_cause(0), WaitCause::kOnItsWayNear);  // robot 2 moves, 2 actions away
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kOnItsWayWaiting);
  adg.on_progress(2, 3, 3.0);                              // robot 2 left (2,1)
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kOnItsWayNear);  // 6 actions away now
  adg.on_progress(0, 8, 4.0);
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kEntering);
  adg.on_progress(0, 9, 5.0);
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kAtLocation);
  adg.on_progress(0, 10, 6.0);
  EXPECT_EQ(adg.wait_cause(1), std::nullopt);
  adg.on_progress(0, 11, 7.0);
  EXPECT_EQ(adg.wait_cause(0), WaitCause::kNoAction) << "until the next window";
}

// Robot 3 follows robot 0 east along row 1; robot 0 waits at the midpoint before (2,1) for robot
// 2 crossing it: robot 3 then waits behind a robot that holds the location and waits itself.
TEST(LiveAdg, AWaitBehindARobotThatWaitsWhereItStandsIsAQueue) {
  const auto g = open_map(5, 3);
  LiveAdg adg(g, {{1, 1}, {4, 0}, {2, 0}, {0, 1}}, Heading::kEast);
  const Paths window{{{1, 1}, {1, 1}, {1, 1}, {2, 1}, {3, 1}},
                     {{4, 0}},
                     {{2, 0}, {2, 1}, {2, 2}},
                     {{0, 1}, {0, 1}, {0, 1}, {1, 1}, {1, 1}, {2, 1}}};
  ASSERT_TRUE(adg.append(window, 0).empty());
  ASSERT_EQ(adg.waits_for(0, 1), (std::vector<NodeRef>{{2, 3}}));  // robot 2 leaving (2,1)
  ASSERT_EQ(adg.waits_for(3, 1), (std::vector<NodeRef>{{0, 0}}));  // robot 0 leaving (1,1)
  ASSERT_EQ(adg.waits_for(3, 2), (std::vector<NodeRef>{{0, 1}}));  // and the midpoint after it
  adg.on_progress(3, 0, 1.0);
  EXPECT_EQ(adg.wait_cause(3), WaitCause::kAtLocation) << "robot 0 is leaving (1,1)";
  adg.on_progress(0, 0, 2.0);
  EXPECT_EQ(adg.wait_cause(0), WaitCause::kOnItsWayNear);
  adg.on_progress(3, 1, 3.0);
  EXPECT_EQ(adg.wait_cause(3), WaitCause::kAtLocationWaiting);
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kNoAction) << "robot 1 stays: it has no action";
}

// Robot 0 turns south at (1,1) before it leaves; robot 1 follows into (1,1) from the west.
TEST(LiveAdg, AWaitBehindARobotTurningWhereItStandsIsToldFromItsLeaving) {
  const auto g = open_map(3, 3);
  LiveAdg adg(g, {{1, 1}, {0, 1}}, Heading::kEast);
  ASSERT_TRUE(adg.append({{{1, 1}, {1, 2}}, {{0, 1}, {0, 1}, {1, 1}}}, 0).empty());
  ASSERT_EQ(adg.action(0, 0).type, ActionType::kRotate);
  ASSERT_EQ(adg.waits_for(1, 1), (std::vector<NodeRef>{{0, 1}}));  // robot 0 leaving (1,1)
  adg.on_progress(1, 0, 1.0);
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kAtLocationTurning);
  adg.on_progress(0, 0, 2.0);
  EXPECT_EQ(adg.wait_cause(1), WaitCause::kAtLocation) << "robot 0 is moving out";
}

// Robot 0 runs east along row 1 and is planned through (3,1) first; robot 1, above (3,1), waits
// for it. Entries are sent two actions ahead, so robot 0's way into (3,1) (its 6th half-move) is
// not sent yet: robot 1 may pass first.
struct LateRobotFixture {
  Grid g = open_map(5, 3);
  Paths window{{{0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}},
               {{3, 0}, {3, 0}, {3, 0}, {3, 0}, {3, 0}, {3, 1}, {3, 2}}};
  LiveAdg adg{g, {{0, 1}, {3, 0}}, Heading::kEast};

  uint32_t at_3_1() const { return static_cast<uint32_t>(g.half_index(HalfCell::of({3, 1}))); }

  // switchable-opt, entries sent `commit` actions ahead; the window appended at t = 0.
  void anticipate(uint32_t commit, double margin_s = SwitchOptions{}.margin_s) {
    SwitchOptions o{commit};
    o.anticipate = true;
    o.margin_s = margin_s;
    adg.enable_switching(o);
    ASSERT_TRUE(adg.append(window, 0).empty());
  }
};

TEST(LiveAdgSwitching, TheReadyRobotPassesTheLateOneAndTheOrderFollows) {
  LateRobotFixture f;
  f.adg.enable_switching({2});
  ASSERT_TRUE(f.adg.append(f.window, 0).empty());
  EXPECT_EQ(f.adg.enqueued(0), 5u);  // the entry into (3,1) is held back
  EXPECT_EQ(f.adg.enqueued(1), 2u);  // rotate south, half-move; entering waits for robot 0
  ASSERT_EQ(f.adg.waits_for(1, 2), (std::vector<NodeRef>{{0, 6}}));
  f.adg.on_progress(1, 0, 0.5);  // robot 1 turned: it is ready, robot 0 far
  EXPECT_EQ(*f.adg.switches(), (std::vector<PassingSwitch>{{0.5, f.at_3_1(), 1, 0}}));
  EXPECT_EQ(f.adg.enqueued(1), 5u);
  EXPECT_EQ(f.adg.waits_for(0, 5), (std::vector<NodeRef>{{1, 3}}));  // now behind robot 1
  f.adg.on_progress(0, 4, 1.0);
  EXPECT_EQ(f.adg.enqueued(0), 5u);  // near, but (3,1) is robot 1's until it leaves
  f.adg.on_progress(1, 3, 1.5);
  EXPECT_EQ(f.adg.enqueued(0), 8u);
  EXPECT_FALSE(f.adg.deadlocked());
}

// The following case of the chain tests below, as one window (4 x 3, open).
Paths following_window() {
  return {{{0, 2}, {0, 1}, {1, 1}, {2, 1}, {3, 1}},
          {{1, 0}, {1, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}}};
}

// Chains on the growing graph (SwitchableTracker's
// AReadyRobotPassesARobotThatGoesOnAheadAtEveryLocationTheyShare): robot 0 goes north from (0,2)
// and east along row 1; robot 1 waits at (1,0), then goes south into (1,1), east to (2,1) and
// south, planned behind robot 0 at (1,1), the midpoint (1.5,1) and (2,1). Robot 0 is late (its
// entries sent one action ahead). One location at a time robot 1 cannot pass: robot 0 would
// still be ahead at the next location, a cycle. With chains it passes at all three at once and
// both finish.
TEST(LiveAdgSwitching, AReadyRobotPassesARobotThatGoesOnAheadAtEveryLocationTheyShare) {
  const auto g = open_map(4, 3);
  const Paths window = following_window();
  const auto at = [&](HalfCell h) { return static_cast<uint32_t>(g.half_index(h)); };
  for (const uint32_t chain : {1u, 8u}) {
    SCOPED_TRACE("chain " + std::to_string(chain));
    LiveAdg adg(g, {{0, 2}, {1, 0}}, Heading::kEast);
    adg.enable_switching({.commit_actions = 1, .chain_locations = chain});
    ASSERT_TRUE(adg.append(window, 0).empty());
    adg.on_progress(1, 0, 1.0);  // robot 1 turned south: ready at the edge of (1,0)
    if (chain == 1) {
      EXPECT_TRUE(adg.switches()->empty());
      continue;
    }
    ASSERT_EQ(adg.switches()->size(), 3u);
    EXPECT_EQ(adg.chained(), 3u);
    std::vector<uint32_t> locations;
    for (const auto& s : *adg.switches()) {
      EXPECT_EQ(s.first, 1u);
      EXPECT_EQ(s.second, 0u);
      locations.push_back(s.location);
    }
    EXPECT_EQ(locations, (std::vector<uint32_t>{at(HalfCell::of({1, 1})), at({3, 2}),
                                                at(HalfCell::of({2, 1}))}));
    Executor ex(g, adg, {{0, 2}, {1, 0}}, 7, 0.0);
    for (int t = 1; t < 40 && adg.unfinished_total() > 0; ++t) ex.tick(t);
    EXPECT_EQ(adg.unfinished_total(), 0u) << "both robots finish";
    EXPECT_EQ(ex.conflicts, 0u);
  }
}

// The same following case under switchable-lookahead (SwitchableTracker's
// TheLookaheadComparesAChainAsAWholeWhereOneLocationClosesACycle): passing robot 0 at (1,1) alone
// closes a cycle inside the compared actions (it costs for ever), so before chains were compared
// as a whole the lookahead made no switch here. Robot 0 has not moved for 5 s: the chain of three
// locations is expected to save, and robot 1 passes at all three.
TEST(LiveAdgLookahead, AChainIsComparedAsAWholeWhereOneLocationClosesACycle) {
  const auto g = open_map(4, 3);
  const Paths window = following_window();
  for (const uint32_t chain : {1u, 8u}) {
    SCOPED_TRACE("chain " + std::to_string(chain));
    LiveAdg adg(g, {{0, 2}, {1, 0}}, Heading::kEast);
    adg.enable_switching({.commit_actions = 1,
                          .anticipate = true,
                          .lookahead_actions = 24,
                          .chain_locations = chain});
    ASSERT_TRUE(adg.append(window, 0).empty());
    adg.on_progress(1, 0, 5.0);  // robot 1 turned south: ready at the edge of (1,0)
    if (chain == 1) {
      EXPECT_TRUE(adg.switches()->empty());
      continue;
    }
    ASSERT_EQ(adg.switches()->size(), 3u);
    EXPECT_EQ(adg.chained(), 3u);
    for (const auto& s : *adg.switches()) {
      EXPECT_EQ(s.first, 1u);
      EXPECT_EQ(s.second, 0u);
      EXPECT_FALSE(s.anticipated);
    }
    Executor ex(g, adg, {{0, 2}, {1, 0}}, 7, 0.0);
    for (int t = 6; t < 60 && adg.unfinished_total() > 0; ++t) ex.tick(t);
    EXPECT_EQ(adg.unfinished_total(), 0u) << "both robots finish";
    EXPECT_EQ(ex.conflicts, 0u);
  }
}

// Anticipation compares a chain as a whole too (SwitchableTracker's
// TheLookaheadAnticipatesAChainWhereOneLocationClosesACycle): entries sent 6 actions ahead, so
// robot 0's entry into (1,1) is due at the append. Robot 1 is expected there after one turn,
// robot 0 after two turns and a move: robot 1 passing at (1,1) alone closes a cycle (robot 0 goes
// on ahead along row 1), and passing at all three shared locations saves more than the margin.
// So it passes at all three, anticipated at t = 0 (no switch without chains in anticipation,
// checked), and both finish.
TEST(LiveAdgLookahead, AnticipationComparesAChainAsAWhole) {
  const auto g = open_map(4, 3);
  const Paths window = following_window();
  LiveAdg adg(g, {{0, 2}, {1, 0}}, Heading::kEast);
  adg.enable_switching({.anticipate = true, .lookahead_actions = 24});
  ASSERT_TRUE(adg.append(window, 0).empty());
  ASSERT_EQ(adg.switches()->size(), 3u);
  EXPECT_EQ(adg.chained(), 3u);
  for (const auto& s : *adg.switches()) {
    EXPECT_EQ(s.first, 1u);
    EXPECT_EQ(s.second, 0u);
    EXPECT_TRUE(s.anticipated);
    EXPECT_EQ(s.time_s, 0.0);
  }
  Executor ex(g, adg, {{0, 2}, {1, 0}}, 7, 0.0);
  for (int t = 1; t < 60 && adg.unfinished_total() > 0; ++t) ex.tick(t);
  EXPECT_EQ(adg.unfinished_total(), 0u) << "both robots finish";
  EXPECT_EQ(ex.conflicts, 0u);
}

TEST(LiveAdgSwitching, PlanOrderWithoutSwitching) {
  LateRobotFixture f;
  ASSERT_TRUE(f.adg.append(f.window, 0).empty());
  EXPECT_EQ(f.adg.switches(), nullptr);
  EXPECT_EQ(f.adg.enqueued(0), 8u);
  f.adg.on_progress(1, 0, 0.5);
  EXPECT_EQ(f.adg.enqueued(1), 2u);
  f.adg.on_progress(0, 6, 1.0);
  EXPECT_EQ(f.adg.enqueued(1), 5u);
}

// Regression: a robot whose next entry comes up at another robot's report is tried then. Robot 1
// waits at (2,0) for robot 2 to leave (3,0), then turns south into (3,1), planned after robot 0
// (late, its entry 5 actions away; entries sent 3 actions ahead). Robot 2's report at t = 1
// sends robot 1 up to that entry: robot 1 passes robot 0 at once, not only at its own next report.
TEST(LiveAdgSwitching, AnEntryThatComesUpAtAnotherRobotsReportIsTriedThen) {
  const auto g = open_map(5, 3);
  LiveAdg adg(g, {{0, 1}, {2, 0}, {3, 0}}, Heading::kEast);
  adg.enable_switching({3});
  ASSERT_TRUE(adg.append({{{0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}},
                          {{2, 0}, {2, 0}, {3, 0}, {3, 0}, {3, 0}, {3, 1}, {3, 2}},
                          {{3, 0}, {4, 0}}},
                         0)
                  .empty());
  ASSERT_EQ(adg.waits_for(1, 1), (std::vector<NodeRef>{{2, 0}}));  // into (3,0)
  ASSERT_EQ(adg.action(1, 4).to, HalfCell::of({3, 1}));
  ASSERT_EQ(adg.waits_for(1, 4), (std::vector<NodeRef>{{0, 6}}));
  adg.on_progress(1, 0, 0.5);
  EXPECT_TRUE(adg.switches()->empty());
  EXPECT_EQ(adg.enqueued(1), 1u);
  adg.on_progress(2, 0, 1.0);  // robot 2 left (3,0): robot 1 is sent up to (3,1)'s edge
  ASSERT_EQ(adg.switches()->size(), 1u);
  EXPECT_DOUBLE_EQ(adg.switches()->front().time_s, 1.0);
  EXPECT_EQ(adg.switches()->front().first, 1u);
  EXPECT_EQ(adg.enqueued(1), 7u);  // through (3,1) into (3,2)
  EXPECT_EQ(adg.waits_for(0, 5), (std::vector<NodeRef>{{1, 5}}));
}

// A robot already sent its way in keeps its turn, whoever is ready.
TEST(LiveAdgSwitching, ASentEntryIsNeverPassed) {
  LateRobotFixture f;
  f.adg.enable_switching({6});
  ASSERT_TRUE(f.adg.append(f.window, 0).empty());
  EXPECT_EQ(f.adg.enqueued(0), 8u);  // within 6 actions: sent
  f.adg.on_progress(1, 0, 0.5);
  EXPECT_TRUE(f.adg.switches()->empty());
  EXPECT_EQ(f.adg.enqueued(1), 2u);
}

// switchable-opt: robot 0's way into (3,1) is due at once (entries sent 6 actions ahead). With
// every action expected to take 1 s (nothing learned yet), robot 0 is expected at (3,1) at 5 s
// and out at 7 s, robot 1 at 2 s and out at 4 s: robot 1 first saves 5 s of waiting, more than a
// 1 s margin, so the order is switched before robot 0's entry is sent (anticipated, at the
// append's time), where plain switching sends it (ASentEntryIsNeverPassed).
TEST(LiveAdgAnticipation, ADueEntryIsPassedWhenThatIsExpectedToSaveMoreThanTheMargin) {
  LateRobotFixture f;
  f.anticipate(6, 1);
  EXPECT_EQ(*f.adg.switches(), (std::vector<PassingSwitch>{{0, f.at_3_1(), 1, 0, true}}));
  EXPECT_EQ(f.adg.enqueued(0), 5u);  // robot 0 waits for robot 1 to leave (3,1)
  EXPECT_EQ(f.adg.waits_for(0, 5), (std::vector<NodeRef>{{1, 3}}));
  EXPECT_EQ(f.adg.enqueued(1), 5u);  // robot 1's entry was decided too: kept, and sent
  f.adg.on_progress(1, 3, 2.0);
  EXPECT_EQ(f.adg.enqueued(0), 8u);
}

// The same under the default 10 s margin: the order stays and robot 0's entry is sent.
TEST(LiveAdgAnticipation, TheOrderStaysWhenTheSavingIsUnderTheMargin) {
  LateRobotFixture f;
  f.anticipate(6);
  EXPECT_TRUE(f.adg.switches()->empty());
  EXPECT_EQ(f.adg.enqueued(0), 8u);
  EXPECT_EQ(f.adg.enqueued(1), 2u);
}

// Entries sent 2 actions ahead: robot 0 reports three actions at once (t = 0.1 s), so its way
// into (3,1) is due in the same report that tries robot 1 (still dirty from the append). First
// come, first served would pass it (robot 1 first is expected to save 0.2 s); a due entry is
// anticipation's to decide, which keeps it under the 10 s margin (SwitchableTracker's
// AnEntryDueNowIsNotTakenByFirstComeFirstServed, on the growing graph).
TEST(LiveAdgAnticipation, AnEntryDueNowIsNotTakenByFirstComeFirstServed) {
  LateRobotFixture f;
  f.anticipate(2);
  EXPECT_EQ(f.adg.enqueued(0), 5u);  // held: farther than 2 actions
  f.adg.on_progress(0, 2, 0.1);
  EXPECT_TRUE(f.adg.switches()->empty());
  EXPECT_EQ(f.adg.enqueued(0), 8u);
  EXPECT_EQ(f.adg.waits_for(1, 2), (std::vector<NodeRef>{{0, 6}}));
}

// Far from a free location, first come, first served still passes a robot that is expected
// late: robot 1 turned at 0.5 s, robot 0 is 5 actions from (3,1) and not due (entries 2 ahead).
TEST(LiveAdgAnticipation, FirstComeFirstServedPassesWhenThatIsExpectedToSave) {
  LateRobotFixture f;
  f.anticipate(2);
  f.adg.on_progress(1, 0, 0.5);
  ASSERT_EQ(f.adg.switches()->size(), 1u);
  EXPECT_FALSE(f.adg.switches()->front().anticipated);
  EXPECT_EQ(f.adg.switches()->front().first, 1u);
  EXPECT_EQ(f.adg.waits_for(0, 5), (std::vector<NodeRef>{{1, 3}}));
}

// A switched order is the one the next window links behind: robot 2, planned into (3,1) after
// both, waits for robot 0 (now the last to leave), not for robot 1 (last in the plan's order).
TEST(LiveAdgSwitching, TheNextWindowFollowsTheSwitchedOrder) {
  LateRobotFixture f;
  LiveAdg adg(f.g, {{0, 1}, {3, 0}, {2, 0}}, Heading::kEast);
  adg.enable_switching({2});
  auto window = f.window;
  window.push_back({{2, 0}});
  ASSERT_TRUE(adg.append(window, 0).empty());
  adg.on_progress(1, 0, 0.5);
  ASSERT_EQ(adg.switches()->size(), 1u);
  adg.truncate(adg.commit_cut({5, 5, 0}, 100));  // keeps every action
  // Robot 2: east to (3,0), turn south, into (3,1) (its 5th action), then west to (2,1).
  ASSERT_TRUE(adg.append({{{4, 1}}, {{3, 2}}, {{2, 0}, {3, 0}, {3, 1}, {2, 1}}}, 8).empty());
  EXPECT_EQ(adg.action(2, 4).to, HalfCell::of({3, 1}));
  EXPECT_EQ(adg.waits_for(2, 4), (std::vector<NodeRef>{{0, 6}}));
}

// Regression: truncate dropped robot 0's actions first, then cleaned the out-lists of robot 1's
// dropped actions' predecessors through node(0, s) for s past robot 0's end: a write into
// destroyed nodes (silent in a release build; the sanitized build's checked deque aborts).
TEST(LiveAdg, TruncatingBothSidesOfAPassingOrderTouchesNoDroppedAction) {
  const auto g = open_map(3, 3);
  LiveAdg adg(g, {{0, 1}, {1, 0}}, Heading::kEast);
  ASSERT_TRUE(adg.append({{{0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 0}, {1, 1}, {1, 2}}}, 0).empty());
  ASSERT_EQ(adg.waits_for(1, 2), (std::vector<NodeRef>{{0, 2}}));
  const auto cut = adg.commit_cut({0, 0}, 0);  // nothing sent, no look-ahead: all dropped
  EXPECT_EQ(cut.end, (std::vector<uint32_t>{0, 0}));
  adg.truncate(cut);
  EXPECT_EQ(adg.end(0), 0u);
  EXPECT_EQ(adg.end(1), 0u);
  EXPECT_EQ(adg.appended_total(), 0u);
  // The graph grows again from the cut as if nothing had been appended.
  ASSERT_TRUE(adg.append({{{0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 0}, {1, 1}, {1, 2}}}, 1).empty());
  EXPECT_EQ(adg.waits_for(1, 2), (std::vector<NodeRef>{{0, 2}}));
}

TEST(LiveAdg, ASwapWindowIsRefusedWhole) {
  const auto g = open_map(2, 1);
  LiveAdg adg(g, {{0, 0}, {1, 0}}, Heading::kEast);
  const auto problems = adg.append({{{0, 0}, {1, 0}}, {{1, 0}, {0, 0}}}, 0);
  ASSERT_FALSE(problems.empty());
  EXPECT_THAT(problems[0].message, HasSubstr("cycle"));
  EXPECT_EQ(adg.appended_total(), 0u);
  EXPECT_EQ(adg.end(0), 0u);
}

TEST(LiveAdg, EnteringWhereAnotherRobotStaysIsRefused) {
  const auto g = open_map(3, 1);
  LiveAdg adg(g, {{0, 0}, {2, 0}}, Heading::kEast);
  // Robot 1 parks on (1,0) at t=1; robot 0 enters it at t=2.
  const auto problems = adg.append({{{0, 0}, {0, 0}, {1, 0}}, {{2, 0}, {1, 0}, {1, 0}}}, 0);
  ASSERT_FALSE(problems.empty());
  EXPECT_THAT(problems[0].to_string(), HasSubstr("robot 0: enters (x=1,y=0)"));
  EXPECT_EQ(adg.appended_total(), 0u);
}

TEST(LiveAdg, AWindowMustStartWhereTheRobotStops) {
  const auto g = open_map(3, 1);
  LiveAdg adg(g, {{0, 0}}, Heading::kEast);
  const auto problems = adg.append({{{1, 0}, {2, 0}}}, 0);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_THAT(problems[0].message,
              HasSubstr("starts at (x=1,y=0) but the robot stops at (x=0,y=0)"));
}

TEST(LiveAdg, TheCutKeepsEveryPredecessorOfAKeptAction) {
  const auto g = open_map(4, 3);
  LiveAdg adg(g, {{0, 1}, {1, 0}}, Heading::kEast);
  // Robot 1 passes (1,1) first (t=1), robot 0 follows it there at t=2.
  ASSERT_TRUE(
      adg.append({{{0, 1}, {0, 1}, {1, 1}, {2, 1}}, {{1, 0}, {1, 1}, {1, 2}, {1, 2}}}, 0).empty());
  // Keep robot 0's first two actions (rotation-free east half-moves), nothing of robot 1: the
  // closure keeps robot 1 up to leaving (1,1) and past the midpoint, onto a cell.
  const auto cut = adg.commit_cut({2, 0}, 0);
  EXPECT_EQ(cut.end[0], 2u);
  EXPECT_EQ(cut.end[1], 5u);  // rotate, 2 half-moves to (1,1), 2 half-moves to (1,2)
  EXPECT_EQ(cut.cell[1], (Cell{1, 2}));
  EXPECT_EQ(cut.cell[0], (Cell{1, 1}));
  // Nothing is stranded: the kept actions run to the end without a new window.
  adg.truncate(cut);
  Executor ex(g, adg, {{0, 1}, {1, 0}}, 1);
  for (int t = 0; t < 50; ++t) ex.tick();
  EXPECT_EQ(adg.finished(0), 2u);
  EXPECT_EQ(adg.finished(1), 5u);
  EXPECT_EQ(adg.after_finished(0), HalfCell::of({1, 1}));
  EXPECT_FALSE(adg.deadlocked());
}

struct StreamCase {
  uint64_t seed;
  double delay_p;
  uint32_t lookahead;
  int period;
  uint32_t commit = 0;      // > 0: passing orders switch (entries sent this many actions ahead)
  bool anticipate = false;  // switchable-opt (margin 0.5 s: many anticipated switches)
  bool look = false;        // switchable-lookahead (24 actions)
  uint32_t chain = SwitchOptions{}.chain_locations;  // 1: one location at a time
  uint32_t window = 0;  // the lookahead's window search (SwitchOptions::window_pairs)
};

// Random task streams on a cramped map, replanned every `period` ticks from the commit cut with
// PIBT, executed with random durations and delays: every window is accepted (acyclic), no two
// robots ever hold one location, every action runs once, nothing deadlocks, a cut never strands
// a robot, and tasks keep being done.
// With switching on, the same must hold; returns the switches made.
std::size_t anticipated_total = 0;  // anticipated switches of the streams run
std::size_t compared_total = 0;     // and pairs compared over their cone
std::size_t chained_total = 0;      // and switches made as parts of chains
std::size_t windowed_total = 0;     // and comparisons searched over a window

std::size_t run_stream(const StreamCase& c) {
  const auto g = planning::generate_random_map(16, 16, 0.2, c.seed);
  const std::size_t robots = 40;
  const auto starts = planning::random_starts(g, robots, c.seed);
  const auto tasks = planning::generate_tasks(g, {}, 2000, 1, c.seed);
  planning::DistanceCache dist(g);
  planning::TableHeuristic tables(dist);
  planning::Pibt pibt(g, tables, c.seed);
  LiveAdg adg(g, starts, Heading::kEast);
  if (c.commit > 0) {
    SwitchOptions o{c.commit};
    o.anticipate = c.anticipate || c.look;
    o.margin_s = 0.5;
    if (c.look) o.lookahead_actions = 24;
    o.chain_locations = c.chain;
    o.window_pairs = c.window;
    adg.enable_switching(o);
  }
  Executor ex(g, adg, starts, c.seed + 1, c.delay_p);
  std::vector<std::size_t> task(robots);
  for (std::size_t r = 0; r < robots; ++r) task[r] = r;
  std::size_t next = robots, reached = 0, executed = 0;
  for (int t = 0; t < 1500; ++t) {
    if (t % c.period == 0) {
      const auto cut = adg.commit_cut(ex.sent(8), c.lookahead);
      for (uint32_t r = 0; r < robots; ++r) EXPECT_GE(cut.end[r], ex.sent(8)[r]);
      adg.truncate(cut);
      planning::WindowRequest req{cut.cell, Paths(robots), 6};
      for (std::size_t r = 0; r < robots; ++r) req.goals[r] = tasks[task[r]].errands;
      const auto w = pibt.plan(req);
      const auto problems = adg.append(w.paths, t);
      EXPECT_TRUE(problems.empty()) << problems[0].to_string();
      if (!problems.empty()) return 0;
    }
    executed += ex.tick(t);
    EXPECT_FALSE(adg.deadlocked()) << "t=" << t;
    if (adg.deadlocked()) return 0;
    for (uint32_t r = 0; r < robots; ++r) {
      if (adg.after_finished(r) == HalfCell::of(tasks[task[r]].errands[0]))
        task[r] = next++, ++reached;
    }
  }
  EXPECT_EQ(ex.conflicts, 0u);
  EXPECT_EQ(executed, adg.finished_total());
  EXPECT_GT(reached, robots) << "the stream stalled";
  compared_total += adg.lookahead_comparisons();
  windowed_total += adg.lookahead_windowed();
  chained_total += adg.chained();
  if (c.chain == 1) {
    EXPECT_EQ(adg.chained(), 0u);
  }
  if (c.anticipate || c.look)
    anticipated_total +=
        std::ranges::count_if(*adg.switches(), [](const auto& s) { return s.anticipated; });
  return adg.switches() ? adg.switches()->size() : 0;
}

TEST(LiveAdgProperty, RandomStreamsStaySafeAndLive) {
  for (const StreamCase c : {StreamCase{1, 0, 0, 5}, StreamCase{2, 0.2, 4, 3},
                             StreamCase{3, 0.5, 2, 7}, StreamCase{4, 0.1, 10, 1}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed));
    EXPECT_EQ(run_stream(c), 0u);
    if (HasFailure()) return;
  }
}

// Switching on the growing graph (issue 29): random streams under heavy delays, entries sent 1,
// 2 or 6 actions ahead, replanned often (so windows link behind switched orders), one location
// at a time and with chains (live_adg_chain.cpp): still no two robots on one location, no
// deadlock, every action once, tasks done; and switches happen, chained ones too.
TEST(LiveAdgProperty, SwitchingStreamsStaySafeAndLive) {
  for (const uint32_t chain : {1u, 8u}) {
    std::size_t switches = 0;
    chained_total = 0;
    for (StreamCase c :
         {StreamCase{11, 0.3, 4, 3, 1}, StreamCase{12, 0.5, 2, 7, 2}, StreamCase{13, 0.2, 10, 1, 6},
          StreamCase{14, 0.4, 0, 5, 1}, StreamCase{15, 0.6, 8, 2, 6}, StreamCase{16, 0, 4, 4, 2}}) {
      c.chain = chain;
      SCOPED_TRACE("seed " + std::to_string(c.seed) + " commit " + std::to_string(c.commit) +
                   " chain " + std::to_string(chain));
      switches += run_stream(c);
      if (HasFailure()) return;
    }
    EXPECT_GT(switches, 100u);
    if (chain > 1) {
      EXPECT_GT(chained_total, 500u);  // 1440 of 1982
    }
  }
}

// switchable-opt on the growing graph: the same streams with durations learned from the
// executor's reports (ticks of 1 s, delays), robots up to 12 actions from their entry passing by
// expected times and due entries decided before they are sent: the same safety and liveness, and
// anticipated switches happen.
TEST(LiveAdgProperty, AnticipatingStreamsStaySafeAndLive) {
  std::size_t switches = 0;
  anticipated_total = chained_total = 0;
  for (const StreamCase c :
       {StreamCase{21, 0.3, 4, 3, 1, true}, StreamCase{22, 0.5, 2, 7, 2, true},
        StreamCase{23, 0.2, 10, 1, 6, true}, StreamCase{24, 0.4, 0, 5, 1, true},
        StreamCase{25, 0.6, 8, 2, 6, true}, StreamCase{26, 0, 4, 4, 2, true}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " commit " + std::to_string(c.commit));
    switches += run_stream(c);
    if (HasFailure()) return;
  }
  EXPECT_GT(switches, 100u);
  EXPECT_GT(anticipated_total, 50u);
  EXPECT_GT(chained_total, 300u);  // 1000 of 1748: a chain's links by expected savings too
}

// switchable-lookahead on the growing graph (SwitchableTracker's
// LookaheadKeepsTheOrderWhenThePassedRobotHoldsUpOthersLater): robot 0 runs east along row 1 to
// (8,1); robot 1, above (2,1), is planned to cross it after robot 0; robots 2, 3 and 4, below
// (5,1), (6,1) and (7,1), are planned to cross row 1 right after robot 0 too. Every action
// expected to take 1 s: at (2,1) the location's queue expects robot 1 passing first to save
// waiting (switchable-opt with a 0.5 s margin switches at the append), but robot 0's later pass
// holds up robots 2, 3 and 4: the lookahead keeps the order.
Paths crossing_with_followers() {
  std::vector<Cell> zero;
  for (int32_t x = 0; x <= 8; ++x) zero.push_back({x, 1});
  Paths paths{zero, {{2, 0}, {2, 0}, {2, 0}, {2, 1}, {2, 2}}};
  for (int32_t x = 5; x <= 7; ++x) {
    std::vector<Cell> up(static_cast<std::size_t>(x + 1), Cell{x, 2});
    up.push_back({x, 1});
    up.push_back({x, 0});
    paths.push_back(up);
  }
  return paths;
}

SwitchOptions lookahead_options(bool look) {
  SwitchOptions o;
  o.anticipate = true;
  o.margin_s = 0.5;
  if (look) o.lookahead_actions = 24;
  return o;
}

TEST(LiveAdgLookahead, TheOrderStaysWhenThePassedRobotHoldsUpOthersLater) {
  const auto g = open_map(9, 3);
  const auto paths = crossing_with_followers();
  std::vector<Cell> starts;
  for (const auto& p : paths) starts.push_back(p[0]);
  const auto at_2_1 = static_cast<uint32_t>(g.half_index(HalfCell::of({2, 1})));
  ASSERT_EQ(paths.size(), 5u);
  LiveAdg opt(g, starts, Heading::kEast);
  opt.enable_switching(lookahead_options(false));
  ASSERT_TRUE(opt.append(paths, 0).empty());
  EXPECT_EQ(*opt.switches(), (std::vector<PassingSwitch>{{0, at_2_1, 1, 0, true}}));

  LiveAdg adg(g, starts, Heading::kEast);
  adg.enable_switching(lookahead_options(true));
  ASSERT_TRUE(adg.append(paths, 0).empty());
  EXPECT_EQ(adg.lookahead_comparisons(), 1u);
  EXPECT_EQ(adg.lookahead_widened(), 1u);  // its first 16 actions do not show the loss
  EXPECT_TRUE(adg.switches()->empty());
  ASSERT_EQ(adg.action(0, 3).to, HalfCell::of({2, 1}));
  EXPECT_GT(adg.enqueued(0), 3u);  // decided: sent its way into (2,1)
  EXPECT_EQ(adg.enqueued(1), 2u);  // robot 1 waits at the cell's edge
  EXPECT_EQ(adg.waits_for(1, 2), (std::vector<NodeRef>{{0, 4}}));
  Executor ex(g, adg, starts, 1);
  for (int t = 0; t < 60; ++t) ex.tick(t);
  EXPECT_EQ(ex.conflicts, 0u);
  for (uint32_t r = 0; r < 5; ++r) EXPECT_EQ(adg.finished(r), adg.end(r)) << "robot " << r;
  EXPECT_TRUE(std::ranges::none_of(*adg.switches(),
                                   [&](const PassingSwitch& s) { return s.location == at_2_1; }));
}

// The window search on the growing graph (SwitchableTracker's
// WindowSearchSwitchesWhenThePairsAfterItMaySwitchToo): with the followers' three crossings in
// the window (8 settings), the best setting has them pass robot 0 where they are ready long
// before it, and robot 1 passing first at (2,1) then costs nobody behind: robot 1 passes,
// anticipated at the append. Every setting's edges are restored: the graph after the comparison
// is the one-switch graph, and all finish without a conflict.
TEST(LiveAdgLookahead, TheWindowSearchSwitchesWhenThePairsAfterItMaySwitchToo) {
  const auto g = open_map(9, 3);
  const auto paths = crossing_with_followers();
  std::vector<Cell> starts;
  for (const auto& p : paths) starts.push_back(p[0]);
  const auto at_2_1 = static_cast<uint32_t>(g.half_index(HalfCell::of({2, 1})));
  LiveAdg adg(g, starts, Heading::kEast);
  SwitchOptions o = lookahead_options(true);
  o.window_pairs = 3;
  adg.enable_switching(o);
  ASSERT_TRUE(adg.append(paths, 0).empty());
  EXPECT_EQ(adg.lookahead_windowed(), 1u);
  EXPECT_EQ(adg.window_settings(), 8u);
  EXPECT_EQ(*adg.switches(), (std::vector<PassingSwitch>{{0, at_2_1, 1, 0, true}}));
  // Robot 0's entry into (2,1) waits for robot 1's leaving it; each follower still waits for
  // robot 0 at its crossing (their own turn has not come).
  EXPECT_EQ(adg.waits_for(0, 3), (std::vector<NodeRef>{{1, 3}}));
  Executor ex(g, adg, starts, 1);
  for (int t = 0; t < 60; ++t) ex.tick(t);
  EXPECT_EQ(ex.conflicts, 0u);
  for (uint32_t r = 0; r < 5; ++r) EXPECT_EQ(adg.finished(r), adg.end(r)) << "robot " << r;
}

// Without robots behind (LateRobotFixture's crossing), the lookahead lets the robot expected
// sooner pass first: robot 1 goes first, anticipated at the append, as switchable-opt does.
TEST(LiveAdgLookahead, TheRobotExpectedSoonerPassesFirst) {
  LateRobotFixture f;
  f.adg.enable_switching(lookahead_options(true));
  ASSERT_TRUE(f.adg.append(f.window, 0).empty());
  EXPECT_EQ(*f.adg.switches(), (std::vector<PassingSwitch>{{0, f.at_3_1(), 1, 0, true}}));
  EXPECT_EQ(f.adg.lookahead_comparisons(), 1u);
  EXPECT_EQ(f.adg.waits_for(0, 5), (std::vector<NodeRef>{{1, 3}}));
  EXPECT_EQ(f.adg.enqueued(1), 5u);
}

// switchable-lookahead on the growing graph: the same streams, both decisions made by the
// expected times of the actions each pair's order affects: the same safety and liveness, cones
// compared, and switches, anticipated ones too.
TEST(LiveAdgProperty, LookaheadStreamsStaySafeAndLive) {
  std::size_t switches = 0;
  anticipated_total = compared_total = chained_total = 0;
  for (const StreamCase c :
       {StreamCase{31, 0.3, 4, 3, 1, false, true}, StreamCase{32, 0.5, 2, 7, 2, false, true},
        StreamCase{33, 0.2, 10, 1, 6, false, true}, StreamCase{34, 0.4, 0, 5, 1, false, true},
        StreamCase{35, 0.6, 8, 2, 6, false, true}, StreamCase{36, 0, 4, 4, 2, false, true}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " commit " + std::to_string(c.commit));
    switches += run_stream(c);
    if (HasFailure()) return;
  }
  EXPECT_GT(switches, 100u);
  EXPECT_GT(anticipated_total, 20u);
  EXPECT_GT(compared_total, 100u);
  EXPECT_GT(chained_total, 100u);  // 1051; 3 before chains were compared as a whole
}

// The window search on the growing graph: the same streams with a window of 3 pairs, each
// setting made on the graph's edges and restored before anything is sent: the same safety and
// liveness, and windows searched.
TEST(LiveAdgProperty, WindowSearchStreamsStaySafeAndLive) {
  std::size_t switches = 0;
  windowed_total = 0;
  for (StreamCase c :
       {StreamCase{41, 0.3, 4, 3, 1, false, true}, StreamCase{42, 0.5, 2, 7, 2, false, true},
        StreamCase{43, 0.2, 10, 1, 6, false, true}, StreamCase{44, 0.4, 0, 5, 1, false, true},
        StreamCase{45, 0.6, 8, 2, 6, false, true}, StreamCase{46, 0, 4, 4, 2, false, true}}) {
    c.window = 3;
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " commit " + std::to_string(c.commit));
    switches += run_stream(c);
    if (HasFailure()) return;
  }
  EXPECT_GT(switches, 100u);
  EXPECT_GT(windowed_total, 100u);
}

}  // namespace
}  // namespace smart::monitor
