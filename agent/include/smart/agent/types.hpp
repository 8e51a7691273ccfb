// Contract: plain value types of the agent, in the world frame of grid/grid.hpp (metres,
// yaw counter-clockwise from +x). Times are in seconds of whichever clock drives the agent (sim
// time in simulation, wall time on hardware); an agent never mixes the two. Poses, twists and
// wheel values live in common/pose.hpp (they are shared by layers below the agent) and are named
// here as the agent's own.
#pragma once

#include <cstdint>

#include "smart/common/pose.hpp"

namespace smart::agent {

using common::Pose2D;
using common::PoseSample;
using common::Twist;
using common::WheelFactors;
using common::WheelSpeeds;

enum class ActionKind : uint8_t { kMove, kRotate };

// One action as the agent executes it (converted from the wire type at the DDS edge).
struct AgentAction {
  uint32_t seq = 0;
  ActionKind kind = ActionKind::kMove;
  double from_x_m = 0, from_y_m = 0;
  double to_x_m = 0, to_y_m = 0;
  double heading_rad = 0;  // held during a move, reached by a rotation
};

}  // namespace smart::agent
