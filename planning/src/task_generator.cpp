#include "smart/planning/task_generator.hpp"

#include <random>
#include <stdexcept>
#include <string>

#include "smart/planning/generators.hpp"

namespace smart::planning {

namespace {

// A draw in [0, n) from the engine's raw output: std::uniform_int_distribution and std::shuffle
// differ between standard libraries, this does not (the bias for n << 2^64 is negligible).
std::size_t below(std::mt19937_64& rng, std::size_t n) {
  return static_cast<std::size_t>(rng() % n);
}

// The marked cells inside the largest region (a marked cell walled off is never an errand).
std::vector<grid::Cell> reachable(const std::vector<grid::Cell>& marked,
                                  const std::vector<uint8_t>& in_region, const grid::Grid& g) {
  std::vector<grid::Cell> out;
  for (const auto c : marked) {
    if (in_region[g.index(c)]) out.push_back(c);
  }
  return out;
}

}  // namespace

std::vector<grid::Cell> random_starts(const grid::Grid& grid, std::size_t robots, uint64_t seed) {
  auto cells = largest_region_cells(grid);
  if (cells.size() < robots) {
    throw std::invalid_argument(std::to_string(robots) +
                                " robots need distinct start cells but the map's largest free "
                                "region has " +
                                std::to_string(cells.size()) + "; use fewer robots");
  }
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < robots; ++i)
    std::swap(cells[i], cells[i + below(rng, cells.size() - i)]);
  cells.resize(robots);
  return cells;
}

std::vector<grid::Task> generate_tasks(const grid::Grid& grid, const grid::MapMarks& marks,
                                       std::size_t count, std::size_t errands, uint64_t seed) {
  const auto cells = largest_region_cells(grid);
  if (cells.size() < 2) throw std::invalid_argument("the map has fewer than two free cells");
  std::vector<uint8_t> in_region(static_cast<std::size_t>(grid.width()) * grid.height(), 0);
  for (const auto c : cells) in_region[grid.index(c)] = 1;
  const auto stations = reachable(marks.workstations, in_region, grid);
  const auto ends = reachable(marks.endpoints, in_region, grid);
  const bool alternate = !stations.empty() && !ends.empty();
  std::mt19937_64 rng(seed ^ 0x7a5c5eedULL);
  std::vector<grid::Task> tasks(count);
  for (std::size_t t = 0; t < count; ++t) {
    tasks[t].id = static_cast<uint32_t>(t);
    for (std::size_t k = 0; k < errands; ++k) {
      const auto& pool = !alternate ? cells : (k % 2 == 0 ? ends : stations);
      grid::Cell c = pool[below(rng, pool.size())];
      while (!alternate && !tasks[t].errands.empty() && c == tasks[t].errands.back()) {
        c = pool[below(rng, pool.size())];
      }
      tasks[t].errands.push_back(c);
    }
  }
  return tasks;
}

}  // namespace smart::planning
