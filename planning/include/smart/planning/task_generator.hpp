// Contract: seeded lifelong task streams and starts for any map (`smart run --lifelong --map M
// --tasks random`). Everything is drawn from the free cells reachable from one another (the
// largest 4-connected free region), so no errand is ever walled off:
// - random_starts(): `robots` distinct cells;
// - generate_tasks(): `count` tasks of `errands` cells each. Where the map marks workstations
//   and endpoints (LoRR 'E'/'S', LSMART 'w'/'e', map_reader.hpp) errands alternate between an
//   endpoint and a workstation (fetch at a shelf, deliver at a station, as LSMART's warehouse
//   tasks do); otherwise they are uniform random cells, each differing from the one before.
// Deterministic for a seed (std::mt19937_64, so the same on every machine and compiler).
#pragma once

#include <cstdint>
#include <vector>

#include "smart/grid/lorr.hpp"

namespace smart::planning {

// Throws std::invalid_argument when the largest free region has fewer than `robots` cells.
std::vector<grid::Cell> random_starts(const grid::Grid& grid, std::size_t robots, uint64_t seed);

std::vector<grid::Task> generate_tasks(const grid::Grid& grid, const grid::MapMarks& marks,
                                       std::size_t count, std::size_t errands, uint64_t seed);

}  // namespace smart::planning
