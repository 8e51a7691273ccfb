// World's awake robots in Simbody body slots: robots at rest sleep outside Simbody and wake into
// a slot when commanded or touched; after every period the awake robots are packed into as few
// systems as possible (docs/performance.md, "Simulator").
#include <algorithm>

#include "world_impl.hpp"

namespace smart::sim {

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

}  // namespace smart::sim
