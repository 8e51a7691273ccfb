// World's side of sim shards (shard.hpp): robots that arrive from or leave for another shard at
// a period boundary, and the neighbours' robots near the border shown as ghosts.
#include <stdexcept>
#include <string>

#include "world_impl.hpp"

namespace smart::sim {

Presence World::presence(uint32_t robot) const { return impl_->presence.at(robot); }

void World::set_presence(uint32_t robot, Presence p) {
  auto& I = *impl_;
  if (I.presence.at(robot) == p) return;
  if (I.awake(robot)) I.sleep(robot);  // out of Simbody; its snapshot state stays
  if (p != Presence::kSimulated) {
    I.target_l[robot] = I.target_r[robot] = 0;
    I.ramp_from_l[robot] = I.ramp_from_r[robot] = 0;
  }
  I.presence[robot] = p;
  I.contacts_stale = true;
}

RobotPhysics World::export_robot(uint32_t i) const {
  const auto& I = *impl_;
  RobotPhysics p{motion(i),        I.target_l.at(i),       I.target_r[i], I.ramp_from_l[i],
                 I.ramp_from_r[i], I.wall_last_contact[i], I.awake(i),    {}};
  for (const auto& [pair, t] : I.pair_last_contact) {
    const auto a = static_cast<uint32_t>(pair >> 32), b = static_cast<uint32_t>(pair & 0xffffffffu);
    if (a == i || b == i) p.pair_last_contact_s.emplace_back(a == i ? b : a, t);
  }
  return p;
}

void World::import_robot(uint32_t i, const RobotPhysics& p) {
  auto& I = *impl_;
  if (i >= I.n) throw std::out_of_range("import_robot: no robot " + std::to_string(i));
  set_presence(i, Presence::kSimulated);
  const auto& m = p.motion;
  I.x[i] = m.x_m, I.y[i] = m.y_m, I.yaw[i] = m.yaw_rad;
  I.vx[i] = m.vx_mps, I.vy[i] = m.vy_mps, I.w[i] = m.w_radps;
  I.target_l[i] = p.target_l_mps, I.target_r[i] = p.target_r_mps;
  I.ramp_from_l[i] = p.ramp_from_l_mps, I.ramp_from_r[i] = p.ramp_from_r_mps;
  I.wall_last_contact[i] = p.wall_last_contact_s;
  for (const auto& [other, t] : p.pair_last_contact_s) {
    if (other >= I.n || other == i) continue;
    I.pair_last_contact[(uint64_t{std::min(i, other)} << 32) | std::max(i, other)] = t;
  }
  if (p.awake) I.wake(i);  // from the snapshot just set, as the exporting World had it
}

void World::set_ghost(uint32_t i, const RobotMotion& m) {
  auto& I = *impl_;
  set_presence(i, Presence::kGhost);
  I.any_ghosts = true;
  I.x.at(i) = m.x_m, I.y[i] = m.y_m, I.yaw[i] = m.yaw_rad;
  I.vx[i] = m.vx_mps, I.vy[i] = m.vy_mps, I.w[i] = m.w_radps;
  I.contacts_stale = true;
}

RobotMotion World::motion(uint32_t i) const {
  const auto& I = *impl_;
  return {I.x.at(i), I.y[i], I.yaw[i], I.vx[i], I.vy[i], I.w[i]};
}

// A ghost moves on at the velocity it was given: the neighbour's robot is nearer where it
// really is than if it were held at the period's start (one period's lag at most 0.1 s).
void World::Impl::move_ghosts(double h) {
  if (!any_ghosts) return;
  for (uint32_t i = 0; i < n; ++i) {
    if (presence[i] != Presence::kGhost) continue;
    x[i] += vx[i] * h;
    y[i] += vy[i] * h;
    yaw[i] += w[i] * h;
  }
}

}  // namespace smart::sim
