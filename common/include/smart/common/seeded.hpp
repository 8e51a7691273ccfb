// Contract: seeded draws that are a pure function of their coordinates (seed, and whatever the
// caller folds in: robot, stream, index), so that a lock-step run is the same whatever order
// robots or samples are handled in. Header-only, no state.
#pragma once

#include <cstdint>

namespace smart::common {

// SplitMix64's finaliser (Steele, Lea, Flood: "Fast splittable pseudorandom number generators",
// OOPSLA 2014): a well-mixed 64-bit hash.
constexpr uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A uniform draw in [0, 1) from a hash.
constexpr double unit_interval(uint64_t hash) {
  return static_cast<double>(hash >> 11) * 0x1.0p-53;
}

}  // namespace smart::common
