#include "smart/planning/space_time_reservations.hpp"

#include <gtest/gtest.h>

#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

using grid::Cell;

TEST(SpaceTimeReservations, APathTakesItsCellsAndMovesAndTakingItOutFreesThem) {
  const auto g = generate_empty_map(4, 1);
  SpaceTimeReservations res(g, 70);  // two words a cell
  const std::vector<Cell> p{{0, 0}, {1, 0}, {1, 0}, {2, 0}};
  res.set(p, true);
  EXPECT_TRUE(res.taken(g.index({1, 0}), 1));
  EXPECT_FALSE(res.taken(g.index({1, 0}), 3));
  EXPECT_TRUE(res.swaps(g.index({1, 0}), g.index({0, 0}), 0));   // coming the other way
  EXPECT_FALSE(res.swaps(g.index({2, 0}), g.index({1, 0}), 0));  // following is allowed
  EXPECT_EQ(res.last_use(g.index({2, 0})), 3);
  EXPECT_FALSE(res.taken(g.index({2, 0}), 4));  // not parked
  res.set(p, false);
  EXPECT_FALSE(res.taken(g.index({1, 0}), 1));
  EXPECT_FALSE(res.swaps(g.index({1, 0}), g.index({0, 0}), 0));
  EXPECT_EQ(res.last_use(g.index({2, 0})), -1);
}

TEST(SpaceTimeReservations, AParkedRobotHoldsItsCellPastTheHorizon) {
  const auto g = generate_empty_map(3, 1);
  SpaceTimeReservations res(g, 4);
  const std::vector<Cell> p{{0, 0}, {1, 0}};
  res.set(p, true, true);
  EXPECT_FALSE(res.taken(g.index({1, 0}), 0));
  EXPECT_TRUE(res.taken(g.index({1, 0}), 1000));
  EXPECT_EQ(res.last_use(g.index({1, 0})), 1);
  res.set(p, false, true);
  EXPECT_FALSE(res.taken(g.index({1, 0}), 1000));
}

}  // namespace
}  // namespace smart::planning
