#include "smart/sim/walls.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/monitor_fixtures.hpp"

namespace smart::sim {
namespace {

// 5x5 map, cell 1 m; world y = 4 - row. The blocked cell (2,2) is centred at (2, 2).
const auto kGrid = test::grid_of({".....", ".....", "..@..", ".....", "....."});

std::vector<WallContact> at(double x, double y, double r = 0.25, const monitor::Grid& g = kGrid) {
  std::vector<WallContact> out;
  wall_contacts(g, 1.0, x, y, r, out);
  return out;
}

TEST(Walls, FaceContactPushesOutAlongTheFaceNormal) {
  const auto c = at(2.7, 2.1);  // 0.2 from the east face at x = 2.5
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth_m, 0.05, 1e-12);
  EXPECT_EQ(c[0].nx, 1.0);
  EXPECT_EQ(c[0].ny, 0.0);
  EXPECT_TRUE(at(2.8, 2.1).empty());
}

TEST(Walls, ConvexCornerIsAPoint) {
  const auto c = at(2.6, 2.6);  // diagonal from the NE corner (2.5, 2.5)
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth_m, 0.25 - std::hypot(0.1, 0.1), 1e-12);
  EXPECT_NEAR(c[0].nx, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(c[0].ny, std::sqrt(0.5), 1e-12);
}

TEST(Walls, FlatWallSeamGivesOneContactNotTwo) {
  const auto wall = test::grid_of({".....", ".....", "@@@@@", ".....", "....."});
  for (double x : {1.5, 1.7, 2.0, 2.5}) {
    const auto c = at(x, 2.7, 0.25, wall);
    ASSERT_EQ(c.size(), 1u) << "x = " << x;
    EXPECT_NEAR(c[0].depth_m, 0.05, 1e-12);
    EXPECT_EQ(c[0].ny, 1.0);
  }
}

TEST(Walls, ConcaveCornerGivesTwoContacts) {
  const auto g = test::grid_of({"@@@", "@..", "@.."});
  // Free cell (1,1) is centred at (1, 1); walls to its west (x = 0.5) and north (y = 1.5).
  const auto c = at(0.7, 1.3, 0.25, g);
  ASSERT_EQ(c.size(), 2u);
}

TEST(Walls, OutsideTheMapIsBlocked) {
  const auto c = at(0.1, 2.0);  // west map edge at x = -0.5
  EXPECT_TRUE(c.empty());
  const auto e = at(-0.4, 2.0);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].nx, 1.0);
  EXPECT_NEAR(e[0].depth_m, 0.15, 1e-12);
}

TEST(Walls, CellAtUsesTheWorldFrame) {
  EXPECT_EQ(cell_at(kGrid, 1.0, 2.2, 3.9), (monitor::Cell{2, 0}));
  EXPECT_EQ(cell_at(kGrid, 0.5, 1.0, 0.0), (monitor::Cell{2, 4}));
}

}  // namespace
}  // namespace smart::sim
