#include "smart/monitor/action_builder.hpp"

#include <gtest/gtest.h>

#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using test::plan_of;

TEST(ActionBuilder, StraightMoveIsTwoHalfMovesThroughTheMidpoint) {
  const auto ap = build_actions(plan_of({{{0, 0}, {1, 0}}}), Heading::kEast);
  ASSERT_EQ(ap.count(0), 2u);
  const auto& a = ap.at(0, 0);
  const auto& b = ap.at(0, 1);
  EXPECT_EQ(a.type, ActionType::kMove);
  EXPECT_EQ(a.from, (HalfCell{0, 0}));
  EXPECT_EQ(a.to, (HalfCell{1, 0}));
  EXPECT_EQ(b.from, (HalfCell{1, 0}));
  EXPECT_EQ(b.to, (HalfCell{2, 0}));
  EXPECT_DOUBLE_EQ(a.start_time, 0.0);
  EXPECT_DOUBLE_EQ(a.end_time, 0.5);
  EXPECT_DOUBLE_EQ(b.end_time, 1.0);
  EXPECT_EQ(a.heading, Heading::kEast);
  EXPECT_EQ(ap.moves, 2u);
  EXPECT_EQ(ap.rotations, 0u);
}

TEST(ActionBuilder, RotatesBeforeTurningAndWaitsGiveNoAction) {
  // East, wait, then north (up a row), then south: a 90° and then a 180° rotation.
  const auto ap =
      build_actions(plan_of({{{0, 2}, {1, 2}, {1, 2}, {1, 1}, {1, 2}}}), Heading::kEast);
  std::vector<ActionType> types;
  std::vector<Heading> headings;
  for (uint32_t s = 0; s < ap.count(0); ++s) {
    types.push_back(ap.at(0, s).type);
    headings.push_back(ap.at(0, s).heading);
    EXPECT_EQ(ap.at(0, s).seq, s);
  }
  using T = ActionType;
  using H = Heading;
  EXPECT_EQ(types, (std::vector<T>{T::kMove, T::kMove, T::kRotate, T::kMove, T::kMove, T::kRotate,
                                   T::kMove, T::kMove}));
  EXPECT_EQ(headings, (std::vector<H>{H::kEast, H::kEast, H::kNorth, H::kNorth, H::kNorth,
                                      H::kSouth, H::kSouth, H::kSouth}));
  const auto& rot = ap.at(0, 2);
  EXPECT_EQ(rot.from, rot.to);
  EXPECT_EQ(rot.from, (HalfCell{2, 4}));
  EXPECT_DOUBLE_EQ(rot.start_time, 2.0);  // after the wait, when the move starts
  EXPECT_EQ(ap.rotations, 2u);
}

TEST(ActionBuilder, InitialHeadingIsConfigurable) {
  const auto ap = build_actions(plan_of({{{0, 0}, {1, 0}}}), Heading::kNorth);
  ASSERT_EQ(ap.count(0), 3u);
  EXPECT_EQ(ap.at(0, 0).type, ActionType::kRotate);
  EXPECT_EQ(ap.at(0, 0).heading, Heading::kEast);
  EXPECT_EQ(ap.initial_heading[0], Heading::kNorth);
}

TEST(ActionBuilder, RobotThatNeverMovesHasNoActions) {
  const auto ap = build_actions(plan_of({{{3, 3}, {3, 3}}, {{0, 0}, {0, 1}}}));
  EXPECT_EQ(ap.count(0), 0u);
  EXPECT_EQ(ap.count(1), 3u);  // rotate south + two half-moves
  EXPECT_EQ(ap.start[0], (HalfCell{6, 6}));
  EXPECT_EQ(ap.robots(), 2u);
}

}  // namespace
}  // namespace smart::monitor
