// Contract: the grid world of a MovingAI map and its coordinate conventions (one place).
// - Cell{x, y}: MovingAI x = column, y = row, row 0 at the top.
// - HalfCell{x2, y2}: a location in half cells (x2 = 2·x); odd in one coordinate = the midpoint
//   of an edge between two cells. Every move is split there (SMART §IV-B).
// - World frame: metres, right-handed, z up: x_w = x·cell_m, y_w = (height−1−y)·cell_m; yaw 0
//   along +x_w (east, increasing column), counter-clockwise positive; so north (+y_w) is
//   decreasing row.
#pragma once

#include <compare>
#include <cstdint>
#include <string>
#include <vector>

namespace smart::grid {

struct Cell {
  int32_t x = 0;  // column
  int32_t y = 0;  // row
  // NOLINTNEXTLINE(modernize-use-nullptr): clang-tidy 14 misreads a defaulted <=> (LLVM #46235)
  auto operator<=>(const Cell&) const = default;
};

struct HalfCell {
  int32_t x2 = 0;
  int32_t y2 = 0;
  // NOLINTNEXTLINE(modernize-use-nullptr): as Cell's (LLVM #46235)
  auto operator<=>(const HalfCell&) const = default;
  static HalfCell of(Cell c) { return {2 * c.x, 2 * c.y}; }
  static HalfCell midpoint(Cell a, Cell b) { return {a.x + b.x, a.y + b.y}; }
  bool is_cell() const { return x2 % 2 == 0 && y2 % 2 == 0; }
};

// Readers reject numbers beyond these instead of letting them wrap into valid-looking values.
inline constexpr int32_t kMaxGridSide = 100000;        // cells along one side of a map
inline constexpr int64_t kMaxGridCells = 100'000'000;  // cells of one map (100 MB of grid)
inline constexpr int64_t kMaxRobots = 10'000'000;      // robot ids in plan files

// Headings in the world frame; yaw = value · π/2.
enum class Heading : uint8_t { kEast = 0, kNorth = 1, kWest = 2, kSouth = 3 };

double yaw_rad(Heading h);
std::string to_string(Heading h);
// Heading of a 4-neighbour step from `a` to `b` (which must differ in exactly one coordinate).
Heading heading_of_step(Cell a, Cell b);
// Parses east|north|west|south (also e/n/w/s); throws std::invalid_argument otherwise.
Heading parse_heading(const std::string& s);

std::string to_string(Cell c);      // "(x=3,y=7)"
std::string to_string(HalfCell h);  // "(x=3,y=7)" or "(x=3.5,y=7)" for midpoints

struct WorldPoint {
  double x_m = 0;
  double y_m = 0;
};

class Grid {
 public:
  Grid() = default;
  Grid(int32_t width, int32_t height, std::vector<uint8_t> blocked, std::string name = {});

  int32_t width() const { return width_; }
  int32_t height() const { return height_; }
  const std::string& name() const { return name_; }
  bool inside(Cell c) const { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }
  bool blocked(Cell c) const { return blocked_[index(c)] != 0; }
  bool free(Cell c) const { return inside(c) && !blocked(c); }
  std::size_t index(Cell c) const {
    return static_cast<std::size_t>(c.y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(c.x);
  }
  std::size_t free_cells() const;
  // Cells of the map, free or not: the size of a per-cell table indexed by index().
  std::size_t cell_count() const {
    return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  }

  // Dense index of every half-cell location of the grid, for per-location tables.
  std::size_t half_cell_count() const {
    return static_cast<std::size_t>(2 * width_ - 1) * static_cast<std::size_t>(2 * height_ - 1);
  }
  std::size_t half_index(HalfCell h) const {
    return static_cast<std::size_t>(h.y2) * static_cast<std::size_t>(2 * width_ - 1) +
           static_cast<std::size_t>(h.x2);
  }

  WorldPoint to_world(HalfCell h, double cell_m) const {
    return {0.5 * h.x2 * cell_m, (height_ - 1 - 0.5 * h.y2) * cell_m};
  }

 private:
  int32_t width_ = 0;
  int32_t height_ = 0;
  std::vector<uint8_t> blocked_;
  std::string name_;
};

}  // namespace smart::grid
