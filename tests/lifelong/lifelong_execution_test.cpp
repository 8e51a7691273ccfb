#include "smart/lifelong/lifelong_execution.hpp"

#include <gtest/gtest.h>

#include "smart/grid/lorr.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/task_generator.hpp"
#include "support/ideal_executor.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::lifelong {
namespace {

struct Outcome {
  uint64_t tasks = 0;
  std::vector<std::string> events;
  uint64_t conflicts = 0;
};

// The supervisor's loop without DDS: ticks of 0.1 s, windows sent up to 8 actions ahead.
Outcome drive(const grid::Grid& g, const std::vector<grid::Cell>& starts,
              std::vector<grid::Task> tasks, LifelongOptions o, double delay_p = 0) {
  LifelongExecution exec(g, starts, std::move(tasks), o);
  test::IdealExecutor ex(g, exec, starts, o.seed, delay_p);
  Outcome out;
  for (int k = 0; !exec.complete(); ++k) {
    const double t = 0.1 * k;
    exec.on_time(t, ex.sent(8));
    ex.tick(t);
    EXPECT_FALSE(exec.deadlocked()) << "t=" << t;
    for (const auto& e : exec.take_events()) {
      out.events.push_back(std::to_string(e.t_s) + " " + e.event + " " + e.detail);
    }
  }
  out.tasks = exec.tasks().finished();
  out.conflicts = ex.conflicts;
  EXPECT_EQ(exec.stats().windows_refused, 0u);
  return out;
}

TEST(LifelongExecution, AGeneratedStreamKeepsFinishingTasks) {
  const auto g = planning::generate_random_map(20, 20, 0.15, 4);
  const auto starts = planning::random_starts(g, 30, 4);
  LifelongOptions o;
  o.duration_s = 60;
  o.seed = 4;
  const auto r = drive(g, starts, planning::generate_tasks(g, {}, 200, 2, 4), o, 0.1);
  EXPECT_EQ(r.conflicts, 0u);
  EXPECT_GT(r.tasks, 30u);  // robots keep working the whole minute
}

TEST(LifelongExecution, TheSameSeedGivesTheSameRun) {
  const auto g = planning::generate_random_map(16, 16, 0.2, 7);
  const auto starts = planning::random_starts(g, 20, 7);
  const auto tasks = planning::generate_tasks(g, {}, 100, 1, 7);
  LifelongOptions o;
  o.duration_s = 30;
  o.seed = 7;
  o.budget_s = 0.3;
  const auto a = drive(g, starts, tasks, o);
  const auto b = drive(g, starts, tasks, o);
  EXPECT_EQ(a.events, b.events);
  EXPECT_GT(a.tasks, 0u);
}

TEST(LifelongExecution, AWindowArrivesOnlyAfterThePlanningBudget) {
  const auto g = planning::generate_empty_map(8, 8);
  LifelongExecution exec(g, {{0, 0}}, {{0, 2, {{7, 7}}}}, {.duration_s = 10, .budget_s = 0.5});
  EXPECT_TRUE(exec.on_time(0.0, {0}).empty());  // planned at 0, charged 0.5 s
  EXPECT_EQ(exec.known(0), 0u);
  EXPECT_TRUE(exec.on_time(0.4, {0}).empty());
  EXPECT_EQ(exec.on_time(0.5, {0}), (std::vector<uint32_t>{0}));
  EXPECT_GT(exec.known(0), 0u);
  EXPECT_FALSE(exec.complete());
  exec.on_time(10, {0});
  EXPECT_TRUE(exec.complete());
}

TEST(LifelongExecution, TheSmallestLorrExampleRunsSafely) {
  // The 40-robot maze problem of the LoRR 2026 Start-Kit, a minute of ideal execution.
  const auto p = grid::load_lorr_problem(test::benchmarks_dir() / "lorr-2026" / "maze.domain" /
                                         "maze-example_40.json");
  LifelongOptions o;
  o.duration_s = 60;
  o.task_pool = static_cast<std::size_t>(p.spec.num_tasks_reveal * double(p.starts.size()));
  const auto r = drive(p.grid, p.starts, p.tasks, o, 0.05);
  EXPECT_EQ(r.conflicts, 0u);
  EXPECT_GT(r.tasks, 0u);
}

// Regression: with switching, a cut that drops the robots following a held entry frees it, and
// the window's append sends it; the robot was left out of the robots the append reported when
// the window gave it no new actions (it waits where it stands), so a monitor told it nothing
// until its next event. Every robot whose sent actions grew at on_time is among the robots it
// returns.
TEST(LifelongExecution, ARobotSentAnActionWhenAWindowArrivesIsReported) {
  const auto g = planning::generate_random_map(16, 16, 0.2, 5);
  const auto starts = planning::random_starts(g, 40, 5);
  LifelongOptions o;
  o.duration_s = 60;
  o.seed = 5;
  o.switching = monitor::SwitchOptions{2};
  LifelongExecution exec(g, starts, planning::generate_tasks(g, {}, 400, 1, 5), o);
  test::IdealExecutor ex(g, exec, starts, o.seed, 0.3);
  std::size_t without_new_actions = 0;  // the case of the bug: sent an old action
  for (int k = 0; !exec.complete(); ++k) {
    const double t = 0.1 * k;
    std::vector<uint32_t> sent(exec.robots()), known(exec.robots());
    for (uint32_t r = 0; r < sent.size(); ++r) {
      sent[r] = exec.enqueued(r);
      known[r] = exec.known(r);
    }
    const auto changed = exec.on_time(t, ex.sent(8));
    for (uint32_t r = 0; r < sent.size(); ++r) {
      if (exec.enqueued(r) == sent[r]) continue;
      if (exec.known(r) == known[r]) ++without_new_actions;
      EXPECT_TRUE(std::ranges::find(changed, r) != changed.end()) << "robot " << r << " t=" << t;
    }
    ex.tick(t);
  }
  EXPECT_GT(without_new_actions, 0u);
}

}  // namespace
}  // namespace smart::lifelong
