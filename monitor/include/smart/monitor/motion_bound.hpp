// Contract: the fastest each robot could execute its actions alone (docs/fidelity.md): every
// straight run (consecutive half-moves holding one heading) and every rotation (90° or 180°)
// as a rest-to-rest trapezoid, or triangle, profile under the speed and acceleration limits;
// nothing else (no waits for other robots, no controller settling). A robot's finish time can
// only be above its bound; the ratio says what the controller and the waits cost. Pure.
#pragma once

#include <vector>

#include "smart/grid/action.hpp"

namespace smart::monitor {

struct MotionLimits {
  double max_speed_mps = 1, max_accel_mps2 = 1, max_decel_mps2 = 1;
  double max_turn_rate_radps = 1, max_angular_accel_radps2 = 1;
};

// Time to cover `distance` from rest to rest with the peak speed v_max, accelerating at
// `accel` and braking at `decel` (triangle profile when v_max is not reached).
double rest_to_rest_s(double distance, double v_max, double accel, double decel);

// Per robot, seconds; half-moves are cell_m / 2 long.
std::vector<double> motion_lower_bounds_s(const grid::ActionPlan& actions, double cell_m,
                                          const MotionLimits& limits);

}  // namespace smart::monitor
