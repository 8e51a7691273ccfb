#include "smart/sim/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "smart/planning/random_plan.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::sim {
namespace {

agent::RobotModel model(double max_speed = 1.0) {
  agent::RobotModel m;
  m.name = "test";
  m.radius_m = 0.2;
  m.mass_kg = 10;
  m.wheel_base_m = 0.3;
  m.max_speed_mps = max_speed;
  m.max_accel_mps2 = 0.4;
  m.max_decel_mps2 = 0.4;
  return m;
}

grid::Grid open_map(int w, int h) {
  return grid::Grid(w, h, std::vector<uint8_t>(static_cast<std::size_t>(w) * h, 0), "open");
}

TEST(World, FullSpeedFromRestFollowsVEqualsATUntilTheLimit) {
  const auto grid = open_map(20, 5);
  World world(grid, model(1.0), {}, {{1.0, 2.0, 0.0}});
  world.set_wheel_targets(0, {1.0, 1.0});
  double max_err = 0;
  for (int k = 1; k <= 50; ++k) {
    world.step();
    const double t = world.time_s();
    const double expected = std::min(0.4 * t, 1.0);
    max_err = std::max(max_err, std::abs(world.pose(0).linear_mps - expected));
    EXPECT_NEAR(world.pose(0).linear_mps, expected, 0.02) << "t = " << t;
    EXPECT_LE(world.pose(0).linear_mps, 1.0 + 1e-6);
  }
  EXPECT_NEAR(world.pose(0).pose.y_m, 2.0, 1e-6);
  EXPECT_NEAR(world.pose(0).pose.yaw_rad, 0.0, 1e-6);
  // x(t) = 1 + 0.5·0.4·2.5² + 1·(5 − 2.5) = 4.75 at t = 5 s, less the slip lag.
  EXPECT_NEAR(world.pose(0).pose.x_m, 4.75, 0.05);
  EXPECT_EQ(world.contacts().robot_wall_events, 0u);
}

TEST(World, RotationInPlace) {
  const auto grid = open_map(5, 5);
  World world(grid, model(), {}, {{2.0, 2.0, 0.0}});
  world.set_wheel_targets(0, {-0.1, 0.1});  // ω = 0.2 / 0.3 rad/s once ramped
  for (int k = 0; k < 30; ++k) world.step();
  const auto p = world.pose(0);
  EXPECT_GT(p.pose.yaw_rad, 0.5);
  EXPECT_NEAR(p.angular_radps, 0.2 / 0.3, 0.01);
  EXPECT_NEAR(p.pose.x_m, 2.0, 1e-3);
  EXPECT_NEAR(p.pose.y_m, 2.0, 1e-3);
}

TEST(World, RobotDrivenIntoAWallStopsAtItAndTheContactIsCounted) {
  // Wall column at x = 4 (its west face at x = 3.5).
  const auto grid = test::grid_of({"....@...", "....@...", "....@..."});
  World world(grid, model(), {}, {{1.0, 1.0, 0.0}});
  world.set_wheel_targets(0, {0.5, 0.5});
  for (int k = 0; k < 150; ++k) world.step();
  const auto p = world.pose(0);
  EXPECT_NEAR(p.pose.x_m, 3.5 - 0.2, 0.02);  // against the face, barely penetrating
  EXPECT_LT(std::abs(p.linear_mps), 0.01);
  EXPECT_EQ(world.contacts().robot_wall_events, 1u);
  EXPECT_EQ(world.contacts().robot_wall_now, 1u);
}

TEST(World, TwoRobotsDrivenHeadOnCollideAndAreReported) {
  const auto grid = open_map(10, 3);
  World world(grid, model(), {}, {{2.0, 1.0, 0.0}, {7.0, 1.0, std::numbers::pi}});
  world.set_wheel_targets(0, {0.8, 0.8});
  world.set_wheel_targets(1, {0.8, 0.8});
  for (int k = 0; k < 100; ++k) world.step();
  EXPECT_GE(world.contacts().robot_robot_events, 1u);
  EXPECT_LT(world.contacts().min_gap_m, 0.0);
  // Pushing against each other they stay apart by about two radii, not through each other.
  const double d = world.pose(1).pose.x_m - world.pose(0).pose.x_m;
  EXPECT_GT(d, 0.3);
  EXPECT_LT(d, 0.4 + 1e-9);
}

// Random drive commands for many robots, changed every period; some robots get no command in
// some periods, so they come to rest, sleep and are woken again (by a command or a push).
uint64_t run_hash(int threads, int capacity) {
  const auto grid = planning::generate_random_grid(30, 30, 0.1, 5);
  std::vector<agent::Pose2D> starts;
  const auto inst = planning::generate_random_plan(grid, {120, 1, 9});
  for (const auto& p : inst.plan.paths) {
    const auto c = p.steps.front().cell;
    starts.push_back({double(c.x), double(grid.height() - 1 - c.y), 0.3 * c.x});
  }
  SimConfig cfg;
  cfg.threads = threads;
  cfg.system_capacity = capacity;
  World world(grid, model(), cfg, starts);
  uint64_t seed = 12345;
  std::size_t max_awake = 0, min_awake = starts.size();
  for (int k = 0; k < 60; ++k) {
    for (uint32_t i = 0; i < starts.size(); ++i) {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      const double a = double(seed >> 40) / double(1ull << 24) - 0.5;
      // Every third robot pauses for 2 s out of every 3 s (long enough to come to rest).
      const bool pause = i % 3 == 0 && (k / 10) % 3 != 0;
      world.set_wheel_targets(
          i, pause ? agent::WheelSpeeds{0, 0} : agent::WheelSpeeds{0.8 * a + 0.3, 0.3 - 0.8 * a});
    }
    world.step();
    max_awake = std::max(max_awake, world.awake_robots());
    min_awake = std::min(min_awake, world.awake_robots());
  }
  EXPECT_GT(world.contacts().robot_robot_events + world.contacts().robot_wall_events, 0u);
  EXPECT_EQ(max_awake, starts.size());
  EXPECT_LT(min_awake, starts.size()) << "no robot ever slept: the test does not cover sleeping";
  return world.state_hash();
}

TEST(World, SameInputsGiveBitIdenticalTrajectoriesWhateverThreadsAndSystemCapacity) {
  const auto a = run_hash(2, 32);
  EXPECT_EQ(a, run_hash(2, 32));
  EXPECT_EQ(a, run_hash(1, 32));
  EXPECT_EQ(a, run_hash(2, 7)) << "packing robots into other slots changed results";
  EXPECT_EQ(a, run_hash(1, 1));
  EXPECT_EQ(a, run_hash(2, 200));
  EXPECT_EQ(a, run_hash(2, 0));
}

// Regression (web_viewer failed in CI): a 50-robot lock-step run with two sim threads took over
// 120 s instead of 9 s while other processes kept both cores busy, each sub-step barrier waiting
// for a descheduled thread. Automatic threads: one for small fleets, two from 2000 robots.
TEST(World, AutomaticThreadsAreOneForSmallFleetsAndWhatWasAskedForOtherwise) {
  EXPECT_EQ(sim_threads(0, 1), 1);
  EXPECT_EQ(sim_threads(0, 50), 1);
  EXPECT_EQ(sim_threads(0, 1000), 1);  // SMART's 1000-robot warehouse
  EXPECT_EQ(sim_threads(0, 2 * kMinRobotsPerThread - 1), 1);
  EXPECT_EQ(sim_threads(0, 2 * kMinRobotsPerThread), 2);
  EXPECT_EQ(sim_threads(0, 10000), 2);
  EXPECT_EQ(sim_threads(3, 10), 3);
  const auto grid = planning::generate_random_grid(10, 10, 0.0, 1);
  std::vector<agent::Pose2D> starts{{1, 1, 0}, {3, 3, 0}};
  EXPECT_EQ(World(grid, model(), SimConfig{}, starts).threads(), 1);
  SimConfig two;
  two.threads = 2;
  EXPECT_EQ(World(grid, model(), two, starts).threads(), 2);
}

TEST(World, RestingRobotsSleepAndACommandWakesThem) {
  const auto grid = open_map(10, 10);
  SimConfig cfg;
  cfg.system_capacity = 2;
  World world(grid, model(), cfg, {{1, 1, 0}, {5, 5, 0}, {8, 8, 0}});
  world.step();
  EXPECT_EQ(world.awake_robots(), 0u);
  EXPECT_EQ(world.active_systems(), 0u);
  const auto before = world.pose(1).pose;
  world.set_wheel_targets(1, {0.3, 0.3});
  world.step();
  EXPECT_TRUE(world.awake(1));
  EXPECT_FALSE(world.awake(0));
  EXPECT_EQ(world.awake_robots(), 1u);
  EXPECT_EQ(world.active_systems(), 1u);
  for (int k = 0; k < 9; ++k) world.step();
  world.set_wheel_targets(1, {0, 0});
  for (int k = 0; k < 40; ++k) world.step();
  EXPECT_EQ(world.awake_robots(), 0u);
  EXPECT_GT(world.pose(1).pose.x_m, before.x_m + 0.05);
  EXPECT_EQ(world.pose(1).linear_mps, 0.0);
  EXPECT_EQ(world.pose(0).pose.x_m, 1.0);  // never woken, never moved
  EXPECT_DOUBLE_EQ(world.time_s(), 5.1);
}

TEST(World, ARobotPushedByAMovingOneWakesAndIsMoved) {
  const auto grid = open_map(10, 3);
  World world(grid, model(), {}, {{2.0, 1.0, 0.0}, {5.0, 1.0, 0.0}});
  world.set_wheel_targets(0, {0.5, 0.5});
  bool woke = false;
  for (int k = 0; k < 150; ++k) {
    world.step();
    woke = woke || world.awake(1);
  }
  EXPECT_TRUE(woke);
  EXPECT_GT(world.pose(1).pose.x_m, 5.1);  // pushed east
  EXPECT_GE(world.contacts().robot_robot_events, 1u);
}

TEST(World, MovingRobotsArePackedIntoFewSystems) {
  const auto grid = open_map(40, 3);
  SimConfig cfg;
  cfg.system_capacity = 4;
  std::vector<agent::Pose2D> starts;
  for (int i = 0; i < 16; ++i) starts.push_back({2.0 * i + 1, 1.0, 0.0});
  World world(grid, model(), cfg, starts);
  // Wake every other robot one period at a time, then stop all but three.
  for (uint32_t i = 0; i < 16; i += 2) {
    world.set_wheel_targets(i, {-0.1, 0.1});
    world.step();
  }
  EXPECT_EQ(world.awake_robots(), 8u);
  EXPECT_EQ(world.active_systems(), 2u);
  for (uint32_t i = 6; i < 16; i += 2) world.set_wheel_targets(i, {0, 0});
  for (int k = 0; k < 30; ++k) world.step();
  EXPECT_EQ(world.awake_robots(), 3u);
  EXPECT_EQ(world.active_systems(), 1u);
  EXPECT_NEAR(world.pose(0).angular_radps, 0.2 / 0.3, 0.01);
}

TEST(World, RejectsBadConfigurations) {
  const auto grid = test::grid_of({"..", ".@"});
  EXPECT_THROW(World(grid, model(), {}, {{1.0, 0.0, 0.0}}), std::invalid_argument);  // on '@'
  auto big = model();
  big.radius_m = 0.6;
  EXPECT_THROW(World(grid, big, {}, {{0.0, 1.0, 0.0}}), std::invalid_argument);
  SimConfig odd;
  odd.physics_step_s = 0.03;
  EXPECT_THROW(World(grid, model(), odd, {{0.0, 1.0, 0.0}}), std::invalid_argument);
  SimConfig negative;
  negative.system_capacity = -1;
  EXPECT_THROW(World(grid, model(), negative, {{0.0, 1.0, 0.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace smart::sim
