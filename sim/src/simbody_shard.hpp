// Internal (sim/ only). The one place that includes Simbody. Simbody 3.7's headers do not
// compile as C++20 (ambiguous reversed operator== in ContactGeometry.h), so simbody_shard.cpp is
// built as C++17 and this header must stay C++17-clean: no project headers, no C++20.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace smart::sim::detail {

// Supplies the forces on one robot: q = (yaw, x, y), u = (ω, vx, vy) in the world frame;
// writes (torque, fx, fy) to f.
class RobotForces {
 public:
  virtual ~RobotForces() = default;
  virtual void robot_force(uint32_t robot, double time_s, const double* q, const double* u,
                           double* f) const = 0;
};

// One Simbody MultibodySystem of robots on MobilizedBody::Planar, with one Force::Custom
// calling RobotForces, integrated by a fixed-step SemiExplicitEulerIntegrator.
class SimbodyShard {
 public:
  SimbodyShard(const RobotForces& forces, std::vector<uint32_t> robots, double mass_kg,
               double radius_m, const std::vector<std::array<double, 3>>& start_q, double step_s);
  ~SimbodyShard();
  const std::vector<uint32_t>& robots() const;
  double time_s() const;
  // Steps to `t` (a multiple of the step size); forces are re-evaluated from scratch.
  void step_to(double t);
  // After a pause: continue from the current state at time t.
  void restart_at(double t);
  void read(std::size_t k, double* q, double* u) const;
  void zero_velocity(std::size_t k);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::sim::detail
