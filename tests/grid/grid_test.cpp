#include "smart/grid/grid.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "support/monitor_fixtures.hpp"

namespace smart::grid {
namespace {

TEST(Grid, WorldFrameIsColumnRightRowDown) {
  const auto g = test::grid_of({"...", "...", "..."});
  // Row 0 is the top: y_w = (height-1-row) * cell_m.
  const auto top_left = g.to_world(HalfCell::of({0, 0}), 0.5);
  EXPECT_DOUBLE_EQ(top_left.x_m, 0.0);
  EXPECT_DOUBLE_EQ(top_left.y_m, 1.0);
  const auto mid = g.to_world(HalfCell::midpoint({1, 2}, {2, 2}), 1.0);
  EXPECT_DOUBLE_EQ(mid.x_m, 1.5);
  EXPECT_DOUBLE_EQ(mid.y_m, 0.0);
}

TEST(Grid, HeadingsFollowTheWorldFrame) {
  EXPECT_EQ(heading_of_step({1, 1}, {2, 1}), Heading::kEast);
  EXPECT_EQ(heading_of_step({1, 1}, {1, 0}), Heading::kNorth);  // up a row = +y_w
  EXPECT_EQ(heading_of_step({1, 1}, {0, 1}), Heading::kWest);
  EXPECT_EQ(heading_of_step({1, 1}, {1, 2}), Heading::kSouth);
  EXPECT_DOUBLE_EQ(yaw_rad(Heading::kNorth), std::numbers::pi / 2);
  EXPECT_EQ(parse_heading("south"), Heading::kSouth);
  EXPECT_THROW(parse_heading("up"), std::invalid_argument);
}

TEST(Grid, HalfCellsAndIndices) {
  const auto g = test::grid_of({"..@", "..."});
  EXPECT_TRUE(g.blocked({2, 0}));
  EXPECT_FALSE(g.free({3, 0}));
  EXPECT_FALSE(g.free({-1, 0}));
  EXPECT_EQ(g.free_cells(), 5u);
  EXPECT_EQ(g.half_cell_count(), 5u * 3u);
  EXPECT_EQ(g.half_index({4, 2}), 14u);
  const auto m = HalfCell::midpoint({0, 0}, {1, 0});
  EXPECT_FALSE(m.is_cell());
  EXPECT_EQ(to_string(m), "(x=0.5,y=0)");
  EXPECT_EQ(to_string(Cell{3, 7}), "(x=3,y=7)");
}

}  // namespace
}  // namespace smart::grid
