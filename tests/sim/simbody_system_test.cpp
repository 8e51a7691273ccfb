// The Simbody body-slot system (sim/src/simbody_system.hpp, internal to sim/).
#include "simbody_system.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace smart::sim::detail {
namespace {

// Force on robot r: a velocity- and position-dependent law different for every robot, so that a
// mix-up of slots or robots shows.
struct TestForces : RobotForces {
  mutable std::atomic<int> calls{0};
  mutable uint32_t last_robot = kVacant;
  void robot_force(uint32_t r, double t, const double* q, const double* u,
                   double* f) const override {
    ++calls;
    last_robot = r;
    f[0] += 0.3 * std::sin(t + r) - 0.2 * u[0];
    f[1] += 2.0 * std::cos(0.7 * t * (r + 1)) - 0.5 * u[1] - 0.1 * q[1];
    f[2] += 1.0 + 0.01 * r - 0.5 * u[2];
  }
};

constexpr double kMass = 10, kRadius = 0.2, kH = 0.01;

std::array<double, 6> state(const SimbodySystem& s, std::size_t k) {
  std::array<double, 6> out{};
  s.read(k, out.data(), out.data() + 3);
  return out;
}

class OneStep : public ::testing::TestWithParam<SimbodySystem::Dynamics> {};

TEST_P(OneStep, IsSemiExplicitEuler) {
  struct Constant : RobotForces {
    void robot_force(uint32_t, double, const double*, const double*, double* f) const override {
      f[0] += 0.5;  // N·m
      f[1] += 2.0;  // N
      f[2] += -1.0;
    }
  } forces;
  SimbodySystem sys(forces, 1, kMass, kRadius, GetParam());
  sys.place(0, 7, {0.1, 1.0, 2.0}, {0.0, 0.3, 0.0});
  sys.step(0.0, kH);
  const auto s = state(sys, 0);
  // Disc inertia about z: m r² / 2 (UnitInertia::cylinderAlongZ).
  const double izz = kMass * kRadius * kRadius / 2;
  const double w1 = 0.5 / izz * kH, vx1 = 0.3 + 2.0 / kMass * kH, vy1 = -1.0 / kMass * kH;
  EXPECT_NEAR(s[3], w1, 1e-12);
  EXPECT_NEAR(s[4], vx1, 1e-12);
  EXPECT_NEAR(s[5], vy1, 1e-12);
  // Positions advance with the new velocities (semi-explicit, not explicit, Euler).
  EXPECT_NEAR(s[0], 0.1 + kH * w1, 1e-12);
  EXPECT_NEAR(s[1], 1.0 + kH * vx1, 1e-12);
  EXPECT_NEAR(s[2], 2.0 + kH * vy1, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(SimbodySystem, OneStep,
                         ::testing::Values(SimbodySystem::Dynamics::kMassMatrix,
                                           SimbodySystem::Dynamics::kFullRealize));

// The mass-matrix path skips Simbody's per-step kinematics, inertias and velocity-dependent
// forces because for these bodies they change nothing: same bits as the full forward dynamics,
// for robots spinning through every heading at speed, in every slot, vacant slots included.
TEST(SimbodySystem, MassMatrixStepsAreBitIdenticalToSimbodysFullForwardDynamics) {
  struct Spinning : TestForces {
    void robot_force(uint32_t r, double t, const double* q, const double* u,
                     double* f) const override {
      TestForces::robot_force(r, t, q, u, f);
      f[0] += 0.4 + 0.1 * std::cos(q[0] * 3 + q[1]) - 0.05 * u[1] * u[2];
    }
  } forces;
  using D = SimbodySystem::Dynamics;
  SimbodySystem fast(forces, 5, kMass, kRadius, D::kMassMatrix);
  SimbodySystem full(forces, 5, kMass, kRadius, D::kFullRealize);
  for (auto* sys : {&fast, &full}) {
    sys->place(0, 3, {2.5, 1.0, -4.0}, {3.0, 0.7, -0.2});
    sys->place(1, 8, {-1.2, 10.0, 20.0}, {-2.0, -1.5, 0.4});
    sys->place(4, 1, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0});
  }
  for (int k = 0; k < 1000; ++k) {
    fast.step(k * kH, kH);
    full.step(k * kH, kH);
    for (std::size_t slot = 0; slot < 5; ++slot) {
      const auto a = state(fast, slot), b = state(full, slot);
      ASSERT_EQ(std::memcmp(a.data(), b.data(), sizeof a), 0) << "slot " << slot << " step " << k;
    }
    if (k == 499) fast.vacate(1), full.vacate(1);
  }
  EXPECT_GT(std::abs(state(fast, 0)[0] - 2.5), 7.0);  // more than a full turn: every heading was stepped
}

TEST(SimbodySystem, ARobotsTrajectoryIsBitIdenticalInAnySlotOfAnySystem) {
  TestForces forces;
  const std::array<double, 3> q0{0.4, 3.0, 1.0}, u0{0.1, 0.2, -0.1};
  // Robot 5 alone in a one-body system...
  SimbodySystem alone(forces, 1, kMass, kRadius);
  alone.place(0, 5, q0, u0);
  // ...and in slot 2 of a four-body system next to two other robots and a vacant slot.
  SimbodySystem shared(forces, 4, kMass, kRadius);
  shared.place(0, 1, {0, 0, 0}, {1, 1, 1});
  shared.place(3, 2, {1, 5, 5}, {0, -1, 0});
  shared.place(2, 5, q0, u0);
  for (int k = 0; k < 200; ++k) {
    alone.step(k * kH, kH);
    shared.step(k * kH, kH);
  }
  const auto a = state(alone, 0), b = state(shared, 2);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof a), 0);
  EXPECT_GT(std::abs(a[1] - q0[1]), 0.1);  // it did move
  // Moved to another system half-way: still the same trajectory.
  SimbodySystem first(forces, 2, kMass, kRadius), second(forces, 3, kMass, kRadius);
  first.place(1, 5, q0, u0);
  for (int k = 0; k < 100; ++k) first.step(k * kH, kH);
  const auto mid = state(first, 1);
  first.vacate(1);
  second.place(0, 5, {mid[0], mid[1], mid[2]}, {mid[3], mid[4], mid[5]});
  for (int k = 100; k < 200; ++k) second.step(k * kH, kH);
  const auto c = state(second, 0);
  EXPECT_EQ(std::memcmp(a.data(), c.data(), sizeof a), 0);
}

