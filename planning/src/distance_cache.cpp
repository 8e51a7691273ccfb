#include "smart/planning/distance_cache.hpp"

#include <algorithm>

#include "smart/planning/generators.hpp"

namespace smart::planning {

DistanceCache::DistanceCache(const grid::Grid& grid, std::size_t budget_bytes,
                             std::size_t max_tables)
    : grid_(grid),
      max_tables_(std::max<std::size_t>(
          4, std::min(max_tables, budget_bytes / std::max<std::size_t>(1, table_bytes(grid))))) {}

DistanceCache::Table DistanceCache::to(grid::Cell goal) {
  const auto key = static_cast<uint32_t>(grid_.index(goal));
  if (const auto it = tables_.find(key); it != tables_.end()) {
    lru_.splice(lru_.begin(), lru_, it->second.at);
    return it->second.table;
  }
  if (tables_.size() >= max_tables_) {
    tables_.erase(lru_.back());
    lru_.pop_back();
  }
  ++computed_;
  lru_.push_front(key);
  auto table = std::make_shared<const std::vector<int32_t>>(bfs_distances(grid_, goal));
  tables_.emplace(key, Entry{table, lru_.begin()});
  return table;
}

}  // namespace smart::planning
