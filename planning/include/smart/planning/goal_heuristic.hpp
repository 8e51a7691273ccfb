// Contract: how PIBT (pibt.hpp) ranks a robot's candidate cells toward its goal. Each step the
// planner aims every robot (its cell, its goal) and then asks the rank of its own cell and of its
// free neighbours: smaller is nearer the goal. Two kinds:
// - TableHeuristic: exact distances, one backward BFS table per goal cell shared by every robot
//   heading there (distance_cache.hpp): best for maps where the tables fit in memory.
// - GuidePaths (guide_paths.hpp): one shortest path per robot, for maps where a table per goal
//   cannot fit (LoRR's iron_harvest: 2.2 M free cells, 49 000 task cells).
// Deterministic: the same aims give the same ranks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/distance_cache.hpp"

namespace smart::planning {

enum class HeuristicKind { kAuto, kTables, kPaths };

// kAuto: tables when one per robot would fit in `budget_bytes` (a goal per robot at once), guide
// paths otherwise; the others as they say.
HeuristicKind choose_heuristic(HeuristicKind kind, const grid::Grid& grid, std::size_t robots,
                               std::size_t budget_bytes);

class GoalHeuristic {
 public:
  virtual ~GoalHeuristic() = default;
  // Robot `robot` stands on `at` and heads for `goal`; false when no path reaches the goal (as
  // far as the heuristic has looked: one that defers its search says true).
  virtual bool aim(uint32_t robot, grid::Cell at, grid::Cell goal) = 0;
  // `c` is the aimed robot's cell or a free neighbour of it: smaller ranks are nearer the goal.
  virtual int64_t rank(uint32_t robot, grid::Cell c) = 0;
  virtual std::size_t memory_bytes() const = 0;
  virtual std::string name() const = 0;
  // A window's planning begins: every robot's start and first goal (its start when it has none).
  // A heuristic may budget its work per window, or prepare it all at once here.
  virtual void new_window(const std::vector<grid::Cell>& /*at*/,
                          const std::vector<grid::Cell>& /*goal*/) {}
};

class TableHeuristic final : public GoalHeuristic {
 public:
  explicit TableHeuristic(DistanceCache& tables) : tables_(tables) {}
  bool aim(uint32_t robot, grid::Cell at, grid::Cell goal) override;
  int64_t rank(uint32_t robot, grid::Cell c) override;
  std::size_t memory_bytes() const override;
  std::string name() const override { return "distance tables"; }
  std::size_t tables() const { return tables_.tables(); }

 private:
  DistanceCache& tables_;
  std::vector<grid::Cell> goal_;  // per robot
  std::vector<uint8_t> holding_;  // per robot: aimed at the cell it stands on
  // Per robot, its goal's table, taken when it is aimed: rank() asked the cache again for each
  // robot it ranked (a hash lookup and the LRU's splice). A robot holds its table while it
  // heads there; the cache keeps a table per robot and a quarter more (window_planner.cpp), so a
  // table held past its eviction is rare and at most one a robot.
  std::vector<DistanceCache::Table> table_;
};

}  // namespace smart::planning
