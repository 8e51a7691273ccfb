// Contract: deterministic (seeded) generators of valid MAPF instances for property tests and
// benchmarks. generate_random_grid() makes a random obstacle map; generate_random_plan() makes
// conflict-free random-walk paths of `steps` timesteps: robots move to random free neighbours,
// entering a cell only once its occupant has committed to leave (following is allowed, swaps
// and vertex conflicts never happen), and with probability `rotation_probability` per timestep
// a 2x2 block of four waiting robots rotates one cell round the block (a rotation cycle, the
// case the edge midpoints exist for). Trailing waits are dropped, so robots park at their last
// cell. The scenario holds each robot's first and last cell.
#pragma once

#include <cstdint>

#include "smart/grid/grid.hpp"
#include "smart/grid/plan.hpp"
#include "smart/grid/scen_reader.hpp"

namespace smart::planning {

struct RandomPlanOptions {
  std::size_t robots = 10;
  std::size_t steps = 50;
  uint64_t seed = 1;
  double move_probability = 0.8;
  double rotation_probability = 0.2;
};

struct GeneratedInstance {
  grid::Plan plan;
  grid::Scenario scen;
  std::size_t rotation_cycles = 0;
};

grid::Grid generate_random_grid(int32_t width, int32_t height, double obstacle_fraction,
                                uint64_t seed);

// Throws std::invalid_argument when the grid has fewer free cells than robots.
GeneratedInstance generate_random_plan(const grid::Grid& grid, const RandomPlanOptions& options);

}  // namespace smart::planning
