#include "smart/sim/world.hpp"

#include <algorithm>
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

#include "simbody_shard.hpp"
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

// Everything the force elements read: per-robot commands and the sub-step snapshot.
struct World::Impl : detail::RobotForces {
  const monitor::Grid& grid;
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

  // Snapshot at the start of the current sub-step (world frame).
  std::vector<double> x, y, yaw, vx, vy, w;
  std::vector<uint32_t> nb_begin, nb;  // neighbours within contact range (CSR)

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

  struct Shard {
    std::unique_ptr<detail::SimbodyShard> body;
    bool asleep = false;
    const std::vector<uint32_t>& robots() const { return body->robots(); }
  };
  std::vector<std::unique_ptr<Shard>> shards;
  std::vector<uint32_t> shard_of;
  Workers workers;

  Impl(const monitor::Grid& g, const agent::RobotModel& m, const SimConfig& c, std::size_t robots)
      : grid(g), model(m), cfg(c), n(robots), workers(c.threads) {}

  double command(const std::vector<double>& from, const std::vector<double>& target, uint32_t i,
                 double t) const {
    const double max_change = ramp_rate * std::max(0.0, t - ramp_t0);
    return from[i] + std::clamp(target[i] - from[i], -max_change, max_change);
  }

  void take_snapshot();
  void find_neighbours_and_count_contacts();
  void build_shards(const std::vector<std::vector<uint32_t>>& members,
                    const std::vector<std::vector<std::array<double, 3>>>& start_q) {
    shards.clear();
    for (std::size_t s = 0; s < members.size(); ++s) {
      auto sh = std::make_unique<Shard>();
      sh->body = std::make_unique<detail::SimbodyShard>(
          *this, members[s], model.mass_kg, model.radius_m, start_q[s], cfg.physics_step_s);
      if (substep > 0) sh->body->restart_at(static_cast<double>(substep) * cfg.physics_step_s);
      for (const uint32_t i : members[s]) shard_of[i] = static_cast<uint32_t>(s);
      shards.push_back(std::move(sh));
    }
  }
  void robot_force(uint32_t robot, double time_s, const double* q, const double* u,
                   double* f) const override;
};

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
  // Walls (grid faces and convex corners).
  thread_local std::vector<WallContact> walls;
  walls.clear();
  wall_contacts(grid, cfg.cell_m, x, y, r, walls);
  for (const auto& wc : walls) {
    const double rate = -(vx_i * wc.nx + vy_i * wc.ny);
    const double f = contact_force(wc.depth_m, rate, E, r, c);
    fx += f * wc.nx;
    fy += f * wc.ny;
  }
  // Other robots, from the snapshot, in a fixed neighbour order.
  for (uint32_t a = nb_begin[i]; a < nb_begin[i + 1]; ++a) {
    const uint32_t j = nb[a];
    const double dx = x - this->x[j], dy = y - this->y[j];
    const double d = std::hypot(dx, dy);
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

void World::Impl::take_snapshot() {
  for (auto& sh : shards) {
    if (sh->asleep) continue;  // unchanged since it fell asleep
    const auto& ids = sh->robots();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const uint32_t i = ids[k];
      double q[3], u[3];
      sh->body->read(k, q, u);
      yaw[i] = q[0];
      x[i] = q[1];
      y[i] = q[2];
      w[i] = u[0];
      vx[i] = u[1];
      vy[i] = u[2];
    }
  }
}

