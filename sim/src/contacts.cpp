// World's contacts: the per-sub-step contact search in the snapshot (spatial hash on map cells,
// walls as faces and corners, walls.hpp), contact episodes, and the forces on one robot.
#include <algorithm>
#include <cmath>

#include "world_impl.hpp"

namespace smart::sim {

namespace {
// Hertz contact with Hunt-Crossley damping (Simbody's HertzCircular law):
// f = 4/3 E sqrt(R) d^1.5 (1 + 1.5 c ḋ), never pulling.
double contact_force(double depth, double depth_rate, double E, double R, double c) {
  const double f = 4.0 / 3.0 * E * std::sqrt(R) * std::pow(depth, 1.5) * (1 + 1.5 * c * depth_rate);
  return std::max(0.0, f);
}
}  // namespace

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
  bin_robots();
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
  build_touch_lists();
  count_robot_contacts(now);
  stats.robot_wall_now = walls_now;
}

// Each present robot in its cell's list (head, next), the lists of the last snapshot cleared.
void World::Impl::bin_robots() {
  const auto W = grid.width(), H = grid.height();
  for (const auto t : touched) head[t] = kNoRobot;
  touched.clear();
  for (auto i = static_cast<uint32_t>(n); i-- > 0;) {
    if (presence[i] == Presence::kAbsent) continue;
    const auto c = cell_at(grid, cfg.cell_m, x[i], y[i]);
    if (c.x < 0 || c.y < 0 || c.x >= W || c.y >= H) continue;
    const auto ci = static_cast<std::size_t>(grid.index(c));
    next[i] = head[ci];
    head[ci] = i;
    touched.push_back(ci);
  }
}

// Per-robot overlap lists from the pairs, in the order found (deterministic).
void World::Impl::build_touch_lists() {
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
}

// Robot-robot contact episodes of the snapshot's pairs (a bounce within the debounce window is
// the same episode).
void World::Impl::count_robot_contacts(double now) {
  uint32_t counted_now = 0;
  for (const auto p : pairs_now) {
    // A pair with a ghost is counted by the shard that simulates its lower index (world.hpp).
    if (!simulated(static_cast<uint32_t>(p >> 32))) continue;
    ++counted_now;
    auto [it, fresh] = pair_last_contact.emplace(p, now);
    if (fresh || now - it->second > cfg.contact_debounce_s) ++stats.robot_robot_events;
    if (stats.first_pair_a < 0) {
      stats.first_pair_a = static_cast<int64_t>(p >> 32);
      stats.first_pair_b = static_cast<int64_t>(p & 0xffffffffu);
    }
    it->second = now;
  }
  stats.robot_robot_now = counted_now;
}

}  // namespace smart::sim
