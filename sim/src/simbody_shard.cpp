// Built as C++17: see simbody_shard.hpp.
#include "simbody_shard.hpp"

#include <Simbody.h>

#include <stdexcept>

namespace smart::sim::detail {

namespace {

class CustomForce : public SimTK::Force::Custom::Implementation {
 public:
  CustomForce(const RobotForces& f, const std::vector<uint32_t>& robots) : f_(f), robots_(robots) {}
  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>&,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector& mobility) const override {
    const SimTK::Vector& q = s.getQ();
    const SimTK::Vector& u = s.getU();
    for (std::size_t k = 0; k < robots_.size(); ++k) {
      const int i = static_cast<int>(3 * k);
      const double qk[3] = {q[i], q[i + 1], q[i + 2]};
      const double uk[3] = {u[i], u[i + 1], u[i + 2]};
      double f[3] = {0, 0, 0};
      f_.robot_force(robots_[k], s.getTime(), qk, uk, f);
      mobility[i] += f[0];
      mobility[i + 1] += f[1];
      mobility[i + 2] += f[2];
    }
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  const RobotForces& f_;
  const std::vector<uint32_t>& robots_;
};

}  // namespace

struct SimbodyShard::Impl {
  std::vector<uint32_t> robots;
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  std::unique_ptr<SimTK::SemiExplicitEulerIntegrator> integ;
  double step_s = 0;
};

SimbodyShard::SimbodyShard(const RobotForces& forces, std::vector<uint32_t> robots, double mass_kg,
                           double radius_m, const std::vector<std::array<double, 3>>& start_q,
                           double step_s)
    : impl_(std::make_unique<Impl>()) {
  auto& I = *impl_;
  I.robots = std::move(robots);
  I.step_s = step_s;
  const SimTK::Body::Rigid body(SimTK::MassProperties(
      mass_kg, SimTK::Vec3(0), SimTK::UnitInertia::cylinderAlongZ(radius_m, 0.05)));
  std::vector<SimTK::MobilizedBody::Planar> bodies;
  for (std::size_t k = 0; k < I.robots.size(); ++k) bodies.emplace_back(I.matter.Ground(), body);
  SimTK::Force::Custom(I.forces, new CustomForce(forces, I.robots));
  I.system.realizeTopology();
  SimTK::State s = I.system.getDefaultState();
  I.system.realizeModel(s);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    // Verified layout (simulation.md pitfall 8): Planar bodies on Ground at q = u = 3k,
    // q = (θ, x, y) about/along the ground frame's axes.
    const int i = static_cast<int>(3 * k);
    if (static_cast<int>(bodies[k].getFirstQIndex(s)) != i ||
        static_cast<int>(bodies[k].getFirstUIndex(s)) != i) {
      throw std::logic_error("unexpected Simbody q/u layout for Planar bodies");
    }
    for (int a = 0; a < 3; ++a) s.updQ()[i + a] = start_q[k][static_cast<std::size_t>(a)];
  }
  I.integ = std::make_unique<SimTK::SemiExplicitEulerIntegrator>(I.system, step_s);
  I.integ->setAllowInterpolation(false);  // pitfall 4: land exactly on sync ticks
  I.integ->initialize(s);
}

SimbodyShard::~SimbodyShard() = default;

const std::vector<uint32_t>& SimbodyShard::robots() const { return impl_->robots; }
double SimbodyShard::time_s() const { return impl_->integ->getTime(); }

void SimbodyShard::step_to(double t) {
  auto& I = *impl_;
  // Data outside the State (commands, neighbour snapshot) changed: forces must be recomputed
  // (pitfall 5).
  I.integ->updAdvancedState().invalidateAllCacheAtOrAbove(SimTK::Stage::Dynamics);
  while (I.integ->getTime() < t - 1e-9 * I.step_s) I.integ->stepTo(t);
}

void SimbodyShard::restart_at(double t) {
  SimTK::State s = impl_->integ->getState();
  s.setTime(t);
  impl_->integ->initialize(s);
}

void SimbodyShard::read(std::size_t k, double* q, double* u) const {
  const SimTK::State& s = impl_->integ->getState();
  const int i = static_cast<int>(3 * k);
  for (int a = 0; a < 3; ++a) {
    q[a] = s.getQ()[i + a];
    u[a] = s.getU()[i + a];
  }
}

void SimbodyShard::zero_velocity(std::size_t k) {
  SimTK::State& s = impl_->integ->updAdvancedState();
  const int i = static_cast<int>(3 * k);
  s.updU()[i] = s.updU()[i + 1] = s.updU()[i + 2] = 0;
}

}  // namespace smart::sim::detail
