// One-shot plans by LaCAM (lacam.hpp): valid, every robot home, deterministic per seed; solved
// where PIBT alone cycles; an unsolvable instance searched to the end; budgets end in errors.
#include "smart/planning/lacam.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "planning/plan_checks.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/pibt_plan.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::planning {
namespace {

using namespace grid;  // the vocabulary the planners work in

// A corridor of five cells with a pocket under its middle; two robots swap ends. PIBT alone
// never solves it: the robot ahead is pushed back and forth (checked below, every seed tried).
Grid pocket_corridor() { return smart::test::grid_of({".....", "@@.@@"}); }
Scenario swap_ends() {
  Scenario s;
  s.agents = {{{0, 0}, {4, 0}, 4}, {{4, 0}, {0, 0}, 4}};
  return s;
}

TEST(Lacam, SwapsTwoRobotsThroughAPocketWherePibtAloneCycles) {
  const auto g = pocket_corridor();
  const auto s = swap_ends();
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    EXPECT_FALSE(plan_pibt(g, s, {seed, 16, 320}).solved) << "seed " << seed;
    for (const bool swap : {false, true}) {
      LacamStats stats;
      LacamOptions o;
      o.seed = seed;
      o.swap = swap;
      const auto r = plan_lacam(g, s, o, &stats);
      expect_valid_plan(g, s, r, swap ? "pocket, swap" : "pocket");
      // One robot steps into the pocket and back out: the plan lasts at least 6 steps.
      EXPECT_GE(std::max(r.plan.paths[0].steps.size(), r.plan.paths[1].steps.size()), 7u);
      if (swap) {  // the robot ahead pulls the other into the pocket: no step taken back
        EXPECT_EQ(stats.expansions + 1, stats.configurations) << "seed " << seed;
      } else {  // plain PIBT steps lead back: the low-level search finds the way
        EXPECT_GT(stats.expansions, stats.configurations) << "seed " << seed;
      }
    }
  }
}

TEST(Lacam, ACorridorWithoutAPocketIsSearchedToTheEndAndReportedUnsolvable) {
  const auto g = smart::test::grid_of({"...."});
  Scenario s;
  s.agents = {{{0, 0}, {3, 0}, 3}, {{3, 0}, {0, 0}, 3}};
  const auto r = plan_lacam(g, s, {1});
  EXPECT_FALSE(r.solved);
  EXPECT_EQ(r.error, "no plan exists: every configuration reachable was searched");
}

TEST(Lacam, AConfigurationBudgetEndsTheSearchWithAnError) {
  const auto g = smart::test::grid_of({"......"});
  Scenario s;
  s.agents = {{{0, 0}, {5, 0}, 5}, {{5, 0}, {0, 0}, 5}};
  LacamOptions o;
  o.max_configurations = 3;
  const auto r = plan_lacam(g, s, o);
  EXPECT_FALSE(r.solved);
  EXPECT_NE(r.error.find("memory budget reached after"), std::string::npos) << r.error;
}

TEST(Lacam, EveryRobotEndsOnItsGoalOnOpenMapsAndInAMaze) {
  const auto random = generate_random_map(30, 30, 0.15, 2);
  expect_valid_plan(random, generate_scenario(random, 250, 2, "random"),
                    plan_lacam(random, generate_scenario(random, 250, 2, "random"), {2}), "random");
  const auto empty = generate_empty_map(16, 16);
  expect_valid_plan(empty, generate_scenario(empty, 150, 3, "empty"),
                    plan_lacam(empty, generate_scenario(empty, 150, 3, "empty"), {3}), "empty");
  // One-wide corridors: robots pass each other only at forks (swaps, pibt_step.hpp).
  const auto maze = generate_maze(21, 21, 1, 4);
  expect_valid_plan(maze, generate_scenario(maze, 30, 4, "maze"),
                    plan_lacam(maze, generate_scenario(maze, 30, 4, "maze"), {4}), "maze");
}

TEST(Lacam, IsTheSamePlanForTheSameSeed) {
  const auto g = generate_random_map(24, 24, 0.1, 5);
  const auto scen = generate_scenario(g, 120, 5, "random");
  expect_seeded([&](uint64_t seed) { return plan_lacam(g, scen, {seed}); }, 5);
}

// The first `robots` of a MovingAI scenario from the shared benchmarks.
std::pair<Grid, Scenario> benchmark(const std::string& name, std::size_t robots) {
  const auto dir = smart::test::benchmarks_dir();
  const auto map = (dir / "maps" / (name + ".map")).string();
  const auto scen_file = (dir / "scens" / (name + "-random-1.scen")).string();
  auto scen = parse_scen(read_text_file(scen_file, "scenario"), scen_file, robots);
  EXPECT_EQ(scen.agents.size(), robots) << scen_file;
  return {parse_map(read_text_file(map, "map"), map), std::move(scen)};
}

TEST(Lacam, AThousandRobotsOfAMovingAiScenarioWherePibtAloneDoesNotFinish) {
  const auto [g, scen] = benchmark("random-64-64-10", 1000);
  EXPECT_FALSE(plan_pibt(g, scen, {1}).solved);
  expect_valid_plan(g, scen, plan_lacam(g, scen, {1}), "random-64-64-10, 1000 robots");
}

TEST(Lacam, AThousandRobotsInOneWideAislesWithSwaps) {
  const auto [g, scen] = benchmark("warehouse-10-20-10-2-1", 1000);
  expect_valid_plan(g, scen, plan_lacam(g, scen, {1}), "warehouse-10-20-10-2-1, 1000 robots");
}

// What plan_lacam refuses `agents` with (empty when it plans them).
std::string refusal(const Grid& g, std::vector<ScenAgent> agents) {
  Scenario s;
  s.agents = std::move(agents);
  try {
    plan_lacam(g, s, {1});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Lacam, AScenarioThatDoesNotFitIsRefusedNamingTheRobot) {
  const auto g = smart::test::grid_of({"..@", "..."});
  EXPECT_EQ(refusal(g, {{{0, 0}, {2, 0}, 2}}),
            "LaCAM: robot 0: start (x=0,y=0) or goal (x=2,y=0) is not a free cell");
  EXPECT_EQ(refusal(g, {{{0, 0}, {2, 1}, 3}, {{1, 0}, {2, 1}, 2}}),
            "LaCAM: robot 1 has the goal (x=2,y=1) of robot 0: goals must differ");
  EXPECT_EQ(refusal(g, {{{0, 0}, {2, 1}, 3}, {{0, 0}, {1, 1}, 2}}),
            "LaCAM: robot 1 starts on (x=0,y=0) as robot 0 does");
}

}  // namespace
}  // namespace smart::planning
