// Property tests over many seeded random valid plans (planning/random_plan.hpp): the ADG is
// acyclic, any execution order the tracker allows never puts two robots in one location and always
// finishes, and the reduced Type-2 edge set implies every edge of the all-pairs rule.
#include "smart/planning/random_plan.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <random>
#include <set>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/execution_tracker.hpp"
#include "smart/monitor/plan_validator.hpp"

namespace smart::monitor {
namespace {
using planning::generate_random_grid;
using planning::generate_random_plan;
using planning::GeneratedInstance;

struct Case {
  Grid grid;
  GeneratedInstance inst;
  ActionPlan actions;
  Adg adg;
};

Case make_case(uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto w = static_cast<int32_t>(6 + rng() % 10), h = static_cast<int32_t>(6 + rng() % 10);
  Case c;
  c.grid = generate_random_grid(w, h, 0.15, seed);
  const std::size_t robots = std::min<std::size_t>(c.grid.free_cells() / 2, 4 + rng() % 40);
  // Lower move probabilities leave more robots waiting, so more 2x2 rotation cycles happen.
  const double move_probability = 0.5 + 0.1 * static_cast<double>(seed % 4);
  c.inst = generate_random_plan(c.grid, {robots, 10 + rng() % 30, seed, move_probability, 0.5});
  c.actions = build_actions(c.inst.plan, static_cast<Heading>(seed % 4));
  std::vector<Problem> problems;
  c.adg = build_adg(c.actions, c.grid, "random", problems);
  EXPECT_TRUE(problems.empty()) << "seed " << seed << ": " << problems[0].to_string();
  return c;
}

constexpr uint64_t kSeeds = 150;

TEST(RandomPlan, IsDeterministicAndValid) {
  const auto grid = generate_random_grid(10, 10, 0.2, 7);
  const auto a = generate_random_plan(grid, {12, 30, 7});
  const auto b = generate_random_plan(grid, {12, 30, 7});
  ASSERT_EQ(a.plan.paths.size(), b.plan.paths.size());
  for (std::size_t r = 0; r < a.plan.paths.size(); ++r) {
    ASSERT_EQ(a.plan.paths[r].steps.size(), b.plan.paths[r].steps.size());
    for (std::size_t k = 0; k < a.plan.paths[r].steps.size(); ++k) {
      EXPECT_EQ(a.plan.paths[r].steps[k].cell, b.plan.paths[r].steps[k].cell);
    }
  }
  EXPECT_TRUE(validate_plan(a.plan, grid, &a.scen).empty());
  EXPECT_THROW(generate_random_plan(grid, {1000, 5, 1}), std::invalid_argument);
}

TEST(RandomPlanProperty, GeneratedPlansAreValidAndIncludeRotationCycles) {
  std::size_t cycles = 0;
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const auto c = make_case(seed);
    const auto problems = validate_plan(c.inst.plan, c.grid, &c.inst.scen);
    ASSERT_TRUE(problems.empty()) << "seed " << seed << ": " << problems[0].to_string();
    cycles += c.inst.rotation_cycles;
  }
  EXPECT_GT(cycles, 30u) << "the generator should exercise rotation cycles";
  std::cout << "rotation cycles over " << kSeeds << " seeds: " << cycles << "\n";
}

TEST(RandomPlanProperty, AdgIsAcyclic) {
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const auto c = make_case(seed);
    const auto cycle = check_acyclic(c.adg, c.actions, "random");
    ASSERT_TRUE(cycle.empty()) << "seed " << seed << ": " << cycle[0].message;
  }
}

