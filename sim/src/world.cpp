#include "smart/sim/world.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <barrier>
#include <cmath>
#include <cstring>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unordered_map>

#include "simbody_system.hpp"
#include "smart/sim/walls.hpp"

namespace smart::sim {

namespace {

constexpr double kGravity = 9.81;
constexpr uint32_t kNoRobot = 0xffffffffu;

// Runs body(k) for k = 0..n-1 in parallel, k = 0 on the calling thread; reusable threads.
class Workers {
 public:
  explicit Workers(int n) : n_(std::max(1, n)), start_(n_), done_(n_) {
    for (int k = 1; k < n_; ++k) {
      threads_.emplace_back([this, k] {
        for (;;) {
          start_.arrive_and_wait();
          if (stop_.load()) return;
          run_one(k);
          done_.arrive_and_wait();
        }
      });
    }
  }
  ~Workers() {
    stop_.store(true);
    if (n_ > 1) start_.arrive_and_wait();
    for (auto& t : threads_) t.join();
  }
  int size() const { return n_; }
  void run(const std::function<void(int)>& body) {
    body_ = &body;
    error_ = nullptr;
    if (n_ > 1) start_.arrive_and_wait();
    run_one(0);
    if (n_ > 1) done_.arrive_and_wait();
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void run_one(int k) {
    try {
      (*body_)(k);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }
  int n_;
  std::barrier<> start_, done_;
  std::vector<std::thread> threads_;
  std::atomic<bool> stop_{false};
  const std::function<void(int)>* body_ = nullptr;
  std::exception_ptr error_;
  std::mutex mutex_;
};

// Hertz contact with Hunt-Crossley damping (Simbody's HertzCircular law):
// f = 4/3 E sqrt(R) d^1.5 (1 + 1.5 c ḋ), never pulling.
double contact_force(double depth, double depth_rate, double E, double R, double c) {
  const double f = 4.0 / 3.0 * E * std::sqrt(R) * std::pow(depth, 1.5) * (1 + 1.5 * c * depth_rate);
  return std::max(0.0, f);
}

}  // namespace

// Everything the force elements read: per-robot commands, the sub-step snapshot and the
// contacts found in it; and the assignment of awake robots to Simbody body slots.
struct World::Impl : detail::RobotForces {
  const grid::Grid& grid;
  agent::RobotModel model;
  SimConfig cfg;
  std::size_t n;
  int substeps;
  uint64_t substep = 0;  // physics sub-steps done; time = substep · h
  uint64_t control_steps = 0;

  // Commands: the motor ramps from `ramp_from` (at time ramp_t0) towards `target`.
  std::vector<double> target_l, target_r, ramp_from_l, ramp_from_r;
  double ramp_t0 = 0;
  double ramp_rate = 0;  // m/s² per wheel

  // Snapshot at the start of the current sub-step (world frame). For a sleeping robot this is
  // its resting state.
  std::vector<double> x, y, yaw, vx, vy, w;
  // Each awake robot's state after the sub-step, written by the threads stepping the systems
  // while other threads' forces still read the snapshot; copied into it after the barrier.
  std::vector<std::array<double, 6>> stepped;
  // Contacts in the snapshot, per robot (CSR): the robots it overlaps and the walls it touches.
  // A robot's forces for the next sub-step are computed from exactly these.
  std::vector<uint32_t> touch_begin, touch;
  std::vector<uint32_t> wall_begin;
  std::vector<WallContact> wall;

  // Spatial hash on map cells.
  std::vector<uint32_t> head, next;
  std::vector<std::size_t> touched;

  std::vector<uint8_t> is_external;
  std::vector<agent::Pose2D> external_pose;
  ContactStats stats;
  std::vector<uint64_t> pairs_now;
  std::unordered_map<uint64_t, double> pair_last_contact;  // pair -> last time in contact
  std::vector<double> wall_last_contact;
  std::vector<uint8_t> in_contact;  // any contact at the last snapshot
  std::vector<WallContact> scratch;
  std::vector<uint32_t> fill_at;

  // Awake robots and their body slots.
  std::size_t capacity = 1;
  std::vector<std::unique_ptr<detail::SimbodySystem>> systems;
  static constexpr uint32_t kAsleep = 0xffffffffu;
  std::vector<uint32_t> system_of, slot_of;  // system_of[i] == kAsleep: robot i sleeps
  std::size_t awake_count = 0;
  std::vector<detail::SimbodySystem*> active;  // systems stepped in this sub-step
  Workers workers;

  Impl(const grid::Grid& g, const agent::RobotModel& m, const SimConfig& c, std::size_t robots)
      : grid(g), model(m), cfg(c), n(robots), workers(c.threads) {}

