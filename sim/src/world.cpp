#include "smart/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "world_impl.hpp"

namespace smart::sim {

World::World(const grid::Grid& grid, const agent::RobotModel& model, const SimConfig& config,
             const std::vector<agent::Pose2D>& starts)
    : impl_(std::make_unique<Impl>(grid, model, config, starts.size())) {
  auto& I = *impl_;
  if (model.radius_m > config.cell_m / 2) {
    throw std::invalid_argument("robot '" + model.name + "' has radius " +
                                std::to_string(model.radius_m) + " m, more than half the " +
                                std::to_string(config.cell_m) +
                                " m cell: robots could not pass each other at edge midpoints; "
                                "use a larger cell size");
  }
  const double ratio = config.control_period_s / config.physics_step_s;
  I.substeps = static_cast<int>(std::lround(ratio));
  if (I.substeps < 1 || std::abs(ratio - I.substeps) > 1e-9) {
    throw std::invalid_argument("control period must be a whole multiple of the physics step");
  }
  if (config.system_capacity < 0) {
    throw std::invalid_argument("system_capacity must be >= 0 (0 = automatic)");
  }
  const std::size_t n = starts.size();
  I.target_l.assign(n, 0);
  I.target_r.assign(n, 0);
  I.ramp_from_l.assign(n, 0);
  I.ramp_from_r.assign(n, 0);
  I.ramp_rate = std::max(model.max_accel_mps2, model.max_decel_mps2);
  for (auto* v : {&I.x, &I.y, &I.yaw, &I.vx, &I.vy, &I.w}) v->assign(n, 0);
  I.stepped.assign(n, {});
  I.touch_begin.assign(n + 1, 0);
  I.wall_begin.assign(n + 1, 0);
  I.head.assign(static_cast<std::size_t>(grid.width()) * grid.height(), kNoRobot);
  I.next.assign(n, kNoRobot);
  I.wall_last_contact.assign(n, -1e300);
  I.in_contact.assign(n, 0);
  I.system_of.assign(n, Impl::kAsleep);
  I.slot_of.assign(n, Impl::kAsleep);
  I.is_external.assign(n, 0);
  I.presence.assign(n, Presence::kSimulated);
  I.external_pose.assign(starts.begin(), starts.end());
  for (uint32_t i = 0; i < n; ++i) {
    const auto& p = starts[i];
    const auto cell = cell_at(grid, config.cell_m, p.x_m, p.y_m);
    if (!grid.free(cell)) {
      throw std::invalid_argument("robot " + std::to_string(i) + " starts at " +
                                  grid::to_string(cell) + ", which is outside the map or blocked");
    }
    I.x[i] = p.x_m;
    I.y[i] = p.y_m;
    I.yaw[i] = p.yaw_rad;
  }
  // Automatic capacity: 32 bodies (per-body cost within 20 % of a single large system, and
  // little left empty), fewer for small fleets so that both threads get work when all move.
  const auto threads = static_cast<std::size_t>(I.workers.size());
  I.capacity = config.system_capacity > 0
                   ? static_cast<std::size_t>(config.system_capacity)
                   : std::clamp<std::size_t>((n + threads - 1) / threads, 1, 32);
  // Enough systems for every robot awake at once (e.g. all pushed in a pile-up).
  const std::size_t count = std::max<std::size_t>(1, (n + I.capacity - 1) / I.capacity);
  for (std::size_t s = 0; s < count; ++s) {
    I.systems.push_back(
        std::make_unique<detail::SimbodySystem>(I, I.capacity, model.mass_kg, model.radius_m));
  }
  I.find_contacts(true);
}

World::~World() = default;

int sim_threads(int requested, std::size_t robots) {
  if (requested > 0) return requested;
  return static_cast<int>(std::clamp<std::size_t>(robots / kMinRobotsPerThread, 1, 2));
}

std::size_t World::robots() const { return impl_->n; }
double World::time_s() const {
  return static_cast<double>(impl_->substep) * impl_->cfg.physics_step_s;
}
uint64_t World::steps() const { return impl_->control_steps; }
const ContactStats& World::contacts() const { return impl_->stats; }
const SimConfig& World::config() const { return impl_->cfg; }
bool World::awake(uint32_t robot) const { return impl_->awake(robot); }
std::size_t World::awake_robots() const { return impl_->awake_count; }
std::size_t World::system_capacity() const { return impl_->capacity; }
int World::threads() const { return impl_->workers.size(); }

std::size_t World::active_systems() const {
  return static_cast<std::size_t>(std::count_if(impl_->systems.begin(), impl_->systems.end(),
                                                [](const auto& s) { return s->occupied() > 0; }));
}

void World::set_external(uint32_t robot, bool external) {
  impl_->is_external.at(robot) = external ? 1 : 0;
}
void World::set_external_pose(uint32_t robot, const agent::Pose2D& pose) {
  impl_->external_pose.at(robot) = pose;
}
bool World::external(uint32_t robot) const { return impl_->is_external.at(robot) != 0; }

void World::set_wheel_targets(uint32_t robot, agent::WheelSpeeds t) {
  auto& I = *impl_;
  I.target_l.at(robot) = t.left_mps;
  I.target_r.at(robot) = t.right_mps;
}

agent::WheelSpeeds World::wheel_speeds(uint32_t robot) const {
  const auto& I = *impl_;
  const double t = time_s();
  return {I.command(I.ramp_from_l, I.target_l, robot, t),
          I.command(I.ramp_from_r, I.target_r, robot, t)};
}

agent::PoseSample World::pose(uint32_t i) const {
  const auto& I = *impl_;
  const double ct = std::cos(I.yaw[i]), st = std::sin(I.yaw[i]);
  return {{I.x[i], I.y[i], I.yaw[i]}, I.vx[i] * ct + I.vy[i] * st, I.w[i], time_s(), true};
}

void World::step() {
  auto& I = *impl_;
  const double h = I.cfg.physics_step_s;
  const double t0 = time_s();
  // The ramp restarts from where each motor is now towards the new target.
  for (uint32_t i = 0; i < I.n; ++i) {
    I.ramp_from_l[i] = I.command(I.ramp_from_l, I.target_l, i, t0);
    I.ramp_from_r[i] = I.command(I.ramp_from_r, I.target_r, i, t0);
  }
  I.ramp_t0 = t0;
  // Robots arrived, left or moved as ghosts at this boundary: their contacts are found anew.
  if (I.contacts_stale) I.find_contacts(false);
  I.contacts_stale = false;
  for (uint32_t i = 0; i < I.n; ++i) {
    if (I.simulated(i) && I.commanded(i, t0)) I.wake(i);
  }
  for (int j = 0; j < I.substeps; ++j) I.substep_once(h);
  ++I.control_steps;
  // Forget pairs whose last contact is older than the debounce window.
  std::erase_if(I.pair_last_contact,
                [&](const auto& kv) { return time_s() - kv.second > I.cfg.contact_debounce_s; });
  I.settle(time_s());
  I.pack();
}

// One physics sub-step: every active system in parallel against the snapshot, then the new
// states become the snapshot and its contacts are found.
void World::Impl::substep_once(double h) {
  // Contacts wake both robots (a sleeping robot can be pushed).
  for (uint32_t i = 0; i < n; ++i) {
    if (in_contact[i] && simulated(i)) wake(i);
  }
  active.clear();
  for (auto& s : systems) {
    if (s->occupied() > 0) active.push_back(s.get());
  }
  const double t = static_cast<double>(substep) * h;
  workers.run([&](int k) {
    for (auto a = static_cast<std::size_t>(k); a < active.size();
         a += static_cast<std::size_t>(workers.size())) {
      auto& sys = *active[a];
      sys.step(t, h);
      for (std::size_t slot = 0; slot < sys.capacity(); ++slot) {
        const uint32_t i = sys.robot(slot);
        if (i == detail::kVacant) continue;
        auto& st = stepped[i];
        sys.read(slot, st.data(), st.data() + 3);
      }
    }
  });
  for (uint32_t i = 0; i < n; ++i) {
    if (!awake(i)) continue;
    const auto& st = stepped[i];
    yaw[i] = st[0];
    x[i] = st[1];
    y[i] = st[2];
    w[i] = st[3];
    vx[i] = st[4];
    vy[i] = st[5];
  }
  move_ghosts(h);
  ++substep;
  find_contacts(false);
}

// Robots at rest are snapped to exactly zero velocity and sleep.
void World::Impl::settle(double t) {
  for (uint32_t i = 0; i < n; ++i) {
    if (!awake(i) || commanded(i, t) || in_contact[i]) continue;
    if (std::abs(vx[i]) < 1e-4 && std::abs(vy[i]) < 1e-4 && std::abs(w[i]) < 1e-3) {
      vx[i] = vy[i] = w[i] = 0;
      sleep(i);
    }
  }
}

uint64_t World::state_hash() const {
  const auto& I = *impl_;
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int b = 0; b < 8; ++b) {
      h ^= (bits >> (8 * b)) & 0xff;
      h *= 1099511628211ull;
    }
  };
  for (std::size_t i = 0; i < I.n; ++i) {
    for (const auto* v : {&I.x, &I.y, &I.yaw, &I.vx, &I.vy, &I.w}) mix((*v)[i]);
  }
  return h;
}

}  // namespace smart::sim
