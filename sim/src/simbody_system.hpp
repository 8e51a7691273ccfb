// Internal (sim/ only). The one place that includes Simbody. Simbody 3.7's headers do not
// compile as C++20 (ambiguous reversed operator== in ContactGeometry.h), so simbody_system.cpp
// is built as C++17 and this header must stay C++17-clean: no project headers, no C++20.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace smart::sim::detail {

constexpr uint32_t kVacant = 0xffffffffu;

// Supplies the forces on one robot: q = (yaw, x, y), u = (ω, vx, vy) in the world frame;
// writes (torque, fx, fy) to f.
class RobotForces {
 public:
  virtual ~RobotForces() = default;
  virtual void robot_force(uint32_t robot, double time_s, const double* q, const double* u,
                           double* f) const = 0;
};

// One Simbody MultibodySystem of `capacity` identical bodies on MobilizedBody::Planar ("slots")
// with one Force::Custom calling RobotForces for the robot in each occupied slot.
//
// Slots, not robots, are what the system owns: a robot is put into a slot by copying its state
// in, and taken out by reading it back, so the World can pack the robots that are moving into
// few systems and leave the rest out of Simbody altogether (docs/simulation.md, design (c');
// pitfall 6: topology is fixed, so park unused bodies).
// A vacant slot holds a body at rest with no force on it; it costs its share of the step but its
// state never changes.
//
// Bodies hang directly off Ground with no constraints, so each body's arithmetic depends only on
// its own q, u and force: a robot's trajectory is bit-identical in whatever slot of whatever
// system it is stepped (tested).
//
// step() is one semi-explicit Euler step of h, the update of Simbody's
// SemiExplicitEulerIntegrator: u1 = u0 + h·u̇(t, q0, u0), q1 = q0 + h·N(q0)·u1, with u̇ from
// Simbody (see Dynamics). It is done here rather than by the Integrator so that the
// time is set exactly (t = k·h, no accumulated stepTo rounding) and a system that sat empty can
// resume without a 0.2 ms re-initialisation; measured per-system overhead 10 µs per step
// instead of 18 µs (docs/performance.md).
class SimbodySystem {
 public:
  // How u̇ is computed. kMassMatrix: u̇ = M⁻¹·f with Simbody's O(n) operator
  // (SimbodyMatterSubsystem::multiplyByMInv) against articulated body inertias realized once;
  // exact for these bodies because M does not depend on q and there are no velocity-dependent
  // forces (a Planar body on Ground with its centre of mass on the rotation axis). kFullRealize:
  // realize(Acceleration) at every step, Simbody's whole forward dynamics (kinematics, inertias,
  // forces, accelerations), kept as the reference the fast path is tested against.
  enum class Dynamics { kMassMatrix, kFullRealize };

  SimbodySystem(const RobotForces& forces, std::size_t capacity, double mass_kg, double radius_m,
                Dynamics dynamics = Dynamics::kMassMatrix);
  ~SimbodySystem();
  SimbodySystem(const SimbodySystem&) = delete;
  SimbodySystem& operator=(const SimbodySystem&) = delete;

  std::size_t capacity() const;
  std::size_t occupied() const;
  // Robot in slot k, or kVacant.
  uint32_t robot(std::size_t k) const;
  // Lowest vacant slot (capacity() when full).
  std::size_t first_vacant() const;

  // Puts `robot` into the vacant slot k with state q = (θ, x, y), u = (ω, vx, vy).
  void place(std::size_t k, uint32_t robot, const std::array<double, 3>& q,
             const std::array<double, 3>& u);
  // Empties slot k (its body is stopped in place).
  void vacate(std::size_t k);
  void read(std::size_t k, double* q, double* u) const;

  // One step from time t (forces evaluated at t) to t + h. Forces are always recomputed: they
  // read data outside the State (commands, the neighbour snapshot; pitfall 5).
  void step(double t, double h);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::sim::detail
