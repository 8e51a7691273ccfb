// Built as C++17: see simbody_system.hpp.
#include "simbody_system.hpp"

#include <Simbody.h>

#include <stdexcept>

namespace smart::sim::detail {

namespace {

// Adds the forces RobotForces gives for every occupied slot to `mobility` (3 entries per slot).
void add_forces(const RobotForces& f, const std::vector<uint32_t>& slots, double time_s,
                const SimTK::Vector& q, const SimTK::Vector& u, SimTK::Vector& mobility) {
  for (std::size_t k = 0; k < slots.size(); ++k) {
    if (slots[k] == kVacant) continue;
    const int i = static_cast<int>(3 * k);
    const double qk[3] = {q[i], q[i + 1], q[i + 2]};
    const double uk[3] = {u[i], u[i + 1], u[i + 2]};
    double fk[3] = {0, 0, 0};
    f.robot_force(slots[k], time_s, qk, uk, fk);
    mobility[i] += fk[0];
    mobility[i + 1] += fk[1];
    mobility[i + 2] += fk[2];
  }
}

// The reference path's force element: the same forces, read from the State being realized.
class CustomForce : public SimTK::Force::Custom::Implementation {
 public:
  CustomForce(const RobotForces& f, const std::vector<uint32_t>& slots) : f_(f), slots_(slots) {}
  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>&,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobility) const override {
    add_forces(f_, slots_, s.getTime(), s.getQ(), s.getU(), mobility);
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  const RobotForces& f_;
  const std::vector<uint32_t>& slots_;
};

}  // namespace

struct SimbodySystem::Impl {
  std::vector<uint32_t> slots;
  std::size_t occupied = 0;
  Dynamics dynamics = Dynamics::kMassMatrix;
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  const RobotForces* robot_forces = nullptr;
  // kMassMatrix: `state` stays at its default configuration, realized to Position once with its
  // articulated body inertias, and is never changed; the bodies' q and u live here.
  SimTK::State state;
  SimTK::Vector q, u, f, udot;  // 3 per slot: (θ, x, y), (ω, vx, vy), forces, u̇

  void udot_mass_matrix(double t);
  void step_full_realize(double t, double h);
};

SimbodySystem::SimbodySystem(const RobotForces& forces, std::size_t capacity, double mass_kg,
                             double radius_m, Dynamics dynamics)
    : impl_(std::make_unique<Impl>()) {
  auto& I = *impl_;
  I.slots.assign(capacity, kVacant);
  I.dynamics = dynamics;
  I.robot_forces = &forces;
  const SimTK::Body::Rigid body(SimTK::MassProperties(
      mass_kg, SimTK::Vec3(0), SimTK::UnitInertia::cylinderAlongZ(radius_m, 0.05)));
  std::vector<SimTK::MobilizedBody::Planar> bodies;
  for (std::size_t k = 0; k < capacity; ++k) bodies.emplace_back(I.matter.Ground(), body);
  // The handle adds the force to the subsystem, which owns it (Simbody API: Force::Custom).
  SimTK::Force::Custom(I.forces, new CustomForce(forces, I.slots));  // NOLINT(bugprone-unused-raii)
  I.system.realizeTopology();
  I.state = I.system.getDefaultState();
  I.system.realizeModel(I.state);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    // Verified layout (docs/simulation.md, pitfall 8): Planar bodies on Ground at q = u = 3k,
    // q = (θ, x, y) about/along the ground frame's axes.
    const int i = static_cast<int>(3 * k);
    if (static_cast<int>(bodies[k].getFirstQIndex(I.state)) != i ||
        static_cast<int>(bodies[k].getFirstUIndex(I.state)) != i) {
      throw std::logic_error("unexpected Simbody q/u layout for Planar bodies");
    }
  }
  const int n = static_cast<int>(3 * capacity);
  I.q.resize(n);
  I.u.resize(n);
  I.f.resize(n);
  I.udot.resize(n);
  I.q = 0;
  I.u = 0;
  I.system.realize(I.state, SimTK::Stage::Position);
  I.matter.realizeArticulatedBodyInertias(I.state);
}

