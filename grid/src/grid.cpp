#include "smart/grid/grid.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>

namespace smart::grid {

double yaw_rad(Heading h) { return static_cast<int>(h) * std::numbers::pi / 2.0; }

std::string to_string(Heading h) {
  switch (h) {
    case Heading::kEast:
      return "east";
    case Heading::kNorth:
      return "north";
    case Heading::kWest:
      return "west";
    case Heading::kSouth:
      return "south";
  }
  return "east";
}

Heading heading_of_step(Cell a, Cell b) {
  if (b.x > a.x) return Heading::kEast;
  if (b.x < a.x) return Heading::kWest;
  if (b.y < a.y) return Heading::kNorth;  // row 0 is the top: decreasing row is north
  return Heading::kSouth;
}

Heading parse_heading(const std::string& s) {
  if (s == "east" || s == "e") return Heading::kEast;
  if (s == "north" || s == "n") return Heading::kNorth;
  if (s == "west" || s == "w") return Heading::kWest;
  if (s == "south" || s == "s") return Heading::kSouth;
  throw std::invalid_argument("unknown heading '" + s + "'; use east, north, west or south");
}

std::string to_string(Cell c) {
  return "(x=" + std::to_string(c.x) + ",y=" + std::to_string(c.y) + ")";
}

std::string to_string(HalfCell h) {
  auto half = [](int32_t v) {
    return v % 2 == 0 ? std::to_string(v / 2) : std::to_string(v / 2) + ".5";
  };
  return "(x=" + half(h.x2) + ",y=" + half(h.y2) + ")";
}

Grid::Grid(int32_t width, int32_t height, std::vector<uint8_t> blocked, std::string name)
    : width_(width), height_(height), blocked_(std::move(blocked)), name_(std::move(name)) {
  if (width <= 0 || height <= 0 ||
      blocked_.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("Grid: size does not match width x height");
  }
}

std::size_t Grid::free_cells() const {
  return static_cast<std::size_t>(std::count(blocked_.begin(), blocked_.end(), uint8_t{0}));
}

}  // namespace smart::grid