TEST(SimbodySystem, VacantSlotsGetNoForceAndStayPut) {
  TestForces forces;
  SimbodySystem sys(forces, 3, kMass, kRadius);
  EXPECT_EQ(sys.first_vacant(), 0u);
  sys.place(1, 9, {0, 2, 2}, {0, 0.5, 0});
  EXPECT_EQ(sys.occupied(), 1u);
  EXPECT_EQ(sys.robot(1), 9u);
  EXPECT_EQ(sys.robot(0), kVacant);
  EXPECT_EQ(sys.first_vacant(), 0u);
  for (int k = 0; k < 10; ++k) sys.step(k * kH, kH);
  EXPECT_EQ(forces.calls.load(), 10);
  EXPECT_EQ(forces.last_robot, 9u);
  sys.vacate(1);
  const auto parked = state(sys, 1);
  EXPECT_EQ(parked[3], 0.0);
  EXPECT_EQ(parked[4], 0.0);
  for (int k = 10; k < 20; ++k) sys.step(k * kH, kH);
  EXPECT_EQ(forces.calls.load(), 10);
  EXPECT_EQ(state(sys, 1), parked);
  EXPECT_EQ(sys.occupied(), 0u);
}

TEST(SimbodySystem, RejectsATakenSlotAndAVacantVacate) {
  TestForces forces;
  SimbodySystem sys(forces, 2, kMass, kRadius);
  sys.place(0, 1, {0, 0, 0}, {0, 0, 0});
  EXPECT_THROW(sys.place(0, 2, {0, 0, 0}, {0, 0, 0}), std::logic_error);
  EXPECT_THROW(sys.place(2, 2, {0, 0, 0}, {0, 0, 0}), std::logic_error);
  EXPECT_THROW(sys.vacate(1), std::logic_error);
  sys.place(1, 2, {0, 0, 0}, {0, 0, 0});
  EXPECT_EQ(sys.first_vacant(), 2u);  // full
}

}  // namespace
}  // namespace smart::sim::detail
