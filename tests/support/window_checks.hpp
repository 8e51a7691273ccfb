// Contract: checks of a lifelong planner's window (planning/pibt.hpp's WindowPlan) shared by
// the planners' tests: every path as long, on free cells, moving to a 4-neighbour or waiting,
// with no vertex and no swap conflict (following is allowed: SMART §IV-B).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "smart/grid/grid.hpp"
#include "smart/planning/pibt.hpp"

namespace smart::test {

inline void expect_valid_window(const grid::Grid& g, const planning::WindowPlan& w) {
  const auto manhattan = [](grid::Cell a, grid::Cell b) {
    return std::abs(a.x - b.x) + std::abs(a.y - b.y);
  };
  const std::size_t steps = w.paths.at(0).size();
  for (std::size_t t = 0; t < steps; ++t) {
    std::set<grid::Cell> at;
    for (std::size_t r = 0; r < w.paths.size(); ++r) {
      ASSERT_EQ(w.paths[r].size(), steps);
      const grid::Cell c = w.paths[r][t];
      ASSERT_TRUE(g.free(c)) << "robot " << r << " t=" << t;
      ASSERT_TRUE(at.insert(c).second) << "vertex conflict at t=" << t << " robot " << r;
      if (t == 0) continue;
      ASSERT_LE(manhattan(w.paths[r][t - 1], c), 1) << "jump, robot " << r << " t=" << t;
      for (std::size_t q = 0; q < r; ++q) {
        const bool swap =
            w.paths[q][t] == w.paths[r][t - 1] && w.paths[q][t - 1] == c && c != w.paths[r][t - 1];
        ASSERT_FALSE(swap) << "robots " << q << " and " << r << " swap at t=" << t;
      }
    }
  }
}

}  // namespace smart::test