// Executes the ADG in a random order the tracker allows: robots start only enqueued actions,
// finish them after random delays and report progress late or cumulatively. A robot moving to
// a location claims it when it starts and releases the one it left when it finishes.
TEST(RandomPlanProperty, AnyAllowedExecutionOrderIsCollisionFreeAndFinishes) {
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const auto c = make_case(seed);
    ExecutionTracker tracker(c.actions, c.adg);
    const auto robots = static_cast<uint32_t>(c.actions.robots());
    std::map<HalfCell, uint32_t> occupied;
    for (uint32_t r = 0; r < robots; ++r) occupied[c.actions.start[r]] = r;
    std::vector<uint32_t> started(robots, 0), done(robots, 0);
    std::mt19937_64 rng(seed * 7919);
    std::size_t steps = 0;
    while (!tracker.complete()) {
      ASSERT_FALSE(tracker.deadlocked()) << "seed " << seed;
      // Candidate moves: start the next enqueued action, finish the running one, report.
      std::vector<std::pair<uint32_t, int>> options;
      for (uint32_t r = 0; r < robots; ++r) {
        if (started[r] == done[r] && started[r] < tracker.enqueued(r)) options.push_back({r, 0});
        if (started[r] > done[r]) options.push_back({r, 1});
        if (done[r] > tracker.finished(r)) options.push_back({r, 2});
      }
      ASSERT_FALSE(options.empty()) << "seed " << seed << ": nothing can happen";
      const auto [r, kind] = options[rng() % options.size()];
      if (kind == 0) {
        const Action& a = c.actions.at(r, started[r]);
        if (a.type == ActionType::kMove) {
          const auto it = occupied.find(a.to);
          ASSERT_TRUE(it == occupied.end() || it->second == r)
              << "seed " << seed << ": robot " << r << " enters " << to_string(a.to)
              << " held by robot " << it->second;
          occupied[a.to] = r;
        }
        ++started[r];
      } else if (kind == 1) {
        const Action& a = c.actions.at(r, done[r]);
        if (a.type == ActionType::kMove) occupied.erase(a.from);
        ++done[r];
      } else {
        // Report everything done so far (cumulative), occasionally a stale duplicate first.
        if (tracker.finished(r) > 0 && rng() % 4 == 0) {
          ASSERT_EQ(tracker.on_progress(r, tracker.finished(r) - 1).result,
                    ExecutionTracker::Result::kStale);
        }
        ASSERT_EQ(tracker.on_progress(r, done[r] - 1).result, ExecutionTracker::Result::kAdvanced);
      }
      ASSERT_LT(++steps, 1'000'000u);
    }
    for (uint32_t r = 0; r < robots; ++r) {
      const auto goal = HalfCell::of(c.inst.scen.agents[r].goal);
      ASSERT_EQ(occupied.at(goal), r) << "seed " << seed;
    }
  }
}

// The all-pairs rule (Hönig et al.): for every location, every earlier visitor's leaving action
// precedes every later visitor's entering action. Recomputed here by brute force.
TEST(RandomPlanProperty, ReducedEdgesImplyTheAllPairsOrder) {
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    const auto c = make_case(seed);
    struct Visit {
      uint32_t robot;
      double arrive;
      int64_t enter, leave;  // node ids, -1 for start / parked
    };
    std::map<HalfCell, std::vector<Visit>> visits;
    for (uint32_t r = 0; r < c.actions.robots(); ++r) {
      Visit cur{r, -1, -1, -1};
      HalfCell at = c.actions.start[r];
      for (uint32_t s = 0; s < c.actions.count(r); ++s) {
        const Action& a = c.actions.at(r, s);
        if (a.type != ActionType::kMove) continue;
        cur.leave = c.actions.offset[r] + s;
        visits[at].push_back(cur);
        at = a.to;
        cur = {r, a.end_time, static_cast<int64_t>(c.actions.offset[r] + s), -1};
      }
      visits[at].push_back(cur);
    }
    const std::size_t n = c.adg.nodes();
    auto reachable = [&](uint32_t from, uint32_t to) {
      std::vector<uint8_t> seen(n, 0);
      std::vector<uint32_t> stack{from};
      while (!stack.empty()) {
        const uint32_t u = stack.back();
        stack.pop_back();
        if (u == to) return true;
        if (seen[u]) continue;
        seen[u] = 1;
        const Action& a = c.actions.actions[u];
        if (a.seq + 1 < c.actions.count(a.robot)) stack.push_back(u + 1);
        for (uint32_t i = c.adg.out_begin[u]; i < c.adg.out_begin[u + 1]; ++i) {
          stack.push_back(c.adg.out[i]);
        }
      }
      return false;
    };
    std::size_t all_pairs = 0;
    for (const auto& [loc, vs] : visits) {
      for (const auto& p : vs) {
        for (const auto& q : vs) {
          if (p.robot == q.robot || !(p.arrive < q.arrive)) continue;
          ++all_pairs;
          ASSERT_GE(p.leave, 0) << "seed " << seed;
          ASSERT_GE(q.enter, 0) << "seed " << seed;
          ASSERT_TRUE(reachable(static_cast<uint32_t>(p.leave), static_cast<uint32_t>(q.enter)))
              << "seed " << seed << " at " << to_string(loc) << ": robot " << p.robot
              << " before robot " << q.robot << " is not implied";
        }
      }
    }
    EXPECT_EQ(all_pairs, c.adg.stats.type2_all_pairs) << "seed " << seed;
    EXPECT_LE(c.adg.stats.type2, all_pairs);
  }
}

}  // namespace
}  // namespace smart::monitor
