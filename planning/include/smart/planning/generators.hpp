// Contract: deterministic (seeded) generators of MovingAI maps and scenarios, for the demo and
// for tests that must not depend on outside data.
// - warehouse: a border wall, free margins left and right, and a grid of rectangular shelves
//   separated by one-cell aisles. The defaults reproduce MovingAI's warehouse-10-20-10-2-1
//   (161x63) cell for cell (20 shelf rows, 10 shelf columns, shelves 10x2, margins of 25).
// - random: obstacles with a given probability; only the largest 4-connected free region is
//   kept free, so every free cell can reach every other.
// - empty: no obstacles.
// - maze: a perfect maze (randomised depth-first search) with corridors `corridor` cells wide
//   and walls one cell thick, as in MovingAI's maze-32-32-4.
// Scenarios pick distinct random starts and goals in the largest free region; the last column
// is the 4-connected shortest path length.
#pragma once

#include <cstdint>
#include <string>

#include "smart/grid/grid.hpp"
#include "smart/grid/plan.hpp"
#include "smart/grid/scen_reader.hpp"

namespace smart::planning {

struct WarehouseOptions {
  int shelf_rows = 20;
  int shelf_cols = 10;
  int shelf_length = 10;
  int shelf_height = 2;
  int aisle = 1;
  int margin = 25;
};

grid::Grid generate_warehouse(const WarehouseOptions& o);
grid::Grid generate_random_map(int32_t width, int32_t height, double obstacle_fraction,
                               uint64_t seed);
grid::Grid generate_empty_map(int32_t width, int32_t height);
grid::Grid generate_maze(int32_t width, int32_t height, int corridor, uint64_t seed);

// MovingAI .map text ('.' free, '@' blocked; warehouses use 'T' like the MovingAI originals).
std::string to_movingai_map(const grid::Grid& grid, char blocked_symbol = '@');

// Throws std::invalid_argument when the largest free region has fewer than `agents` cells.
grid::Scenario generate_scenario(const grid::Grid& grid, std::size_t agents, uint64_t seed,
                                 const std::string& map_name);
std::string to_movingai_scen(const grid::Scenario& scen, const grid::Grid& grid);

// The free cells of the largest 4-connected free region, row-major.
std::vector<grid::Cell> largest_region_cells(const grid::Grid& grid);

// 4-connected shortest-path distances from `from` to every cell (-1: unreachable).
std::vector<int32_t> bfs_distances(const grid::Grid& grid, grid::Cell from);

}  // namespace smart::planning
