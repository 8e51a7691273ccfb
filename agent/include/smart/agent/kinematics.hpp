// Contract: differential-drive kinematics (pure). A twist (v, ω) maps to wheel ground speeds
// left = v − ω·b/2, right = v + ω·b/2 for wheel base b, and back.
#pragma once

#include "smart/agent/types.hpp"

namespace smart::agent {

WheelSpeeds to_wheels(Twist t, double wheel_base_m);
Twist to_twist(WheelSpeeds w, double wheel_base_m);
// Wraps an angle to (−π, π].
double wrap_angle(double a);
// Scales both wheels down (keeping the curvature) so neither exceeds max_wheel_mps.
WheelSpeeds saturate(WheelSpeeds w, double max_wheel_mps);

}  // namespace smart::agent
