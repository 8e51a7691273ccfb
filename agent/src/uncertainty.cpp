#include "smart/agent/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "smart/common/seeded.hpp"

namespace smart::agent {

namespace {
constexpr uint32_t kStall = 1, kSpeed = 2, kSlip = 3, kDelay = 4, kDelayLength = 5;
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

double delay_at(const Uncertainty& u, uint32_t robot, uint64_t tick) {
  if (!u.delays()) return 0;
  const double p =
      u.delay_rate_hz > 0 ? 1.0 - std::exp(-u.delay_rate_hz * kDelayTickS) : u.delay_probability;
  if (uniform01(u.seed, robot, kDelay, tick) >= p) return 0;
  const double lo = u.delay_min_s, span = std::max(0.0, u.delay_max_s - u.delay_min_s);
  const double d =
      u.delay_std_ratio > 0
          ? lo + u.delay_mean_ratio * span +
                u.delay_std_ratio * span * standard_normal(u.seed, robot, kDelayLength, tick)
          : lo + span * uniform01(u.seed, robot, kDelayLength, tick);
  return std::clamp(d, lo, lo + span);
}

std::vector<std::pair<int64_t, int64_t>> delay_intervals(const Uncertainty& u, uint32_t robot,
                                                         int64_t ticks) {
  std::vector<std::pair<int64_t, int64_t>> out;
  if (!u.delays()) return out;
  for (int64_t k = 0; k < ticks; ++k) {
    const double d = delay_at(u, robot, static_cast<uint64_t>(k));
    if (d <= 0) continue;
    // Free again at the first tick whose time reaches k x tick + d.
    const auto end =
        std::max<int64_t>(k + 1, k + static_cast<int64_t>(std::ceil(d / kDelayTickS - 1e-9)));
    out.emplace_back(k, end);
    k = end - 1;
  }
  return out;
}

nlohmann::json to_json(const Uncertainty& u) {
  nlohmann::json j = {{"stall_probability", u.stall_probability},
                      {"stall_s", u.stall_s},
                      {"speed_sigma", u.speed_sigma},
                      {"slip_sigma", u.slip_sigma},
                      {"seed", u.seed}};
  if (u.delays()) {
    j["delay_probability"] = u.delay_probability;
    j["delay_rate_hz"] = u.delay_rate_hz;
    j["delay_min_s"] = u.delay_min_s;
    j["delay_max_s"] = u.delay_max_s;
    j["delay_mean_ratio"] = u.delay_mean_ratio;
    j["delay_std_ratio"] = u.delay_std_ratio;
  }
  return j;
}

}  // namespace smart::agent
