// What every one-shot plan of the built-in planners must be (pibt_plan_test, lacam_test):
// solved, valid for its scenario (plan_validator), every robot on its goal at its path's end, its
// SMART text read back into an acyclic ADG (half cells: robots follow one another and move round
// cycles, SMART §IV-B).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/plan_reader.hpp"
#include "smart/monitor/plan_validator.hpp"
#include "smart/planning/planner.hpp"

namespace smart::planning {

inline void expect_valid_plan(const grid::Grid& g, const grid::Scenario& scen,
                              const PlannerResult& r, const char* what) {
  ASSERT_TRUE(r.solved) << what << ": " << r.error;
  const auto problems = monitor::validate_plan(r.plan, g, &scen);
  ASSERT_TRUE(problems.empty()) << what << ": " << problems[0].to_string();
  ASSERT_EQ(r.plan.paths.size(), scen.agents.size()) << what;
  for (std::size_t i = 0; i < scen.agents.size(); ++i) {
    EXPECT_EQ(r.plan.paths[i].steps.back().cell, scen.agents[i].goal) << what << " robot " << i;
  }
  const auto back = monitor::parse_plan(to_smart_plan_text(r.plan), what,
                                        {grid::PlanFormat::kAuto, std::nullopt});
  const auto actions = monitor::build_actions(back);
  std::vector<grid::Problem> adg_problems;
  const auto adg = monitor::build_adg(actions, g, what, adg_problems);
  EXPECT_TRUE(adg_problems.empty()) << what;
  EXPECT_TRUE(monitor::check_acyclic(adg, actions, what).empty()) << what;
}

// A planner(seed) gives the same plan text for the same seed and another for the next seed (the
// seed breaks ties).
template <typename Planner>
void expect_seeded(Planner plan, uint64_t seed) {
  const auto a = to_smart_plan_text(plan(seed).plan);
  EXPECT_EQ(a, to_smart_plan_text(plan(seed).plan));
  EXPECT_NE(a, to_smart_plan_text(plan(seed + 1).plan)) << "the seed breaks ties";
}

}  // namespace smart::planning
