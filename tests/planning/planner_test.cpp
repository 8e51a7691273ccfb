#include "smart/planning/planner.hpp"

#include <gtest/gtest.h>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/plan_reader.hpp"
#include "smart/monitor/plan_validator.hpp"
#include "smart/planning/generators.hpp"

namespace smart::planning {
namespace {

using namespace grid;  // the vocabulary the planners work in
using monitor::build_actions;
using monitor::build_adg;
using monitor::check_acyclic;
using monitor::parse_plan;
using monitor::validate_plan;

void expect_valid_plan(const Grid& g, std::size_t robots, uint64_t seed, const char* what) {
  const auto scen = generate_scenario(g, robots, seed, what);
  const auto r = plan_prioritized(g, scen, {seed, 20, 60});
  ASSERT_TRUE(r.solved) << what << ": " << r.error;
  const auto problems = validate_plan(r.plan, g, &scen);
  ASSERT_TRUE(problems.empty()) << what << ": " << problems[0].to_string();
  // The text form reads back as the same plan and builds an acyclic ADG.
  const auto back =
      parse_plan(to_smart_plan_text(r.plan), what, {PlanFormat::kAuto, std::nullopt});  // declared
  EXPECT_TRUE(validate_plan(back, g, &scen).empty());
  const auto actions = build_actions(back);
  std::vector<Problem> adg_problems;
  const auto adg = build_adg(actions, g, what, adg_problems);
  EXPECT_TRUE(adg_problems.empty());
  EXPECT_TRUE(check_acyclic(adg, actions, what).empty());
}

TEST(Planner, SolvesEveryMapKind) {
  expect_valid_plan(generate_warehouse({4, 3, 5, 2, 1, 3}), 30, 1, "warehouse");
  expect_valid_plan(generate_random_map(30, 30, 0.2, 2), 40, 2, "random");
  expect_valid_plan(generate_empty_map(16, 16), 60, 3, "empty");
  expect_valid_plan(generate_maze(31, 31, 3, 4), 15, 4, "maze");
}

TEST(Planner, ThreeHundredRobotsOnTheWarehouse) {
  expect_valid_plan(generate_warehouse({}), 300, 7, "warehouse-300");
}

TEST(Planner, UnreachableGoalIsReported) {
  const Grid g(3, 1, {0, 1, 0}, "split");
  Scenario s;
  s.agents = {{{0, 0}, {2, 0}, 2}};
  const auto r = plan_prioritized(g, s, {});
  EXPECT_FALSE(r.solved);
  EXPECT_NE(r.error.find("cannot reach"), std::string::npos);
}

TEST(Planner, ParksOnlyWhereNobodyPassesLater) {
  // A corridor: robot 0 must go past robot 1's goal cell, so robot 1 must arrive after it.
  const Grid g(5, 1, {0, 0, 0, 0, 0}, "corridor");
  Scenario s;
  s.agents = {{{0, 0}, {4, 0}, 2}, {{1, 0}, {2, 0}, 3}};
  const auto r = plan_prioritized(g, s, {});
  // In a 1-wide corridor robot 0 cannot overtake robot 1; it must fail cleanly, not loop.
  EXPECT_FALSE(r.solved);
  Scenario ok;
  ok.agents = {{{1, 0}, {4, 0}, 2}, {{0, 0}, {3, 0}, 3}};
  const auto r2 = plan_prioritized(g, ok, {});
  ASSERT_TRUE(r2.solved) << r2.error;
  EXPECT_TRUE(validate_plan(r2.plan, g, &ok).empty());
}

// plan_from_timesteps drops a robot's trailing waits; timesteps_of gives its cells back up to
// its arrival.
TEST(Planner, TimestepsOfUndoesPlanFromTimesteps) {
  const std::vector<std::vector<grid::Cell>> paths{{{0, 0}, {1, 0}, {1, 0}},
                                                   {{2, 2}, {2, 2}, {2, 1}}};
  const std::vector<std::vector<grid::Cell>> back{{{0, 0}, {1, 0}}, {{2, 2}, {2, 2}, {2, 1}}};
  EXPECT_EQ(timesteps_of(plan_from_timesteps(paths, "t")), back);
}

}  // namespace
}  // namespace smart::planning