void World::Impl::find_neighbours_and_count_contacts() {
  const double r = model.radius_m;
  const double now = static_cast<double>(substep) * cfg.physics_step_s;
  const double range = 2 * r + 0.05 * cfg.cell_m;
  const auto W = grid.width(), H = grid.height();
  auto cell_index = [&](uint32_t i) -> std::ptrdiff_t {
    const auto c = cell_at(grid, cfg.cell_m, x[i], y[i]);
    if (c.x < 0 || c.y < 0 || c.x >= W || c.y >= H) return -1;
    return static_cast<std::ptrdiff_t>(grid.index(c));
  };
  for (const auto t : touched) head[t] = kNoRobot;
  touched.clear();
  for (uint32_t i = static_cast<uint32_t>(n); i-- > 0;) {
    const auto ci = cell_index(i);
    if (ci < 0) continue;
    next[i] = head[static_cast<std::size_t>(ci)];
    head[static_cast<std::size_t>(ci)] = i;
    touched.push_back(static_cast<std::size_t>(ci));
  }
  nb.clear();
  pairs_now.clear();
  std::fill(in_contact.begin(), in_contact.end(), 0);
  uint32_t walls_now = 0;
  for (uint32_t i = 0; i < n; ++i) {
    nb_begin[i] = static_cast<uint32_t>(nb.size());
    const auto c = cell_at(grid, cfg.cell_m, x[i], y[i]);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const monitor::Cell cc{c.x + dc, c.y + dr};
        if (!grid.inside(cc)) continue;
        for (uint32_t j = head[grid.index(cc)]; j != kNoRobot; j = next[j]) {
          if (j == i) continue;
          const double d = std::hypot(x[i] - x[j], y[i] - y[j]);
          // Closest approach over every pair in neighbouring cells, in range or not.
          if (i < j) stats.min_gap_m = std::min(stats.min_gap_m, d - 2 * r);
          if (d >= range) continue;
          nb.push_back(j);
          if (i < j && d < 2 * r) pairs_now.push_back((uint64_t{i} << 32) | j);
          if (d < 2 * r) in_contact[i] = 1;
        }
      }
    }
    scratch.clear();
    wall_contacts(grid, cfg.cell_m, x[i], y[i], r, scratch);
    if (!scratch.empty()) {
      ++walls_now;
      in_contact[i] = 1;
      if (now - wall_last_contact[i] > cfg.contact_debounce_s) ++stats.robot_wall_events;
      wall_last_contact[i] = now;
    }
  }
  nb_begin[n] = static_cast<uint32_t>(nb.size());
  for (const auto p : pairs_now) {
    auto [it, fresh] = pair_last_contact.emplace(p, now);
    if (fresh || now - it->second > cfg.contact_debounce_s) ++stats.robot_robot_events;
    it->second = now;
  }
  stats.robot_robot_now = static_cast<uint32_t>(pairs_now.size());
  stats.robot_wall_now = walls_now;
}

World::World(const monitor::Grid& grid, const agent::RobotModel& model, const SimConfig& config,
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
  const std::size_t n = starts.size();
  I.target_l.assign(n, 0);
  I.target_r.assign(n, 0);
  I.ramp_from_l.assign(n, 0);
  I.ramp_from_r.assign(n, 0);
  I.ramp_rate = std::max(model.max_accel_mps2, model.max_decel_mps2);
  for (auto* v : {&I.x, &I.y, &I.yaw, &I.vx, &I.vy, &I.w}) v->assign(n, 0);
  I.nb_begin.assign(n + 1, 0);
  I.head.assign(static_cast<std::size_t>(grid.width()) * grid.height(), kNoRobot);
  I.next.assign(n, kNoRobot);
  I.wall_last_contact.assign(n, -1e300);
  I.in_contact.assign(n, 0);
  I.shard_of.assign(n, 0);
  I.is_external.assign(n, 0);
  I.external_pose.assign(starts.begin(), starts.end());

  const int wanted =
      config.shards > 0 ? config.shards : std::clamp(static_cast<int>((n + 62) / 125), 2, 8);
  const int S = std::max(1, std::min(wanted, static_cast<int>(std::max<std::size_t>(n, 1))));
  std::vector<std::vector<uint32_t>> members(static_cast<std::size_t>(S));
  std::vector<std::vector<std::array<double, 3>>> start_q(static_cast<std::size_t>(S));
  for (uint32_t i = 0; i < n; ++i) {
    const auto& p = starts[i];
    const auto cell = cell_at(grid, config.cell_m, p.x_m, p.y_m);
    if (!grid.free(cell)) {
      throw std::invalid_argument("robot " + std::to_string(i) + " starts at " +
                                  monitor::to_string(cell) +
                                  ", which is outside the map or blocked");
    }
    members[i % static_cast<uint32_t>(S)].push_back(i);
    start_q[i % static_cast<uint32_t>(S)].push_back({p.yaw_rad, p.x_m, p.y_m});
    I.x[i] = p.x_m;
    I.y[i] = p.y_m;
    I.yaw[i] = p.yaw_rad;
  }
  I.build_shards(members, start_q);
  I.take_snapshot();
  I.find_neighbours_and_count_contacts();
  for (auto& sh : I.shards) {
    sh->asleep = std::none_of(sh->robots().begin(), sh->robots().end(),
                              [&](uint32_t i) { return I.in_contact[i] != 0; });
  }
}

World::~World() = default;