  double command(const std::vector<double>& from, const std::vector<double>& target, uint32_t i,
                 double t) const {
    const double max_change = ramp_rate * std::max(0.0, t - ramp_t0);
    return from[i] + std::clamp(target[i] - from[i], -max_change, max_change);
  }
  bool commanded(uint32_t i, double t) const {
    return is_external[i] || target_l[i] != 0 || target_r[i] != 0 ||
           command(ramp_from_l, target_l, i, t) != 0 || command(ramp_from_r, target_r, i, t) != 0;
  }
  bool awake(uint32_t i) const { return system_of[i] != kAsleep; }

  void wake(uint32_t i);
  void sleep(uint32_t i);
  void move(uint32_t i, std::size_t to);
  void pack();
  void find_contacts(bool everyone);
  void robot_force(uint32_t robot, double time_s, const double* q, const double* u,
                   double* f) const override;
};

// Into the fullest system that has room (fewer systems stepped), else the first empty one.
void World::Impl::wake(uint32_t i) {
  if (awake(i)) return;
  std::size_t best = systems.size();
  for (std::size_t s = 0; s < systems.size(); ++s) {
    const auto occ = systems[s]->occupied();
    if (occ == capacity) continue;
    if (best == systems.size() || (occ > systems[best]->occupied())) best = s;
  }
  auto& sys = *systems.at(best);
  const std::size_t k = sys.first_vacant();
  sys.place(k, i, {yaw[i], x[i], y[i]}, {w[i], vx[i], vy[i]});
  system_of[i] = static_cast<uint32_t>(best);
  slot_of[i] = static_cast<uint32_t>(k);
  ++awake_count;
}

void World::Impl::sleep(uint32_t i) {
  systems[system_of[i]]->vacate(slot_of[i]);
  system_of[i] = slot_of[i] = kAsleep;
  --awake_count;
}

// Moves an awake robot to a vacant slot of `to`, state copied bit for bit.
void World::Impl::move(uint32_t i, std::size_t to) {
  auto& from = *systems[system_of[i]];
  std::array<double, 3> q{}, u{};
  from.read(slot_of[i], q.data(), u.data());
  from.vacate(slot_of[i]);
  const std::size_t k = systems[to]->first_vacant();
  systems[to]->place(k, i, q, u);
  system_of[i] = static_cast<uint32_t>(to);
  slot_of[i] = static_cast<uint32_t>(k);
}

// Empties the least occupied systems into the others' free slots while more than one system
// beyond the minimum is in use (the one spare avoids moving robots back and forth).
void World::Impl::pack() {
  const std::size_t needed = (awake_count + capacity - 1) / capacity;
  for (;;) {
    std::size_t in_use = 0, donor = systems.size();
    for (std::size_t s = 0; s < systems.size(); ++s) {
      const auto occ = systems[s]->occupied();
      if (occ == 0) continue;
      ++in_use;
      if (donor == systems.size() || occ <= systems[donor]->occupied()) donor = s;
    }
    if (in_use <= needed + 1) return;
    auto& from = *systems[donor];
    for (std::size_t k = 0; k < from.capacity(); ++k) {
      const uint32_t i = from.robot(k);
      if (i == detail::kVacant) continue;
      std::size_t best = systems.size();
      for (std::size_t s = 0; s < systems.size(); ++s) {
        const auto occ = systems[s]->occupied();
        if (s == donor || occ == 0 || occ == capacity) continue;
        if (best == systems.size() || occ > systems[best]->occupied()) best = s;
      }
      move(i, best);
    }
  }
}

void World::Impl::robot_force(uint32_t i, double t, const double* q, const double* u,
                              double* out) const {
  const double mass = model.mass_kg, b = model.wheel_base_m, r = model.radius_m;
  const double tau = cfg.slip_time_s;
  const double wheel_limit = cfg.friction_mu * mass * kGravity / 2;
  const double E = cfg.contact_modulus_pa, c = cfg.contact_damping_spm;
  const double th = q[0], x = q[1], y = q[2];
  const double om = u[0], vx_i = u[1], vy_i = u[2];
  const double ct = std::cos(th), st = std::sin(th);
  if (is_external[i]) {
    // Critically damped spring (2 Hz) towards the reported pose; contacts still apply below.
    const double wn = 2 * M_PI * 2.0;
    const auto& p = external_pose[i];
    double fx = mass * (wn * wn * (p.x_m - x) - 2 * wn * vx_i);
    double fy = mass * (wn * wn * (p.y_m - y) - 2 * wn * vy_i);
    const double inertia = mass * model.radius_m * model.radius_m / 2;
    const double dth = std::remainder(p.yaw_rad - th, 2 * M_PI);
    out[0] += inertia * (wn * wn * dth - 2 * wn * om);
    out[1] += fx;
    out[2] += fy;
    return;
  }
  // Traction: each wheel pulls its ground speed towards the motor command (linear slip,
  // Coulomb-limited); lateral slip is resisted the same way.
  const double v_fwd = vx_i * ct + vy_i * st, v_lat = -vx_i * st + vy_i * ct;
  const double wl = v_fwd - om * b / 2, wr = v_fwd + om * b / 2;
  const double cl = command(ramp_from_l, target_l, i, t);
  const double cr = command(ramp_from_r, target_r, i, t);
  const double fl = std::clamp(mass / 2 * (cl - wl) / tau, -wheel_limit, wheel_limit);
  const double fr = std::clamp(mass / 2 * (cr - wr) / tau, -wheel_limit, wheel_limit);
  const double flat = std::clamp(-mass * v_lat / tau, -2 * wheel_limit, 2 * wheel_limit);
  double fx = (fl + fr) * ct - flat * st;
  double fy = (fl + fr) * st + flat * ct;
  // Walls (grid faces and convex corners) and other robots, as found in the snapshot, which is
  // this robot's state now (q, u).
  for (uint32_t a = wall_begin[i]; a < wall_begin[i + 1]; ++a) {
    const auto& wc = wall[a];
    const double rate = -(vx_i * wc.nx + vy_i * wc.ny);
    const double f = contact_force(wc.depth_m, rate, E, r, c);
    fx += f * wc.nx;
    fy += f * wc.ny;
  }
  for (uint32_t a = touch_begin[i]; a < touch_begin[i + 1]; ++a) {
    const uint32_t j = touch[a];
    const double dx = x - this->x[j], dy = y - this->y[j];
    const double d = std::sqrt(dx * dx + dy * dy);
    const double depth = 2 * r - d;
    if (depth <= 0 || d == 0) continue;
    const double nx = dx / d, ny = dy / d;
    const double rate = -((vx_i - vx[j]) * nx + (vy_i - vy[j]) * ny);
    const double f = contact_force(depth, rate, E, r / 2, c);
    fx += f * nx;
    fy += f * ny;
  }
  out[0] += (fr - fl) * b / 2;
  out[1] += fx;
  out[2] += fy;
}

// Contacts in the snapshot. Only awake robots are examined (`everyone`: all of them, for the
// start configuration): a pair of sleeping robots neither moved nor touches, and its gap was
// seen when the later of the two fell asleep. Sleeping robots touched by an awake one are
// marked in_contact and wake for the next sub-step.
void World::Impl::find_contacts(bool everyone) {
  const double r = model.radius_m;
  const double now = static_cast<double>(substep) * cfg.physics_step_s;
  const auto W = grid.width(), H = grid.height();
  for (const auto t : touched) head[t] = kNoRobot;
  touched.clear();
  for (uint32_t i = static_cast<uint32_t>(n); i-- > 0;) {
    const auto c = cell_at(grid, cfg.cell_m, x[i], y[i]);
    if (c.x < 0 || c.y < 0 || c.x >= W || c.y >= H) continue;
    const auto ci = static_cast<std::size_t>(grid.index(c));
    next[i] = head[ci];
    head[ci] = i;
    touched.push_back(ci);
  }
  pairs_now.clear();
  wall.clear();
  std::fill(in_contact.begin(), in_contact.end(), 0);
  uint32_t walls_now = 0;
  for (uint32_t i = 0; i < n; ++i) {
    wall_begin[i] = static_cast<uint32_t>(wall.size());
    const bool examined = everyone || awake(i);
    if (!examined) continue;
    const auto c = cell_at(grid, cfg.cell_m, x[i], y[i]);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const grid::Cell cc{c.x + dc, c.y + dr};
        if (!grid.inside(cc)) continue;
        for (uint32_t j = head[grid.index(cc)]; j != kNoRobot; j = next[j]) {
          // Each pair once: from its lower index if both are examined.
          if (j == i || ((everyone || awake(j)) && j < i)) continue;
          const double dx = x[i] - x[j], dy = y[i] - y[j];
          const double d = std::sqrt(dx * dx + dy * dy);
          // Closest approach over every pair in neighbouring cells.
          stats.min_gap_m = std::min(stats.min_gap_m, d - 2 * r);
          if (d < 2 * r) {
            pairs_now.push_back((uint64_t{std::min(i, j)} << 32) | std::max(i, j));
            in_contact[i] = in_contact[j] = 1;
          }
        }
      }
    }
    scratch.clear();
    wall_contacts(grid, cfg.cell_m, x[i], y[i], r, scratch);
    if (!scratch.empty()) {
      wall.insert(wall.end(), scratch.begin(), scratch.end());
      ++walls_now;
      in_contact[i] = 1;
      if (now - wall_last_contact[i] > cfg.contact_debounce_s) ++stats.robot_wall_events;
      wall_last_contact[i] = now;
    }
  }
  wall_begin[n] = static_cast<uint32_t>(wall.size());
  // Per-robot overlap lists from the pairs, in the order found (deterministic).
  std::fill(touch_begin.begin(), touch_begin.end(), 0);
  for (const auto p : pairs_now) {
    ++touch_begin[(p >> 32) + 1];
    ++touch_begin[(p & 0xffffffffu) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) touch_begin[i + 1] += touch_begin[i];
  touch.resize(touch_begin[n]);
  fill_at.assign(touch_begin.begin(), touch_begin.end() - 1);
  for (const auto p : pairs_now) {
    const auto a = static_cast<uint32_t>(p >> 32), b = static_cast<uint32_t>(p & 0xffffffffu);
    touch[fill_at[a]++] = b;
    touch[fill_at[b]++] = a;
  }
  for (const auto p : pairs_now) {
    auto [it, fresh] = pair_last_contact.emplace(p, now);
    if (fresh || now - it->second > cfg.contact_debounce_s) ++stats.robot_robot_events;
    it->second = now;
  }
  stats.robot_robot_now = static_cast<uint32_t>(pairs_now.size());
  stats.robot_wall_now = walls_now;
}

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
  I.external_pose.assign(starts.begin(), starts.end());
  for (uint32_t i = 0; i < n; ++i) {
    const auto& p = starts[i];
    const auto cell = cell_at(grid, config.cell_m, p.x_m, p.y_m);
    if (!grid.free(cell)) {
      throw std::invalid_argument("robot " + std::to_string(i) + " starts at " +
                                  grid::to_string(cell) +
                                  ", which is outside the map or blocked");
    }
    I.x[i] = p.x_m;
    I.y[i] = p.y_m;
    I.yaw[i] = p.yaw_rad;
  }
  // Automatic capacity: 32 bodies (per-body cost within 20 % of a single large system, and
  // little left empty), fewer for small fleets so that both threads get work when all move.
  const std::size_t threads = static_cast<std::size_t>(I.workers.size());
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
  for (uint32_t i = 0; i < I.n; ++i) {
    if (I.commanded(i, t0)) I.wake(i);
  }
  for (int j = 0; j < I.substeps; ++j) {
    // Contacts wake both robots (a sleeping robot can be pushed).
    for (uint32_t i = 0; i < I.n; ++i) {
      if (I.in_contact[i]) I.wake(i);
    }
    I.active.clear();
    for (auto& s : I.systems) {
      if (s->occupied() > 0) I.active.push_back(s.get());
    }
    const double t = static_cast<double>(I.substep) * h;
    I.workers.run([&](int k) {
      for (std::size_t a = static_cast<std::size_t>(k); a < I.active.size();
           a += static_cast<std::size_t>(I.workers.size())) {
        auto& sys = *I.active[a];
        sys.step(t, h);
        for (std::size_t slot = 0; slot < sys.capacity(); ++slot) {
          const uint32_t i = sys.robot(slot);
          if (i == detail::kVacant) continue;
          auto& st = I.stepped[i];
          sys.read(slot, st.data(), st.data() + 3);
        }
      }
    });
    for (uint32_t i = 0; i < I.n; ++i) {
      if (!I.awake(i)) continue;
      const auto& st = I.stepped[i];
      I.yaw[i] = st[0];
      I.x[i] = st[1];
      I.y[i] = st[2];
      I.w[i] = st[3];
      I.vx[i] = st[4];
      I.vy[i] = st[5];
    }
    ++I.substep;
    I.find_contacts(false);
  }
  ++I.control_steps;
  // Forget pairs whose last contact is older than the debounce window.
  std::erase_if(I.pair_last_contact,
                [&](const auto& kv) { return time_s() - kv.second > I.cfg.contact_debounce_s; });
  // Robots at rest are snapped to exactly zero velocity and sleep.
  const double t1 = time_s();
  for (uint32_t i = 0; i < I.n; ++i) {
    if (!I.awake(i) || I.commanded(i, t1) || I.in_contact[i]) continue;
    if (std::abs(I.vx[i]) < 1e-4 && std::abs(I.vy[i]) < 1e-4 && std::abs(I.w[i]) < 1e-3) {
      I.vx[i] = I.vy[i] = I.w[i] = 0;
      I.sleep(i);
    }
  }
  I.pack();
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
