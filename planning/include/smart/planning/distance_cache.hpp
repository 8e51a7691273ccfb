// Contract: shortest-path distances to goal cells, computed lazily and shared (LoRR and LSMART
// planners keep one backward BFS table per goal: every robot heading to one cell shares it).
// A table is a 4-connected BFS from the goal over free cells (-1: unreachable), made on first
// use and kept while the cache holds fewer than its byte budget and `max_tables`; beyond them the
// least recently used table is dropped (tables are handed out as shared pointers, so a caller's
// copy stays valid). Deterministic: what is cached never changes a distance, only when it is
// computed.
#pragma once

#include <cstdint>
#include <limits>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::planning {

class DistanceCache {
 public:
  using Table = std::shared_ptr<const std::vector<int32_t>>;

  explicit DistanceCache(const grid::Grid& grid, std::size_t budget_bytes = std::size_t{1} << 30,
                         std::size_t max_tables = SIZE_MAX);

  Table to(grid::Cell goal);
  int32_t distance(grid::Cell from, grid::Cell goal) { return (*to(goal))[grid_.index(from)]; }
  std::size_t tables() const { return tables_.size(); }
  std::size_t computed() const { return computed_; }  // BFS runs so far (misses)
  const grid::Grid& grid() const { return grid_; }
  static std::size_t table_bytes(const grid::Grid& grid) {  // one table: a distance per cell
    return sizeof(int32_t) * static_cast<std::size_t>(grid.width()) *
           static_cast<std::size_t>(grid.height());
  }

 private:
  const grid::Grid& grid_;
  std::size_t max_tables_;
  std::list<uint32_t> lru_;  // goal indices, most recent first
  struct Entry {
    Table table;
    std::list<uint32_t>::iterator at;
  };
  std::unordered_map<uint32_t, Entry> tables_;
  std::size_t computed_ = 0;
};

}  // namespace smart::planning