void World::repartition(const std::vector<uint32_t>& order) {
  auto& I = *impl_;
  if (order.size() != I.n) throw std::invalid_argument("repartition: order must list every robot");
  for (uint32_t i = 0; i < I.n; ++i) {
    if (I.vx[i] != 0 || I.vy[i] != 0 || I.w[i] != 0 || I.target_l[i] != 0 || I.target_r[i] != 0 ||
        I.ramp_from_l[i] != 0 || I.ramp_from_r[i] != 0) {
      throw std::logic_error("repartition: robot " + std::to_string(i) + " is not at rest");
    }
  }
  const std::size_t S = I.shards.size();
  std::vector<std::vector<uint32_t>> members(S);
  std::vector<std::vector<std::array<double, 3>>> start_q(S);
  for (std::size_t k = 0; k < I.n; ++k) {
    const uint32_t i = order[k];
    const std::size_t s = k * S / I.n;
    members[s].push_back(i);
    start_q[s].push_back({I.yaw[i], I.x[i], I.y[i]});
  }
  I.build_shards(members, start_q);
  for (auto& sh : I.shards) sh->asleep = true;  // all at rest; commands wake them
}

std::size_t World::robots() const { return impl_->n; }
double World::time_s() const {
  return static_cast<double>(impl_->substep) * impl_->cfg.physics_step_s;
}
uint64_t World::steps() const { return impl_->control_steps; }
const ContactStats& World::contacts() const { return impl_->stats; }
const SimConfig& World::config() const { return impl_->cfg; }

std::size_t World::awake_shards() const {
  return static_cast<std::size_t>(std::count_if(impl_->shards.begin(), impl_->shards.end(),
                                                [](const auto& s) { return !s->asleep; }));
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
  // Shards with a commanded robot wake up.
  auto wake = [&](Impl::Shard& sh) {
    if (!sh.asleep) return;
    sh.body->restart_at(time_s());
    sh.asleep = false;
  };
  for (uint32_t i = 0; i < I.n; ++i) {
    if (I.is_external[i] || I.target_l[i] != 0 || I.target_r[i] != 0 || I.ramp_from_l[i] != 0 ||
        I.ramp_from_r[i] != 0) {
      wake(*I.shards[I.shard_of[i]]);
    }
  }
  for (int j = 0; j < I.substeps; ++j) {
    // Contacts wake the shards of both robots (a sleeping robot can be pushed).
    for (uint32_t i = 0; i < I.n; ++i) {
      if (I.in_contact[i]) wake(*I.shards[I.shard_of[i]]);
    }
    const double target = static_cast<double>(I.substep + 1) * h;
    I.workers.run([&](int k) {
      for (std::size_t s = static_cast<std::size_t>(k); s < I.shards.size();
           s += static_cast<std::size_t>(I.workers.size())) {
        auto& sh = *I.shards[s];
        if (sh.asleep) continue;
        sh.body->step_to(target);
      }
    });
    ++I.substep;
    I.take_snapshot();
    I.find_neighbours_and_count_contacts();
  }
  ++I.control_steps;
  // Forget pairs whose last contact is older than the debounce window.
  std::erase_if(I.pair_last_contact,
                [&](const auto& kv) { return time_s() - kv.second > I.cfg.contact_debounce_s; });
  // Robots at rest are snapped to exactly zero velocity; a shard of resting robots sleeps.
  const double t1 = time_s();
  for (auto& sh : I.shards) {
    if (sh->asleep) continue;
    bool all_rest = true;
    for (std::size_t k = 0; k < sh->robots().size(); ++k) {
      const uint32_t i = sh->robots()[k];
      const bool commanded = I.is_external[i] || I.target_l[i] != 0 || I.target_r[i] != 0 ||
                             I.command(I.ramp_from_l, I.target_l, i, t1) != 0 ||
                             I.command(I.ramp_from_r, I.target_r, i, t1) != 0;
      const bool slow =
          std::abs(I.vx[i]) < 1e-4 && std::abs(I.vy[i]) < 1e-4 && std::abs(I.w[i]) < 1e-3;
      if (!commanded && slow && !I.in_contact[i]) {
        if (I.vx[i] != 0 || I.vy[i] != 0 || I.w[i] != 0) {
          sh->body->zero_velocity(k);
          I.vx[i] = I.vy[i] = I.w[i] = 0;
        }
      } else {
        all_rest = false;
      }
    }
    if (all_rest) sh->asleep = true;
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
