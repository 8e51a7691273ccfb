// Contract: PIBT's heuristic for maps where a distance table per goal cannot fit
// (goal_heuristic.hpp): each robot keeps one shortest path to its goal, found by A* (Hart, Nilsson,
// Raphael 1968) with the ALT landmark heuristic (Goldberg and Harrelson, "Computing the shortest
// path: A* search meets graph theory", SODA 2005: h(v) = max over landmarks L of |d(L, goal) - d(L,
// v)|, with Manhattan distance; admissible and consistent, so A*'s paths are shortest). Landmarks
// are chosen farthest-first from the largest free region; each is one BFS table, so the memory is
// `landmarks` tables plus the robots' paths, whatever the number of goals.
// Ranks: the next cell of the robot's path ranks (cells left - 1), its own cell (cells left),
// any other neighbour (cells left + 1), like the exact distances on a 4-connected grid except
// that another shortest way round is not known. A robot found on its path (at or ahead of where
// it was) keeps it; one pushed a cell off it heads back to the path's furthest cell next to it;
// one pushed further finds its way back by a BFS of at most kRepairDepth steps to the nearest
// cell of its path (a detour, not always shortest); otherwise, or for a new goal, A* runs again. At
// most `searches_per_window` A* runs per window (the first window of 10 000 robots on a large map
// would take half a minute): a robot still waiting for its path ranks cells by the landmark bound
// to its goal meanwhile, and gets its path in a later window, robots in index order. Deterministic
// (a count, not a clock); no I/O.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/planning/goal_heuristic.hpp"

namespace smart::planning {

class GuidePaths final : public GoalHeuristic {
 public:
  explicit GuidePaths(const grid::Grid& grid, int landmarks = 8,
                      std::size_t searches_per_window = 2000);

  bool aim(uint32_t robot, grid::Cell at, grid::Cell goal) override;
  int64_t rank(uint32_t robot, grid::Cell c) override;
  std::size_t memory_bytes() const override;
  std::string name() const override { return "guide paths"; }
  void new_window() override { searches_left_ = searches_per_window_; }

  // A shortest path from `from` to `to` (both included), empty when none: the A* behind aim().
  std::vector<grid::Cell> shortest_path(grid::Cell from, grid::Cell to);
  // The ALT lower bound on the distance between two free cells.
  int32_t lower_bound(grid::Cell a, grid::Cell b) const;
  std::size_t searches() const { return searches_; }
  std::size_t repairs() const { return repairs_; }
  std::size_t expanded() const { return expanded_; }

 private:
  struct Guide {
    uint32_t goal = UINT32_MAX;
    std::vector<uint32_t> cells;  // cell indices, [0] where the path was found
    uint32_t idx = 0;             // where the robot is on it
    bool off = false;             // a cell off the path, next to cells[idx]
    uint32_t at = 0;              // its cell when off
    bool waiting = false;         // no path yet (the window's searches ran out): cells = {at}
  };
  bool search(uint32_t from, uint32_t to, std::vector<uint32_t>& out);
  bool rejoin(Guide& p, uint32_t at) const;
  bool repair(Guide& p, uint32_t at);
  int32_t h(uint32_t v, uint32_t goal) const;
  bool adjacent(uint32_t a, uint32_t b) const;

  const grid::Grid& grid_;
  int32_t width_;
  std::size_t landmarks_;
  std::vector<int32_t> landmark_;  // cell-major: landmark_[cell * landmarks_ + k]
  std::vector<Guide> guides_;
  // A*'s workspace, valid where seen_ == stamp_ (never cleared between searches).
  std::vector<int32_t> g_;
  std::vector<uint32_t> parent_, seen_;
  uint32_t stamp_ = 0;
  struct Open {
    int32_t f, g;
    uint32_t cell;
  };
  std::vector<Open> heap_;
  std::size_t searches_ = 0, expanded_ = 0, repairs_ = 0;
  std::vector<uint32_t> queue_;
  std::size_t searches_per_window_, searches_left_;
};

}  // namespace smart::planning
