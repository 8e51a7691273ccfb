// Contract: wheel trim from a straight-drive trial (pure). Both wheels were commanded the same
// ground speed `command_mps`; the pose samples show what the robot did. Over the samples from
// `settle_s` after the first one (acceleration over), the heading rate w is the least-squares
// slope of the unwrapped heading and the speed v the path length over the time (settle_s counts
// from when the robot first moved 2 mm: commands over a network start late); a unicycle
// with wheel base b then had wheels left = v - w b / 2, right = v + w b / 2 (kinematics.hpp), and
// each wheel's gain is its speed over the command. The proposed trim scales the faster wheel
// down to the slower one (no wheel is asked for more than it was), so the robot drives straight.
// Throws std::invalid_argument when the trial is unusable (too few samples, too short, robot
// barely moved), saying what to change.
#pragma once

#include <vector>

#include "smart/agent/types.hpp"

namespace smart::agent {

struct WheelTrial {
  double speed_mps = 0;        // v
  double turn_rate_radps = 0;  // w
  double duration_s = 0;
  WheelFactors gain;  // measured ground speed / commanded, per wheel
  WheelFactors trim;  // factors for the wheels' commands (<= 1); 1 for the slower wheel
};

WheelTrial measure_wheel_trial(const std::vector<PoseSample>& samples, double command_mps,
                               double wheel_base_m, double settle_s);

}  // namespace smart::agent
