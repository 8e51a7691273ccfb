#include "smart/sim/walls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "smart/planning/random_plan.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::sim {
namespace {

// 5x5 map, cell 1 m; world y = 4 - row. The blocked cell (2,2) is centred at (2, 2).
const auto kGrid = test::grid_of({".....", ".....", "..@..", ".....", "....."});

std::vector<WallContact> at(double x, double y, double r = 0.25, const grid::Grid& g = kGrid) {
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
  EXPECT_EQ(cell_at(kGrid, 1.0, 2.2, 3.9), (grid::Cell{2, 0}));
  EXPECT_EQ(cell_at(kGrid, 0.5, 1.0, 0.0), (grid::Cell{2, 4}));
}

// Property: a disc centred in a free cell has a wall contact exactly when it overlaps a blocked
// cell or leaves the map (checked against a brute-force overlap test on every cell), including
// the fast path for discs inside their own cell.
TEST(Walls, ContactIffTheDiscOverlapsABlockedCell) {
  const auto grid = planning::generate_random_grid(12, 9, 0.3, 11);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(-0.5, 11.5), uy(-0.5, 8.5);
  std::vector<WallContact> found;
  int with_contact = 0, checked = 0;
  for (const double r : {0.2, 0.45}) {
    for (int k = 0; k < 20000; ++k) {
      const double x = ux(rng), y = uy(rng);
      const auto c = cell_at(grid, 1.0, x, y);
      if (!grid.free(c)) continue;
      bool overlaps = false;
      for (int32_t row = -1; row <= grid.height(); ++row) {
        for (int32_t col = -1; col <= grid.width(); ++col) {
          if (grid.free({col, row})) continue;  // outside the map counts as blocked
          const double cx = col, cy = grid.height() - 1 - row;
          const double dx = std::max(std::abs(x - cx) - 0.5, 0.0);
          const double dy = std::max(std::abs(y - cy) - 0.5, 0.0);
          if (dx * dx + dy * dy < r * r) overlaps = true;
        }
      }
      found.clear();
      wall_contacts(grid, 1.0, x, y, r, found);
      ASSERT_EQ(!found.empty(), overlaps) << "disc r=" << r << " at (" << x << ", " << y << ")";
      with_contact += overlaps ? 1 : 0;
      ++checked;
    }
  }
  EXPECT_GT(with_contact, checked / 10);  // both cases well covered
  EXPECT_LT(with_contact, checked * 9 / 10);
}

}  // namespace
}  // namespace smart::sim
