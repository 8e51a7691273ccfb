// Contract: PIBT's heuristic for maps where a distance table per goal cannot fit
// (goal_heuristic.hpp): each robot keeps one shortest path to its goal, found by A* (Hart,
// Nilsson, Raphael 1968) with the ALT landmark heuristic (Goldberg and Harrelson, "Computing the
// shortest path: A* search meets graph theory", SODA 2005: h(v) = max over landmarks L of
// |d(L, goal) - d(L, v)|, with Manhattan distance; admissible and consistent, so A*'s paths are
// shortest). Landmarks are chosen farthest-first from the largest free region; each is one BFS
// table of 16-bit distances (clamped at 65534, which keeps the bound admissible and consistent),
// so the memory is `landmarks` x 2 bytes a cell plus the robots' paths, whatever the number of
// goals. 32 landmarks take iron_harvest's A* from 26 000 expansions a search (8) to 6 700.
// Ranks: the next cell of the robot's path ranks (cells left - 1), its own cell (cells left),
// any other neighbour (cells left + 1), like the exact distances on a 4-connected grid except
// that another shortest way round is not known. A robot found on its path (near where it was)
// keeps it; one pushed a cell off it heads back to the path's furthest cell next to it; one
// pushed further finds its way back by a BFS of at most kRepairDepth steps to the nearest cell of
// its path (a detour, not always shortest); otherwise, or for a new goal, A* runs again.
// At most `searches_per_window` A* runs per window (the first window of 10 000 robots on a large
// map would take half a minute): a robot still waiting for its path ranks cells by the landmark
// bound to its goal meanwhile and gets its path in a later window, robots in index order. The
// searches a window starts with run on `threads` threads, each with its own workspace (a
// lock-step sim waits for the planner meanwhile); which robots search is decided in robot order
// first, so the paths are the same for any thread count. Deterministic (counts, not a clock); no
// I/O.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "smart/planning/goal_heuristic.hpp"

namespace smart::planning {

class GuidePaths final : public GoalHeuristic {
 public:
  // threads 0: std::thread::hardware_concurrency().
  explicit GuidePaths(const grid::Grid& grid, int landmarks = 32,
                      std::size_t searches_per_window = 2000, unsigned threads = 0);

  bool aim(uint32_t robot, grid::Cell at, grid::Cell goal) override;
  int64_t rank(uint32_t robot, grid::Cell c) override;
  std::size_t memory_bytes() const override;
  std::string name() const override { return "guide paths"; }
  void new_window(const std::vector<grid::Cell>& at, const std::vector<grid::Cell>& goal) override;

  // A shortest path from `from` to `to` (both included), empty when none: the A* behind aim().
  std::vector<grid::Cell> shortest_path(grid::Cell from, grid::Cell to);
  // The ALT lower bound on the distance between two free cells.
  int32_t lower_bound(grid::Cell a, grid::Cell b) const;
  std::size_t searches() const { return searches_; }
  std::size_t repairs() const { return repairs_; }
  std::size_t expanded() const;

 private:
  struct Guide {
    uint32_t goal = UINT32_MAX;
    std::vector<uint32_t> cells;  // cell indices, [0] where the path was found
    uint32_t idx = 0;             // where the robot is on it
    bool off = false;             // a cell off the path, next to cells[idx]
    uint32_t at = 0;              // its cell when off
    bool waiting = false;         // no path yet (the window's searches ran out): cells = {at}
  };
  struct Open {
    int32_t f, g;
    uint32_t cell;
  };
  // A*'s scratch memory, valid where seen == stamp (never cleared between searches).
  struct Workspace {
    std::vector<int32_t> g;
    std::vector<uint32_t> parent, seen;
    uint32_t stamp = 0;
    std::vector<Open> heap;
    std::vector<uint32_t> queue;
    std::vector<int32_t> depth;
    std::size_t expanded = 0;
    explicit Workspace(std::size_t cells) : g(cells, 0), parent(cells, 0), seen(cells, 0) {}
    uint32_t next_stamp();
  };
  bool search(Workspace& w, uint32_t from, uint32_t to, std::vector<uint32_t>& out) const;
  // The robot's path still serves (same goal, on it or repaired back to it).
  bool keeps(Guide& p, uint32_t at, uint32_t goal);
  bool rejoin(Guide& p, uint32_t at) const;
  bool repair(Guide& p, uint32_t at);
  // Without a search: heading nowhere (at == goal), waiting (no search left); false: search.
  bool settle(Guide& p, uint32_t at, uint32_t goal);
  void found(Guide& p, uint32_t at, uint32_t goal, bool path);
  int32_t h(uint32_t v, uint32_t goal) const;
  grid::Cell cell_of(uint32_t v) const;
  int free_neighbours(uint32_t c, uint32_t (&out)[4]) const;
  static std::pair<std::size_t, std::size_t> near(const Guide& p);
  bool adjacent(uint32_t a, uint32_t b) const;

  const grid::Grid& grid_;
  int32_t width_;
  std::size_t landmarks_;
  // Cell-major: landmark_[cell * landmarks_ + k]; kFar where landmark k does not reach the cell.
  std::vector<uint16_t> landmark_;
  std::vector<Guide> guides_;
  std::vector<Workspace> work_;  // one per thread; [0] also for repairs and later searches
  std::size_t searches_ = 0, repairs_ = 0;
  std::size_t searches_per_window_, searches_left_;
};

}  // namespace smart::planning
