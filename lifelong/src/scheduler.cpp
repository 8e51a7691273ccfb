#include "smart/lifelong/scheduler.hpp"

#include <cstdlib>
#include <limits>

namespace smart::lifelong {

std::vector<std::pair<uint32_t, uint64_t>> GreedyNearestScheduler::assign(
    const std::vector<uint32_t>& free, const std::vector<grid::Cell>& cells,
    const std::vector<OpenTask>& open) {
  std::vector<std::pair<uint32_t, uint64_t>> out;
  std::vector<uint8_t> taken(open.size(), 0);
  for (const uint32_t r : free) {
    const grid::Cell at = cells[r];
    std::size_t best = open.size();
    int32_t best_d = std::numeric_limits<int32_t>::max();
    for (std::size_t k = 0; k < open.size(); ++k) {
      if (taken[k]) continue;
      const int32_t d = std::abs(open[k].first.x - at.x) + std::abs(open[k].first.y - at.y);
      if (d < best_d) best_d = d, best = k;
    }
    if (best == open.size()) break;  // no task left
    taken[best] = 1;
    out.emplace_back(r, open[best].task);
  }
  return out;
}

}  // namespace smart::lifelong
