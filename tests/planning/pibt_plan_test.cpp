// One-shot plans by PIBT alone (pibt_plan.hpp): valid, every robot home, deterministic per seed,
// and an honest error where PIBT alone cannot finish.
#include "smart/planning/pibt_plan.hpp"

#include <gtest/gtest.h>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/plan_reader.hpp"
#include "smart/monitor/plan_validator.hpp"
#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

using namespace grid;  // the vocabulary the planners work in

void expect_valid(const Grid& g, std::size_t robots, uint64_t seed, const char* what) {
  const auto scen = generate_scenario(g, robots, seed, what);
  const auto r = plan_pibt(g, scen, {seed});
  ASSERT_TRUE(r.solved) << what << ": " << r.error;
  const auto problems = monitor::validate_plan(r.plan, g, &scen);
  ASSERT_TRUE(problems.empty()) << what << ": " << problems[0].to_string();
  for (std::size_t i = 0; i < robots; ++i) {
    EXPECT_EQ(r.plan.paths[i].steps.back().cell, scen.agents[i].goal) << what << " robot " << i;
  }
  // Its text reads back and builds an acyclic ADG (on half cells: PIBT's robots follow each
  // other and move round cycles, SMART §IV-B).
  const auto back =
      monitor::parse_plan(to_smart_plan_text(r.plan), what, {PlanFormat::kAuto, std::nullopt});
  const auto actions = monitor::build_actions(back);
  std::vector<Problem> adg_problems;
  const auto adg = monitor::build_adg(actions, g, what, adg_problems);
  EXPECT_TRUE(adg_problems.empty());
  EXPECT_TRUE(monitor::check_acyclic(adg, actions, what).empty());
}

TEST(PibtPlan, EveryRobotEndsOnItsGoalOnOpenMaps) {
  expect_valid(generate_random_map(30, 30, 0.1, 2), 80, 2, "random");
  expect_valid(generate_empty_map(16, 16), 100, 3, "empty");
}

TEST(PibtPlan, IsTheSamePlanForTheSameSeed) {
  const auto g = generate_random_map(24, 24, 0.1, 5);
  const auto scen = generate_scenario(g, 60, 5, "random");
  const auto a = to_smart_plan_text(plan_pibt(g, scen, {5}).plan);
  EXPECT_EQ(a, to_smart_plan_text(plan_pibt(g, scen, {5}).plan));
  EXPECT_NE(a, to_smart_plan_text(plan_pibt(g, scen, {6}).plan)) << "the seed breaks ties";
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
