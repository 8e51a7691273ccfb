#include "smart/planning/random_plan.hpp"

#include <algorithm>
#include <limits>
#include <random>
#include <stdexcept>

namespace smart::planning {

namespace {
constexpr uint32_t kEmpty = std::numeric_limits<uint32_t>::max();
constexpr grid::Cell kSteps[4] = {{1, 0}, {0, -1}, {-1, 0}, {0, 1}};
}  // namespace

grid::Grid generate_random_grid(int32_t width, int32_t height, double obstacle_fraction,
                                uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution blocked(obstacle_fraction);
  std::vector<uint8_t> cells(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (auto& c : cells) c = blocked(rng) ? 1 : 0;
  return grid::Grid(width, height, std::move(cells),
                    "random-" + std::to_string(width) + "x" + std::to_string(height));
}

namespace {

// One timestep at a time: every robot picks a move (or stays), then maybe one rotation cycle.
struct Walker {
  const grid::Grid& grid;
  const RandomPlanOptions& o;
  std::mt19937_64& rng;
  std::size_t n;
  std::vector<grid::Cell> pos, target;
  std::vector<uint32_t> now, next, order;
  std::vector<uint8_t> decided;
  std::bernoulli_distribution try_move, try_rotate;
  std::uniform_int_distribution<std::size_t> pick;
  std::size_t rotation_cycles = 0;

  Walker(const grid::Grid& g, const RandomPlanOptions& opt, std::mt19937_64& r,
         std::vector<grid::Cell> start)
      : grid(g),
        o(opt),
        rng(r),
        n(start.size()),
        pos(std::move(start)),
        target(n),
        now(static_cast<std::size_t>(g.width()) * g.height(), kEmpty),
        next(now.size(), kEmpty),
        order(n),
        decided(n),
        try_move(opt.move_probability),
        try_rotate(opt.rotation_probability),
        pick(0, n - 1) {
    for (std::size_t r = 0; r < n; ++r) {
      now[grid.index(pos[r])] = static_cast<uint32_t>(r);
      order[r] = static_cast<uint32_t>(r);
    }
  }

  void step() {
    std::shuffle(order.begin(), order.end(), rng);
    std::fill(decided.begin(), decided.end(), 0);
    for (const uint32_t r : order) choose(r);
    if (try_rotate(rng)) rotate_one();
    for (std::size_t r = 0; r < n; ++r) {
      now[grid.index(pos[r])] = kEmpty;
      next[grid.index(target[r])] = kEmpty;
    }
    for (std::size_t r = 0; r < n; ++r) {
      pos[r] = target[r];
      now[grid.index(pos[r])] = static_cast<uint32_t>(r);
    }
  }

  void choose(uint32_t r) {
    target[r] = pos[r];
    if (try_move(rng)) {
      int dirs[4] = {0, 1, 2, 3};
      std::shuffle(std::begin(dirs), std::end(dirs), rng);
      for (const int d : dirs) {
        const grid::Cell c{pos[r].x + kSteps[d].x, pos[r].y + kSteps[d].y};
        if (!grid.free(c) || next[grid.index(c)] != kEmpty) continue;
        const uint32_t occupant = now[grid.index(c)];
        // Follow only a robot that has committed to leave, and never swap with it.
        if (occupant != kEmpty &&
            (!decided[occupant] || target[occupant] == c || target[occupant] == pos[r])) {
          continue;
        }
        target[r] = c;
        break;
      }
    }
    decided[r] = 1;
    next[grid.index(target[r])] = r;
  }

  // Rotation cycle: four robots waiting on a 2x2 block each move one cell round it. Look for
  // such a block around the robots in random order and rotate the first one found.
  void rotate_one() {
    for (std::size_t i = 0; i < n; ++i) {
      const grid::Cell p = pos[order[(i + pick(rng)) % n]];
      for (const grid::Cell c0 :
           {p, grid::Cell{p.x - 1, p.y}, grid::Cell{p.x, p.y - 1}, grid::Cell{p.x - 1, p.y - 1}}) {
        const grid::Cell block[4] = {c0, {c0.x + 1, c0.y}, {c0.x + 1, c0.y + 1}, {c0.x, c0.y + 1}};
        uint32_t who[4];
        bool ok = true;
        for (int k = 0; k < 4 && ok; ++k) {
          ok = grid.free(block[k]) && (who[k] = now[grid.index(block[k])]) != kEmpty &&
               target[who[k]] == pos[who[k]];
        }
        if (!ok) continue;
        for (int k = 0; k < 4; ++k) target[who[k]] = block[(k + 1) % 4];
        for (int k = 0; k < 4; ++k) next[grid.index(block[(k + 1) % 4])] = who[k];
        ++rotation_cycles;
        return;
      }
    }
  }
};

}  // namespace

GeneratedInstance generate_random_plan(const grid::Grid& grid, const RandomPlanOptions& o) {
  std::mt19937_64 rng(o.seed);
  std::vector<grid::Cell> free;
  for (int32_t y = 0; y < grid.height(); ++y) {
    for (int32_t x = 0; x < grid.width(); ++x) {
      if (!grid.blocked({x, y})) free.push_back({x, y});
    }
  }
  if (free.size() < o.robots) {
    throw std::invalid_argument("generate_random_plan: " + std::to_string(o.robots) +
                                " robots do not fit on " + std::to_string(free.size()) +
                                " free cells");
  }
  std::shuffle(free.begin(), free.end(), rng);
  const std::size_t n = o.robots;
  Walker walk(grid, o, rng,
              std::vector<grid::Cell>(free.begin(), free.begin() + static_cast<std::ptrdiff_t>(n)));
  std::vector<std::vector<grid::Cell>> paths(n);
  for (std::size_t r = 0; r < n; ++r) paths[r].push_back(walk.pos[r]);
  for (std::size_t t = 1; t <= o.steps; ++t) {
    walk.step();
    for (std::size_t r = 0; r < n; ++r) paths[r].push_back(walk.pos[r]);
  }
  GeneratedInstance out;
  out.rotation_cycles = walk.rotation_cycles;
  out.plan.source = "<random seed " + std::to_string(o.seed) + ">";
  out.plan.format = grid::PlanFormat::kSmart;
  out.scen.source = out.plan.source;
  out.scen.map_name = grid.name();
  out.scen.map_width = grid.width();
  out.scen.map_height = grid.height();
  for (std::size_t r = 0; r < n; ++r) {
    auto& p = paths[r];
    while (p.size() > 1 && p[p.size() - 1] == p[p.size() - 2]) p.pop_back();
    grid::RobotPath rp{static_cast<int>(r), static_cast<int>(r) + 1, {}};
    for (std::size_t k = 0; k < p.size(); ++k) {
      rp.steps.push_back({p[k], static_cast<double>(k), static_cast<int>(r) + 1});
    }
    out.plan.paths.push_back(std::move(rp));
    out.scen.agents.push_back({p.front(), p.back(), static_cast<int>(r) + 2});
  }
  return out;
}

}  // namespace smart::planning
