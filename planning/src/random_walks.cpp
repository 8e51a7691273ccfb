#include "smart/planning/random_walks.hpp"

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>

namespace smart::planning {

namespace {

std::vector<grid::Cell> free_cells(const grid::Grid& grid) {
  std::vector<grid::Cell> free;
  for (int32_t y = 0; y < grid.height(); ++y) {
    for (int32_t x = 0; x < grid.width(); ++x) {
      if (!grid.blocked({x, y})) free.push_back({x, y});
    }
  }
  return free;
}

grid::RobotPath walk(const grid::Grid& grid, int robot, grid::Cell c, std::size_t steps,
                     std::mt19937_64& rng) {
  grid::RobotPath p{robot, 0, {}};
  p.steps.push_back({c, 0, 0});
  for (std::size_t k = 1; k < steps; ++k) {
    const grid::Cell n[4] = {{c.x + 1, c.y}, {c.x - 1, c.y}, {c.x, c.y + 1}, {c.x, c.y - 1}};
    for (int tries = 0; tries < 8; ++tries) {
      const auto cand = n[rng() % 4];
      if (grid.free(cand)) {
        c = cand;
        break;
      }
    }
    p.steps.push_back({c, double(k), 0});
  }
  return p;
}

}  // namespace

RandomWalks generate_random_walks(const grid::Grid& grid, std::size_t robots, std::size_t steps,
                                  uint64_t seed) {
  std::vector<grid::Cell> free = free_cells(grid);
  if (free.size() < robots) {
    throw std::invalid_argument(std::to_string(robots) + " robots do not fit on " +
                                std::to_string(free.size()) + " free cells");
  }
  std::mt19937_64 rng(seed);
  std::shuffle(free.begin(), free.end(), rng);
  RandomWalks w;
  w.starts.assign(free.begin(), free.begin() + static_cast<long>(robots));
  for (std::size_t r = 0; r < robots; ++r) {
    w.plan.paths.push_back(walk(grid, static_cast<int>(r), free[r], steps, rng));
  }
  return w;
}

}  // namespace smart::planning
