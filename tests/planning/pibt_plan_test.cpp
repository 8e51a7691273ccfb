// One-shot plans by PIBT alone (pibt_plan.hpp): valid, every robot home, deterministic per seed,
// and an honest error where PIBT alone cannot finish.
#include "smart/planning/pibt_plan.hpp"

#include <gtest/gtest.h>

#include "planning/plan_checks.hpp"
#include "smart/monitor/plan_validator.hpp"
#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

using namespace grid;  // the vocabulary the planners work in

void expect_valid(const Grid& g, std::size_t robots, uint64_t seed, const char* what) {
  const auto scen = generate_scenario(g, robots, seed, what);
  expect_valid_plan(g, scen, plan_pibt(g, scen, {seed}), what);
}

TEST(PibtPlan, EveryRobotEndsOnItsGoalOnOpenMaps) {
  expect_valid(generate_random_map(30, 30, 0.1, 2), 80, 2, "random");
  expect_valid(generate_empty_map(16, 16), 100, 3, "empty");
}

TEST(PibtPlan, IsTheSamePlanForTheSameSeed) {
  const auto g = generate_random_map(24, 24, 0.1, 5);
  const auto scen = generate_scenario(g, 60, 5, "random");
  expect_seeded([&](uint64_t seed) { return plan_pibt(g, scen, {seed}); }, 5);
}

TEST(PibtPlan, OnARingRobotsPassEachOtherAndPathsEndOnTheirLastMove) {
  // A ring of eight cells (biconnected: PIBT's Theorem 2) and three robots crossing it; robot 2
  // starts where robot 0 must pass.
  const Grid g(3, 3, {0, 0, 0, 0, 1, 0, 0, 0, 0}, "ring");
  Scenario s;
  s.agents = {{{0, 0}, {2, 2}, 4}, {{2, 2}, {0, 0}, 4}, {{1, 0}, {1, 2}, 4}};
  const auto r = plan_pibt(g, s, {1});
  ASSERT_TRUE(r.solved) << r.error;
  EXPECT_TRUE(monitor::validate_plan(r.plan, g, &s).empty());
  for (const auto& p : r.plan.paths) {
    ASSERT_GE(p.steps.size(), 2u);
    EXPECT_EQ(p.steps.back().cell, s.agents[p.robot].goal);
    EXPECT_NE(p.steps.back().cell, p.steps[p.steps.size() - 2].cell)
        << "robot " << p.robot << ": trailing waits on its goal";
  }
}

TEST(PibtPlan, ACorridorPibtCannotSolveIsAnErrorNotAHang) {
  // Two robots swap ends of a corridor without a pocket: no plan exists.
  const Grid g(4, 1, {0, 0, 0, 0}, "corridor");
  Scenario s;
  s.agents = {{{0, 0}, {3, 0}, 3}, {{3, 0}, {0, 0}, 3}};
  const auto r = plan_pibt(g, s, {1, 16, 200});
  EXPECT_FALSE(r.solved);
  EXPECT_NE(r.error.find("not every robot on its goal after 208 timesteps"), std::string::npos)
      << r.error;
}

}  // namespace
}  // namespace smart::planning
