#include "smart/planning/generators.hpp"

#include <algorithm>
#include <random>
#include <sstream>
#include <stdexcept>

namespace smart::planning {

namespace {

std::vector<int32_t> component_labels(const grid::Grid& g, int32_t* largest) {
  std::vector<int32_t> label(static_cast<std::size_t>(g.width()) * g.height(), -1);
  std::vector<std::size_t> sizes;
  std::vector<grid::Cell> stack;
  for (int32_t y = 0; y < g.height(); ++y) {
    for (int32_t x = 0; x < g.width(); ++x) {
      if (g.blocked({x, y}) || label[g.index({x, y})] >= 0) continue;
      const auto id = static_cast<int32_t>(sizes.size());
      sizes.push_back(0);
      stack.push_back({x, y});
      label[g.index({x, y})] = id;
      while (!stack.empty()) {
        const grid::Cell c = stack.back();
        stack.pop_back();
        ++sizes.back();
        for (const grid::Cell n : {grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                                   grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
          if (g.free(n) && label[g.index(n)] < 0) {
            label[g.index(n)] = id;
            stack.push_back(n);
          }
        }
      }
    }
  }
  *largest =
      sizes.empty()
          ? -1
          : static_cast<int32_t>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  return label;
}

}  // namespace

grid::Grid generate_warehouse(const WarehouseOptions& o) {
  if (o.shelf_rows < 1 || o.shelf_cols < 1 || o.shelf_length < 1 || o.shelf_height < 1 ||
      o.aisle < 1 || o.margin < 1) {
    throw std::invalid_argument("warehouse: every size must be at least 1");
  }
  const int32_t w = 2 + 2 * o.margin + o.shelf_cols * o.shelf_length + (o.shelf_cols - 1) * o.aisle;
  const int32_t h = 2 + o.aisle + o.shelf_rows * (o.shelf_height + o.aisle);
  std::vector<uint8_t> cells(static_cast<std::size_t>(w) * h, 0);
  auto set = [&](int32_t x, int32_t y) { cells[static_cast<std::size_t>(y) * w + x] = 1; };
  for (int32_t x = 0; x < w; ++x) set(x, 0), set(x, h - 1);
  for (int32_t y = 0; y < h; ++y) set(0, y), set(w - 1, y);
  for (int r = 0; r < o.shelf_rows; ++r) {
    const int32_t y0 = 1 + o.aisle + r * (o.shelf_height + o.aisle);
    for (int c = 0; c < o.shelf_cols; ++c) {
      const int32_t x0 = 1 + o.margin + c * (o.shelf_length + o.aisle);
      for (int32_t y = y0; y < y0 + o.shelf_height; ++y) {
        for (int32_t x = x0; x < x0 + o.shelf_length; ++x) set(x, y);
      }
    }
  }
  return grid::Grid(w, h, std::move(cells), "warehouse");
}

grid::Grid generate_random_map(int32_t width, int32_t height, double fraction, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution blocked(fraction);
  std::vector<uint8_t> cells(static_cast<std::size_t>(width) * height);
  for (auto& c : cells) c = blocked(rng) ? 1 : 0;
  grid::Grid g(width, height, cells, "random");
  int32_t largest = -1;
  const auto label = component_labels(g, &largest);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (label[i] != largest) cells[i] = 1;  // isolated pockets become obstacles
  }
  return grid::Grid(width, height, std::move(cells), "random");
}

grid::Grid generate_empty_map(int32_t width, int32_t height) {
  return grid::Grid(width, height,
                    std::vector<uint8_t>(static_cast<std::size_t>(width) * height, 0), "empty");
}

grid::Grid generate_maze(int32_t width, int32_t height, int corridor, uint64_t seed) {
  if (corridor < 1) throw std::invalid_argument("maze: corridor width must be at least 1");
  const int unit = corridor + 1;
  const int cw = std::max(1, (width + 1) / unit), ch = std::max(1, (height + 1) / unit);
  std::vector<uint8_t> cells(static_cast<std::size_t>(width) * height, 1);
  auto open = [&](int32_t x, int32_t y) {
    if (x >= 0 && y >= 0 && x < width && y < height)
      cells[static_cast<std::size_t>(y) * width + x] = 0;
  };
  auto carve_room = [&](int cx, int cy) {
    for (int dy = 0; dy < corridor; ++dy)
      for (int dx = 0; dx < corridor; ++dx) open(cx * unit + dx, cy * unit + dy);
  };
  std::mt19937_64 rng(seed);
  std::vector<uint8_t> seen(static_cast<std::size_t>(cw) * ch, 0);
  std::vector<std::pair<int, int>> stack{{0, 0}};
  seen[0] = 1;
  carve_room(0, 0);
  while (!stack.empty()) {
    const auto [cx, cy] = stack.back();
    std::vector<std::pair<int, int>> next;
    for (const auto& [dx, dy] :
         {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
      const int nx = cx + dx, ny = cy + dy;
      if (nx >= 0 && ny >= 0 && nx < cw && ny < ch &&
          !seen[static_cast<std::size_t>(ny) * cw + nx]) {
        next.emplace_back(nx, ny);
      }
    }
    if (next.empty()) {
      stack.pop_back();
      continue;
    }
    const auto [nx, ny] = next[rng() % next.size()];
    seen[static_cast<std::size_t>(ny) * cw + nx] = 1;
    carve_room(nx, ny);
    // Knock down the wall between the two rooms.
    for (int k = 0; k < corridor; ++k) {
      if (nx != cx) {
        open(std::max(cx, nx) * unit - 1, cy * unit + k);
      } else {
        open(cx * unit + k, std::max(cy, ny) * unit - 1);
      }
    }
    stack.emplace_back(nx, ny);
  }
  return grid::Grid(width, height, std::move(cells), "maze");
}

std::string to_movingai_map(const grid::Grid& g, char blocked_symbol) {
  std::ostringstream s;
  s << "type octile\nheight " << g.height() << "\nwidth " << g.width() << "\nmap\n";
  for (int32_t y = 0; y < g.height(); ++y) {
    for (int32_t x = 0; x < g.width(); ++x) s << (g.blocked({x, y}) ? blocked_symbol : '.');
    s << "\n";
  }
  return s.str();
}

std::vector<int32_t> bfs_distances(const grid::Grid& g, grid::Cell from) {
  std::vector<int32_t> d(static_cast<std::size_t>(g.width()) * g.height(), -1);
  if (!g.free(from)) return d;
  std::vector<grid::Cell> queue{from};
  d[g.index(from)] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const grid::Cell c = queue[head];
    for (const grid::Cell n : {grid::Cell{c.x + 1, c.y}, grid::Cell{c.x - 1, c.y},
                               grid::Cell{c.x, c.y + 1}, grid::Cell{c.x, c.y - 1}}) {
      if (g.free(n) && d[g.index(n)] < 0) {
        d[g.index(n)] = d[g.index(c)] + 1;
        queue.push_back(n);
      }
    }
  }
  return d;
}

std::vector<grid::Cell> largest_region_cells(const grid::Grid& g) {
  int32_t largest = -1;
  const auto label = component_labels(g, &largest);
  std::vector<grid::Cell> cells;
  for (int32_t y = 0; y < g.height(); ++y) {
    for (int32_t x = 0; x < g.width(); ++x) {
      if (!g.blocked({x, y}) && label[g.index({x, y})] == largest) cells.push_back({x, y});
    }
  }
  return cells;
}

grid::Scenario generate_scenario(const grid::Grid& g, std::size_t agents, uint64_t seed,
                                 const std::string& map_name) {
  const auto cells = largest_region_cells(g);
  if (cells.size() < agents) {
    throw std::invalid_argument("scenario: " + std::to_string(agents) +
                                " agents need distinct cells but the largest free region has " +
                                std::to_string(cells.size()));
  }
  std::mt19937_64 rng(seed);
  auto starts = cells, goals = cells;
  std::shuffle(starts.begin(), starts.end(), rng);
  std::shuffle(goals.begin(), goals.end(), rng);
  grid::Scenario s;
  s.source = "generated";
  s.map_name = map_name;
  s.map_width = g.width();
  s.map_height = g.height();
  for (std::size_t i = 0; i < agents; ++i) {
    s.agents.push_back({starts[i], goals[i], static_cast<int>(i) + 2});
  }
  return s;
}

std::string to_movingai_scen(const grid::Scenario& scen, const grid::Grid& g) {
  std::ostringstream s;
  s << "version 1\n";
  for (const auto& a : scen.agents) {
    const auto d = bfs_distances(g, a.start)[g.index(a.goal)];
    s << 0 << "\t" << scen.map_name << "\t" << g.width() << "\t" << g.height() << "\t" << a.start.x
      << "\t" << a.start.y << "\t" << a.goal.x << "\t" << a.goal.y << "\t" << d << "\n";
  }
  return s.str();
}

}  // namespace smart::planning
