// Test support: executes an Execution (monitor/execution.hpp) as robots would, without physics:
// each robot starts its next enqueued action when idle (unless delayed), the action takes 1 to 3
// ticks (seeded), and its finish is reported as cumulative progress. Robots hold the location
// they move to from the start of a move and the one they leave until it ends (SMART §IV-B); a
// location held by two robots at once is a test failure (counted in `conflicts`).
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/monitor/execution.hpp"

namespace smart::test {

class IdealExecutor {
 public:
  IdealExecutor(const grid::Grid& grid, monitor::Execution& exec,
                const std::vector<grid::Cell>& starts, uint64_t seed, double delay_p = 0)
      : grid_(grid),
        exec_(exec),
        rng_(seed),
        delay_p_(delay_p),
        busy_(exec.robots(), 0),
        left_(exec.robots(), 0) {
    for (uint32_t r = 0; r < starts.size(); ++r) hold(grid::HalfCell::of(starts[r]), r);
  }

  // One tick at `time_s`; returns the actions finished in it.
  std::size_t tick(double time_s = 0) {
    std::size_t done = 0;
    for (uint32_t r = 0; r < exec_.robots(); ++r) {
      if (busy_[r] && --left_[r] == 0) {
        const grid::Action a = exec_.action(r, exec_.finished(r));
        if (a.type == grid::ActionType::kMove) release(a.from, r);
        const auto u = exec_.on_progress(r, exec_.finished(r), time_s);
        EXPECT_EQ(u.result, monitor::ProgressResult::kAdvanced) << u.reason;
        busy_[r] = 0;
        ++done;
      }
    }
    for (uint32_t r = 0; r < exec_.robots(); ++r) {
      if (busy_[r] || exec_.enqueued(r) <= exec_.finished(r)) continue;
      if (delay_p_ > 0 && std::bernoulli_distribution(delay_p_)(rng_)) continue;
      const grid::Action& a = exec_.action(r, exec_.finished(r));
      if (a.type == grid::ActionType::kMove) hold(a.to, r);
      busy_[r] = 1;
      left_[r] = 1 + static_cast<int>(rng_() % 3);
    }
    return done;
  }
  // What was sent: as the supervisor sends, at most `cap` enqueued actions ahead.
  std::vector<uint32_t> sent(uint32_t cap) const {
    std::vector<uint32_t> s(exec_.robots());
    for (uint32_t r = 0; r < s.size(); ++r) s[r] = exec_.window(r, cap).end;
    return s;
  }
  uint64_t conflicts = 0;

 private:
  void hold(grid::HalfCell h, uint32_t r) {
    const auto [it, fresh] = held_.try_emplace(grid_.half_index(h), r);
    if (!fresh && it->second != r) {
      ++conflicts;
      ADD_FAILURE() << "robots " << it->second << " and " << r << " hold " << grid::to_string(h);
    }
  }
  void release(grid::HalfCell h, uint32_t r) {
    const auto it = held_.find(grid_.half_index(h));
    ASSERT_TRUE(it != held_.end() && it->second == r)
        << "robot " << r << " left " << grid::to_string(h);
    held_.erase(it);
  }

  const grid::Grid& grid_;
  monitor::Execution& exec_;
  std::mt19937_64 rng_;
  double delay_p_;
  std::vector<uint8_t> busy_;
  std::vector<int> left_;
  std::map<std::size_t, uint32_t> held_;
};

}  // namespace smart::test
