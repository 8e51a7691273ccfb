// Contract: independent random walks for sim benchmarks (`smart bench sim`): robots start on
// distinct free cells drawn by a seeded shuffle, and each timestep moves to a random free
// neighbour (up to 8 draws, else it waits). Robots ignore each other: paths collide, which is
// the point (the simulator's contact handling is part of what is measured). Pure and
// deterministic: the same grid, counts and seed give the same walks.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/grid/plan.hpp"

namespace smart::planning {

struct RandomWalks {
  grid::Plan plan;                 // robot r's path starts at starts[r], one step per second
  std::vector<grid::Cell> starts;  // distinct free cells
};

// `steps` timesteps per robot. Throws std::invalid_argument naming both counts when the grid
// has fewer free cells than robots.
RandomWalks generate_random_walks(const grid::Grid& grid, std::size_t robots, std::size_t steps,
                                  uint64_t seed);

}  // namespace smart::planning
