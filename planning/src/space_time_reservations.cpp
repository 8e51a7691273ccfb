#include "smart/planning/space_time_reservations.hpp"

namespace smart::planning {

SpaceTimeReservations::SpaceTimeReservations(const grid::Grid& grid, std::size_t horizon)
    : grid_(grid),
      words_((horizon + 64) / 64),
      bits_(grid.cell_count() * words_, 0),
      parked_from_(grid.cell_count(), INT32_MAX) {}

void SpaceTimeReservations::set(const std::vector<grid::Cell>& p, bool add, bool park) {
  for (std::size_t t = 0; t < p.size(); ++t) {
    const auto cell = grid_.index(p[t]);
    auto& word = bits_[cell * words_ + t / 64];
    const uint64_t bit = uint64_t{1} << (t % 64);
    word = add ? word | bit : word & ~bit;
    if (t > 0 && p[t] != p[t - 1]) {
      const auto k = key(grid_.index(p[t - 1]), cell, static_cast<int32_t>(t - 1));
      add ? (void)moves_.insert(k) : (void)moves_.erase(k);
    }
  }
  if (park)
    parked_from_[grid_.index(p.back())] = add ? static_cast<int32_t>(p.size() - 1) : INT32_MAX;
}

int32_t SpaceTimeReservations::last_use(std::size_t cell) const {
  for (std::size_t w = words_; w-- > 0;) {
    const uint64_t word = bits_[cell * words_ + w];
    if (word != 0) return static_cast<int32_t>(w * 64 + 63 - std::size_t(__builtin_clzll(word)));
  }
  return -1;
}

}  // namespace smart::planning
