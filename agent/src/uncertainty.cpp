#include "smart/agent/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "smart/common/seeded.hpp"

namespace smart::agent {

namespace {
constexpr uint32_t kStall = 1, kSpeed = 2, kSlip = 3;
}  // namespace

double uniform01(uint64_t seed, uint32_t robot, uint32_t stream, uint64_t index) {
  using common::mix64;
  return common::unit_interval(mix64(mix64(mix64(seed) ^ (uint64_t{robot} << 8 | stream)) ^ index));
}

double standard_normal(uint64_t seed, uint32_t robot, uint32_t stream, uint64_t index) {
  // Box-Muller from two uniforms of the same coordinates (index 2i and 2i+1).
  const double u1 = std::max(uniform01(seed, robot, stream, 2 * index), 1e-300);
  const double u2 = uniform01(seed, robot, stream, 2 * index + 1);
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
}

bool stalls_before(const Uncertainty& u, uint32_t robot, uint32_t seq) {
  return u.stall_probability > 0 && u.stall_s > 0 &&
         uniform01(u.seed, robot, kStall, seq) < u.stall_probability;
}

double speed_factor(const Uncertainty& u, uint32_t robot) {
  if (u.speed_sigma <= 0) return 1.0;
  return std::clamp(1.0 + u.speed_sigma * standard_normal(u.seed, robot, kSpeed, 0), 0.3, 1.0);
}

double slip_factor(const Uncertainty& u, uint32_t robot, uint64_t tick, int wheel) {
  if (u.slip_sigma <= 0) return 1.0;
  const uint64_t index = 2 * tick + static_cast<uint64_t>(wheel & 1);
  return std::clamp(1.0 + u.slip_sigma * standard_normal(u.seed, robot, kSlip, index), 0.5, 1.5);
}

nlohmann::json to_json(const Uncertainty& u) {
  return {{"stall_probability", u.stall_probability},
          {"stall_s", u.stall_s},
          {"speed_sigma", u.speed_sigma},
          {"slip_sigma", u.slip_sigma},
          {"seed", u.seed}};
}

}  // namespace smart::agent
