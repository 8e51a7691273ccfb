#include "smart/sim/shard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace smart::sim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

// Cuts at cell edges between the quantiles of the robots' starts along the longer axis; with
// fewer starts than shards, strips of equal width.
ShardMap::ShardMap(const grid::Grid& grid, const SimConfig& config, const agent::RobotModel& model,
                   uint32_t shards, const std::vector<agent::Pose2D>& starts) {
  along_x_ = grid.width() >= grid.height();
  const int cells = along_x_ ? grid.width() : grid.height();
  if (shards == 0 || static_cast<int>(shards) > cells) {
    throw std::invalid_argument("cannot split a map " + std::to_string(cells) +
                                " cells across into " + std::to_string(shards) +
                                " shards; use between 1 and " + std::to_string(cells));
  }
  const double cell = config.cell_m;
  hysteresis_m_ = cell / 2;
  margin_m_ =
      4 * model.radius_m + 2 * model.max_speed_mps * config.control_period_s + hysteresis_m_;
  std::vector<double> a;
  a.reserve(starts.size());
  for (const auto& p : starts) a.push_back(axis(p.x_m, p.y_m));
  std::sort(a.begin(), a.end());
  cuts_m_.assign(shards + 1, -kInf);
  cuts_m_.back() = kInf;
  for (uint32_t s = 1; s < shards; ++s) {
    double at = (static_cast<double>(s) * cells / shards - 0.5) * cell;  // equal widths
    if (a.size() >= shards) {
      const std::size_t k = a.size() * s / shards;
      at = (a[k - 1] + a[k]) / 2;
    }
    // Cell centres are at whole multiples of cell_m: edges at (c + 0.5) cell_m.
    at = (std::floor(at / cell) + 0.5) * cell;
    // NOLINTNEXTLINE(bugprone-narrowing-conversions): clang-tidy 14 misreads infinity
    cuts_m_[s] = std::max(at, s > 1 ? cuts_m_[s - 1] : -kInf);
  }
}

uint32_t ShardMap::region_of(double x_m, double y_m) const {
  const double a = axis(x_m, y_m);
  const auto it = std::upper_bound(cuts_m_.begin() + 1, cuts_m_.end() - 1, a);
  return static_cast<uint32_t>(it - cuts_m_.begin()) - 1;
}

uint32_t ShardMap::keeper(uint32_t current, double x_m, double y_m) const {
  const double a = axis(x_m, y_m);
  if (a >= cuts_m_[current] - hysteresis_m_ && a < cuts_m_[current + 1] + hysteresis_m_) {
    return current;
  }
  return region_of(x_m, y_m);
}

double ShardMap::distance_to_strip(uint32_t s, double a) const {
  if (a < cuts_m_[s]) return cuts_m_[s] - a;
  if (a >= cuts_m_[s + 1]) return a - cuts_m_[s + 1];
  return 0;
}

bool ShardMap::near(uint32_t s, double x_m, double y_m) const {
  return distance_to_strip(s, axis(x_m, y_m)) <= margin_m_;
}

FleetShard::FleetShard(Fleet& fleet, const ShardMap& map, uint32_t shard)
    : fleet_(fleet), map_(map), shard_(shard) {
  if (shard >= map.shards()) {
    throw std::invalid_argument("shard " + std::to_string(shard) + " of " +
                                std::to_string(map.shards()) + ": shards are numbered from 0");
  }
  World& world = fleet.world();
  for (uint32_t r = 0; r < fleet.robots(); ++r) {
    const auto m = world.motion(r);
    home_.push_back(map.region_of(m.x_m, m.y_m));
    if (home_.back() != shard) fleet.release(r, Presence::kAbsent);
  }
}

std::size_t FleetShard::simulated() const {
  std::size_t n = 0;
  for (uint32_t r = 0; r < fleet_.robots(); ++r) n += simulates(r) ? 1 : 0;
  return n;
}

std::vector<Ghost> FleetShard::ghosts_near_others() const {
  std::vector<Ghost> out;
  const World& world = fleet_.world();
  for (uint32_t r = 0; r < fleet_.robots(); ++r) {
    if (!simulates(r)) continue;
    const auto m = world.motion(r);
    for (uint32_t s = 0; s < map_.shards(); ++s) {
      if (s != shard_ && map_.near(s, m.x_m, m.y_m)) {
        out.push_back({r, m});
        break;
      }
    }
  }
  return out;
}

ShardOutbox FleetShard::initial_outbox() const { return {{}, ghosts_near_others()}; }

ShardOutbox FleetShard::after_step(const std::function<Reported(uint32_t)>& reported) {
  ShardOutbox out{{}, ghosts_near_others()};
  released_ghosts_.clear();
  for (uint32_t r = 0; r < fleet_.robots(); ++r) {
    if (!simulates(r)) continue;
    const auto m = fleet_.world().motion(r);
    const uint32_t to = map_.keeper(shard_, m.x_m, m.y_m);
    if (to == shard_) continue;
    const bool near_here = map_.near(shard_, m.x_m, m.y_m);
    auto [physics, agent] = fleet_.release(r, near_here ? Presence::kGhost : Presence::kAbsent);
    const auto [finished, executing] = reported(r);
    out.handovers.push_back({r, to, std::move(physics), std::move(agent), finished, executing});
    if (near_here) released_ghosts_.push_back({r, m});
  }
  return out;
}

std::vector<RobotHandover> FleetShard::before_step(const std::vector<const ShardOutbox*>& others) {
  World& world = fleet_.world();
  std::vector<RobotHandover> adopted;
  for (const ShardOutbox* o : others) {
    for (const auto& h : o->handovers) {
      if (h.to_shard == shard_ && h.robot < fleet_.robots()) adopted.push_back(h);
    }
  }
  std::sort(adopted.begin(), adopted.end(),
            [](const auto& a, const auto& b) { return a.robot < b.robot; });
  for (const auto& h : adopted) fleet_.adopt(h.robot, h.physics, h.agent);
  std::vector<uint8_t> ghost(fleet_.robots(), 0);
  auto show = [&](const Ghost& g) {
    if (g.robot >= fleet_.robots() || simulates(g.robot)) return;
    if (!map_.near(shard_, g.motion.x_m, g.motion.y_m)) return;
    world.set_ghost(g.robot, g.motion);
    ghost[g.robot] = 1;
  };
  for (const auto& g : released_ghosts_) show(g);
  for (const ShardOutbox* o : others) {
    for (const auto& g : o->ghosts) show(g);
  }
  for (uint32_t r = 0; r < fleet_.robots(); ++r) {
    if (!simulates(r) && !ghost[r]) world.set_presence(r, Presence::kAbsent);
  }
  return adopted;
}

}  // namespace smart::sim
