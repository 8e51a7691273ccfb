// Contract: plain value types of a robot's motion in the world frame of grid/grid.hpp (metres,
// yaw counter-clockwise from +x). Times are in seconds of whichever clock produced them (sim
// time in simulation, wall time on hardware); no value mixes the two. Here, below every layer
// that uses them (agent/, monitor/'s ROS view, the wire conversion), so none of them has to
// include agent/ for a pose (docs/architecture.md, "Layers").
#pragma once

namespace smart::common {

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

}  // namespace smart::common
