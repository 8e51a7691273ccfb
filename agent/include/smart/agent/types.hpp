// Contract: plain value types of the agent, in the world frame of grid/grid.hpp (metres,
// yaw counter-clockwise from +x). Times are in seconds of whichever clock drives the agent (sim
// time in simulation, wall time on hardware); an agent never mixes the two.
#pragma once

#include <cstdint>

namespace smart::agent {

struct Pose2D {
  double x_m = 0;
  double y_m = 0;
  double yaw_rad = 0;
};

struct PoseSample {
  Pose2D pose;
  double linear_mps = 0;  // forward speed
  double angular_radps = 0;
  double stamp_s = 0;  // when the pose was measured
  bool valid = false;
};

struct WheelSpeeds {
  double left_mps = 0;
  double right_mps = 0;
};

// A dimensionless factor per wheel (measured gains, trims), 1 = as commanded.
struct WheelFactors {
  double left = 1.0;
  double right = 1.0;
  bool operator==(const WheelFactors&) const = default;
};

struct Twist {
  double linear_mps = 0;
  double angular_radps = 0;
};

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
