#include "smart/planning/generators.hpp"

#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::planning {
namespace {

using namespace grid;  // the vocabulary the planners work in

TEST(Generators, DefaultWarehouseIsMovingAIsWarehouse10201021CellForCell) {
  const auto dir = test::benchmarks_dir() / "maps";
  ASSERT_TRUE(std::filesystem::exists(dir)) << smart::test::no_benchmarks(dir);
  const auto original = parse_map(read_text_file(dir / "warehouse-10-20-10-2-1.map", "map"),
                                  "warehouse-10-20-10-2-1.map");
  const auto generated = generate_warehouse({});
  ASSERT_EQ(generated.width(), original.width());
  ASSERT_EQ(generated.height(), original.height());
  for (int32_t y = 0; y < original.height(); ++y) {
    for (int32_t x = 0; x < original.width(); ++x) {
      ASSERT_EQ(generated.blocked({x, y}), original.blocked({x, y})) << "x=" << x << " y=" << y;
    }
  }
}

bool connected(const Grid& g) {
  Cell first{-1, -1};
  for (int32_t y = 0; y < g.height() && first.x < 0; ++y)
    for (int32_t x = 0; x < g.width(); ++x)
      if (!g.blocked({x, y})) {
        first = {x, y};
        break;
      }
  const auto d = bfs_distances(g, first);
  for (int32_t y = 0; y < g.height(); ++y)
    for (int32_t x = 0; x < g.width(); ++x)
      if (!g.blocked({x, y}) && d[g.index({x, y})] < 0) return false;
  return true;
}

TEST(Generators, RandomAndMazeMapsAreConnectedAndDeterministic) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const auto r = generate_random_map(40, 30, 0.3, seed);
    EXPECT_TRUE(connected(r)) << seed;
    EXPECT_GT(r.free_cells(), 400u);
    const auto m = generate_maze(33, 33, 3, seed);
    EXPECT_TRUE(connected(m)) << seed;
    EXPECT_GT(m.free_cells(), 33u * 33u / 3);
  }
  EXPECT_EQ(to_movingai_map(generate_random_map(20, 20, 0.2, 9)),
            to_movingai_map(generate_random_map(20, 20, 0.2, 9)));
  EXPECT_EQ(generate_empty_map(7, 5).free_cells(), 35u);
}

TEST(Generators, MapAndScenarioTextRoundTripThroughTheReaders) {
  const auto g = generate_maze(21, 17, 2, 3);
  const auto back = parse_map(to_movingai_map(g), "maze.map");
  EXPECT_EQ(to_movingai_map(back), to_movingai_map(g));
  const auto s = generate_scenario(g, 12, 4, "maze.map");
  const auto read = parse_scen(to_movingai_scen(s, g), "maze.scen");
  ASSERT_EQ(read.agents.size(), 12u);
  EXPECT_TRUE(check_scen_against_map(read, back).empty());
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(read.agents[i].start, s.agents[i].start);
    EXPECT_EQ(read.agents[i].goal, s.agents[i].goal);
  }
  EXPECT_THROW(generate_scenario(generate_empty_map(2, 2), 5, 1, "x"), std::invalid_argument);
}

}  // namespace
}  // namespace smart::planning