SimbodySystem::~SimbodySystem() = default;

std::size_t SimbodySystem::capacity() const { return impl_->slots.size(); }
std::size_t SimbodySystem::occupied() const { return impl_->occupied; }
uint32_t SimbodySystem::robot(std::size_t k) const { return impl_->slots[k]; }

std::size_t SimbodySystem::first_vacant() const {
  const auto& slots = impl_->slots;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    if (slots[k] == kVacant) return k;
  }
  return slots.size();
}

void SimbodySystem::place(std::size_t k, uint32_t robot, const std::array<double, 3>& q,
                          const std::array<double, 3>& u) {
  auto& I = *impl_;
  if (k >= I.slots.size() || I.slots[k] != kVacant || robot == kVacant) {
    throw std::logic_error("SimbodySystem::place: slot taken or out of range");
  }
  I.slots[k] = robot;
  ++I.occupied;
  const int i = static_cast<int>(3 * k);
  for (int a = 0; a < 3; ++a) {
    I.q[i + a] = q[static_cast<std::size_t>(a)];
    I.u[i + a] = u[static_cast<std::size_t>(a)];
  }
}

void SimbodySystem::vacate(std::size_t k) {
  auto& I = *impl_;
  if (k >= I.slots.size() || I.slots[k] == kVacant) {
    throw std::logic_error("SimbodySystem::vacate: slot already vacant or out of range");
  }
  I.slots[k] = kVacant;
  --I.occupied;
  const int i = static_cast<int>(3 * k);
  I.u[i] = I.u[i + 1] = I.u[i + 2] = 0;
}

void SimbodySystem::read(std::size_t k, double* q, double* u) const {
  const auto& I = *impl_;
  const int i = static_cast<int>(3 * k);
  for (int a = 0; a < 3; ++a) {
    q[a] = I.q[i + a];
    u[a] = I.u[i + a];
  }
}

// u̇ = M⁻¹·f with Simbody's O(n) operator against the fixed configuration: M of a Planar body on
// Ground whose centre of mass is on its rotation axis does not depend on q, and its
// velocity-dependent forces (gyroscopic, Coriolis) are zero (docs/simulation.md).
void SimbodySystem::Impl::udot_mass_matrix(double t) {
  f = 0;
  add_forces(*robot_forces, slots, t, q, u, f);
  matter.multiplyByMInv(state, f, udot);
}

// The reference: Simbody's whole forward dynamics, realize(Acceleration) at the bodies' own q
// and u, and q̇ from multiplyByN; the step the World took before the mass-matrix path.
void SimbodySystem::Impl::step_full_realize(double t, double h) {
  SimTK::State& s = state;
  s.setTime(t);
  s.updQ() = q;
  s.updU() = u;
  system.realize(s, SimTK::Stage::Acceleration);
  udot = s.getUDot();
  udot *= h;
  s.updU() += udot;
  SimTK::Vector& qdot = f;  // the forces are in the State's cache here: f is free scratch
  matter.multiplyByN(s, false, s.getU(), qdot);
  qdot *= h;
  s.updQ() += qdot;
  q = s.getQ();
  u = s.getU();
}

void SimbodySystem::step(double t, double h) {
  auto& I = *impl_;
  if (I.dynamics == Dynamics::kFullRealize) {
    I.step_full_realize(t, h);
    return;
  }
  I.udot_mass_matrix(t);
  // Semi-explicit Euler; for Planar q̇ = N(q)·u = u (the reference path uses multiplyByN).
  for (int i = 0; i < I.u.size(); ++i) {
    I.u[i] += I.udot[i] * h;
    I.q[i] += I.u[i] * h;
  }
}

}  // namespace smart::sim::detail
