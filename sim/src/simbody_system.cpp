// Built as C++17: see simbody_system.hpp.
#include "simbody_system.hpp"

#include <Simbody.h>

#include <stdexcept>

namespace smart::sim::detail {

namespace {

class CustomForce : public SimTK::Force::Custom::Implementation {
 public:
  CustomForce(const RobotForces& f, const std::vector<uint32_t>& slots) : f_(f), slots_(slots) {}
  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>&,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobility) const override {
    const SimTK::Vector& q = s.getQ();
    const SimTK::Vector& u = s.getU();
    for (std::size_t k = 0; k < slots_.size(); ++k) {
      if (slots_[k] == kVacant) continue;
      const int i = static_cast<int>(3 * k);
      const double qk[3] = {q[i], q[i + 1], q[i + 2]};
      const double uk[3] = {u[i], u[i + 1], u[i + 2]};
      double f[3] = {0, 0, 0};
      f_.robot_force(slots_[k], s.getTime(), qk, uk, f);
      mobility[i] += f[0];
      mobility[i + 1] += f[1];
      mobility[i + 2] += f[2];
    }
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
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  SimTK::State state;
  SimTK::Vector du, qdot;  // step buffers, kept to avoid allocations
};

SimbodySystem::SimbodySystem(const RobotForces& forces, std::size_t capacity, double mass_kg,
                             double radius_m)
    : impl_(std::make_unique<Impl>()) {
  auto& I = *impl_;
  I.slots.assign(capacity, kVacant);
  const SimTK::Body::Rigid body(SimTK::MassProperties(
      mass_kg, SimTK::Vec3(0), SimTK::UnitInertia::cylinderAlongZ(radius_m, 0.05)));
  std::vector<SimTK::MobilizedBody::Planar> bodies;
  for (std::size_t k = 0; k < capacity; ++k) bodies.emplace_back(I.matter.Ground(), body);
  SimTK::Force::Custom(I.forces, new CustomForce(forces, I.slots));
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
  SimTK::Vector& sq = I.state.updQ();
  for (int a = 0; a < 3; ++a) sq[i + a] = q[static_cast<std::size_t>(a)];
  SimTK::Vector& su = I.state.updU();
  for (int a = 0; a < 3; ++a) su[i + a] = u[static_cast<std::size_t>(a)];
}

void SimbodySystem::vacate(std::size_t k) {
  auto& I = *impl_;
  if (k >= I.slots.size() || I.slots[k] == kVacant) {
    throw std::logic_error("SimbodySystem::vacate: slot already vacant or out of range");
  }
  I.slots[k] = kVacant;
  --I.occupied;
  SimTK::Vector& su = I.state.updU();
  const int i = static_cast<int>(3 * k);
  su[i] = su[i + 1] = su[i + 2] = 0;
}

void SimbodySystem::read(std::size_t k, double* q, double* u) const {
  const SimTK::State& s = impl_->state;
  const int i = static_cast<int>(3 * k);
  for (int a = 0; a < 3; ++a) {
    q[a] = s.getQ()[i + a];
    u[a] = s.getU()[i + a];
  }
}

void SimbodySystem::step(double t, double h) {
  auto& I = *impl_;
  SimTK::State& s = I.state;
  s.setTime(t);
  s.invalidateAllCacheAtOrAbove(SimTK::Stage::Dynamics);
  I.system.realize(s, SimTK::Stage::Acceleration);
  I.du = s.getUDot();
  I.du *= h;
  s.updU() += I.du;  // u1 = u0 + h·u̇ (invalidates Velocity; Position stays realized)
  I.matter.multiplyByN(s, false, s.getU(), I.qdot);
  I.qdot *= h;
  s.updQ() += I.qdot;  // q1 = q0 + h·N(q0)·u1
}

}  // namespace smart::sim::detail
