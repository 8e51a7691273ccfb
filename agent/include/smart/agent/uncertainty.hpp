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
// The ADG keeps any such run collision-free: it orders who passes where, not when.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>

namespace smart::agent {

struct Uncertainty {
  double stall_probability = 0;
  double stall_s = 0;
  double speed_sigma = 0;
  double slip_sigma = 0;
  uint64_t seed = 0;
  bool any() const {
    return (stall_probability > 0 && stall_s > 0) || speed_sigma > 0 || slip_sigma > 0;
  }
  bool operator==(const Uncertainty&) const = default;
};

// A uniform draw in [0, 1) and a standard normal draw, from (seed, robot, stream, index).
double uniform01(uint64_t seed, uint32_t robot, uint32_t stream, uint64_t index);
double standard_normal(uint64_t seed, uint32_t robot, uint32_t stream, uint64_t index);

bool stalls_before(const Uncertainty& u, uint32_t robot, uint32_t seq);
double speed_factor(const Uncertainty& u, uint32_t robot);
double slip_factor(const Uncertainty& u, uint32_t robot, uint64_t tick, int wheel);

// {"stall_probability", "stall_s", "speed_sigma", "slip_sigma", "seed"} for summary.json.
nlohmann::json to_json(const Uncertainty& u);

}  // namespace smart::agent
