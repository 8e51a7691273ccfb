// Contract: execution uncertainty (issue 13; SMART §I: "execution imperfections and temporal
// uncertainty"), seeded and pure: every draw is a hash of (seed, robot, what, index), so a run
// is the same for the same seed whatever order robots are stepped in or which process hosts
// them, and changes with the seed.
// - stall_probability / stall_s: when a robot is about to start an action from rest (a rotation,
//   or a move that does not continue a run of moves), with this probability it first stands
//   still for stall_s (a blocked sensor, a human in the aisle).
// - speed_sigma: each robot's top speed is the model's times a factor drawn once per robot from
//   N(1, speed_sigma), clipped to [0.3, 1] (robots are never faster than their limits).
// - slip_sigma: in the sim, each wheel's commanded speed is scaled every control period by
//   1 + N(0, slip_sigma), clipped to [0.5, 1.5] (wheel slip, uneven floor).
// - delays (League of Robot Runners 2026 delayConfig, Start-Kit v3.1): at every 0.1 s tick a
//   robot not delayed starts a delay event with probability delay_probability (Bernoulli), or
//   with probability 1 - exp(-delay_rate_hz x 0.1 s) (Poisson events); it then stops where it is
//   (braking within its limits, between cells if it was moving) for a duration drawn from
//   [delay_min_s, delay_max_s]: uniform, or, with delay_std_ratio > 0, Gaussian with mean
//   min + delay_mean_ratio x (max - min) and standard deviation delay_std_ratio x (max - min),
//   clipped to the range. A LoRR delayConfig maps on tick for tick (pDelay, minDelay x 0.1 s,
//   maxDelay x 0.1 s, gaussMeanRatio, gaussStdRatio).
// The ADG keeps any such run collision-free: it orders who passes where, not when.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace smart::agent {

struct Uncertainty {
  double stall_probability = 0;
  double stall_s = 0;
  double speed_sigma = 0;
  double slip_sigma = 0;
  uint64_t seed = 0;
  double delay_probability = 0;  // per 0.1 s tick (Bernoulli)
  double delay_rate_hz = 0;      // Poisson events per second
  double delay_min_s = 0, delay_max_s = 0;
  double delay_mean_ratio = 0.5, delay_std_ratio = 0;  // std 0: uniform durations
  bool delays() const { return (delay_probability > 0 || delay_rate_hz > 0) && delay_max_s > 0; }
  bool any() const {
    return (stall_probability > 0 && stall_s > 0) || speed_sigma > 0 || slip_sigma > 0 || delays();
  }
  bool operator==(const Uncertainty&) const = default;
};

// A uniform draw in [0, 1) and a standard normal draw, from (seed, robot, stream, index).
double uniform01(uint64_t seed, uint32_t robot, uint32_t stream, uint64_t index);
double standard_normal(uint64_t seed, uint32_t robot, uint32_t stream, uint64_t index);

bool stalls_before(const Uncertainty& u, uint32_t robot, uint32_t seq);
double speed_factor(const Uncertainty& u, uint32_t robot);
double slip_factor(const Uncertainty& u, uint32_t robot, uint64_t tick, int wheel);
inline constexpr double kDelayTickS = 0.1;  // LoRR's tick: delay events are drawn per tick
// The delay a robot starts at delay tick `tick` (its own clock / kDelayTickS), in seconds; 0: none.
double delay_at(const Uncertainty& u, uint32_t robot, uint64_t tick);
// The delay events of `robot` in its first `ticks` ticks as an agent updated at every tick
// lives them (Agent::maybe_delay: one event at a time, drawn at the first tick it is free):
// [the tick it starts, the first tick it is free again], for LoRR's delayIntervals.
std::vector<std::pair<int64_t, int64_t>> delay_intervals(const Uncertainty& u, uint32_t robot,
                                                         int64_t ticks);

// {"stall_probability", "stall_s", "speed_sigma", "slip_sigma", "seed"} and, with delays, the
// delay_* keys, for summary.json.
nlohmann::json to_json(const Uncertainty& u);

}  // namespace smart::agent
