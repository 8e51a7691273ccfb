// Contract: who is where when, for the space-time A* of the LNS planners (window_lns.hpp,
// plan_lns.hpp): a bit per cell and timestep up to a horizon (8 bytes a cell for up to 63
// steps), where a robot parks for good from its arrival (plans only), and the moves as (from,
// to, t) keys, read only where the bits allow a swap (hash sets per (cell, t) cost twice as much,
// docs/performance.md "Window LNS"). Paths are per timestep from t = 0 and must not collide
// with each other (taking one out clears its bits). Pure; no I/O.
#pragma once

#include <climits>
#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::planning {

class SpaceTimeReservations {
 public:
  // A move's key packs two cells in 24 bits each and a timestep in 16.
  static constexpr std::size_t kMaxCells = std::size_t{1} << 24;  // maps below this
  static constexpr std::size_t kMaxHorizon = 65535;               // horizons below this

  // Maps below kMaxCells and horizons below kMaxHorizon (the callers check, naming themselves).
  SpaceTimeReservations(const grid::Grid& grid, std::size_t horizon);

  // Adds (or takes out) a path; `park`: its robot stays on its last cell for good after.
  void set(const std::vector<grid::Cell>& path, bool add, bool park = false);
  bool taken(std::size_t cell, int32_t t) const {
    if (parked_from_[cell] <= t) return true;
    const auto w = static_cast<std::size_t>(t) / 64;
    return w < words_ && (bits_[cell * words_ + w] >> (t % 64) & 1) != 0;
  }
  // Whether a robot moving from -> to during [t, t + 1] swaps with one coming the other way.
  bool swaps(std::size_t from, std::size_t to, int32_t t) const {
    return from != to && taken(to, t) && taken(from, t + 1) && moves_.count(key(to, from, t)) != 0;
  }
  // The last timestep a path is on `cell` (parking aside); -1: none.
  int32_t last_use(std::size_t cell) const;

 private:
  static uint64_t key(std::size_t from, std::size_t to, int32_t t) {
    return (uint64_t(from) << 40) | (uint64_t(to) << 16) | uint64_t(uint16_t(t));
  }
  const grid::Grid& grid_;
  std::size_t words_;
  std::vector<uint64_t> bits_;
  std::vector<int32_t> parked_from_;
  std::unordered_set<uint64_t> moves_;
};

}  // namespace smart::planning
