#include "smart/lifelong/task_manager.hpp"

#include <gtest/gtest.h>

namespace smart::lifelong {
namespace {

using grid::Cell;

std::vector<grid::Task> two_tasks() { return {{0, 2, {{5, 0}, {9, 0}}}, {1, 3, {{1, 0}}}}; }

std::vector<std::string> kinds(const std::vector<results::EventRow>& events) {
  std::vector<std::string> out;
  out.reserve(events.size());
  for (const auto& e : events) out.push_back(e.event);
  return out;
}

TEST(TaskManager, RevealsThePoolCyclingTheSource) {
  GreedyNearestScheduler s;
  TaskManager tm(two_tasks(), 0, 3, s);  // no robots: nothing assigned
  tm.update(0, {});
  EXPECT_EQ(tm.revealed(), 3u);
  const auto open = tm.unfinished();
  ASSERT_EQ(open.size(), 3u);
  EXPECT_EQ(open[2].task, 2u);
  EXPECT_EQ(open[2].source_task, 0u);  // task 2 repeats source task 0 (LoRR: id mod N)
}

TEST(TaskManager, AssignsNearestAndNeverReassigns) {
  GreedyNearestScheduler s;
  TaskManager tm(two_tasks(), 2, 2, s);
  tm.update(0, {{0, 0}, {6, 0}});
  // Robot 0 (at x=0) takes the nearest first errand (x=1, task 1); robot 1 the other.
  EXPECT_EQ(tm.task_of(0), 1u);
  EXPECT_EQ(tm.task_of(1), 0u);
  tm.update(1, {{6, 0}, {0, 0}});  // robots moved: nothing changes hands
  EXPECT_EQ(tm.task_of(0), 1u);
  EXPECT_EQ(tm.task_of(1), 0u);
}

TEST(TaskManager, ErrandsInOrderOpenThenFinishAndFreeTheRobot) {
  GreedyNearestScheduler s;
  TaskManager tm({{0, 2, {{5, 0}, {9, 0}}}}, 1, 1, s);
  tm.update(0, {{0, 0}});
  EXPECT_EQ(tm.goals(0), (std::vector<Cell>{{5, 0}, {9, 0}}));
  EXPECT_FALSE(tm.on_reached(0, {9, 0}, 1));  // not the next errand
  EXPECT_TRUE(tm.on_reached(0, {5, 0}, 2));
  EXPECT_EQ(tm.goals(0), (std::vector<Cell>{{9, 0}}));
  EXPECT_TRUE(tm.on_reached(0, {9, 0}, 5));
  EXPECT_FALSE(tm.task_of(0).has_value());
  EXPECT_EQ(tm.finished(), 1u);
  const auto done = tm.take_finished();
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].opened_s, 2.0);
  EXPECT_EQ(done[0].finished_s, 5.0);
  EXPECT_EQ(done[0].cells, (std::vector<std::pair<int32_t, int32_t>>{{5, 0}, {9, 0}}));
  const auto events = tm.take_events();
  EXPECT_EQ(kinds(events),
            (std::vector<std::string>{"revealed", "assigned", "opened", "finished"}));
  EXPECT_EQ(events[0].detail, "5 0;9 0");  // where the revealed task is (regression: empty)
  tm.update(6, {{9, 0}});  // a new task is revealed (task 1 repeats source 0) and assigned
  EXPECT_EQ(tm.task_of(0), 1u);
}

TEST(TaskManager, ARobotStandingOnItsErrandsDoesThem) {
  GreedyNearestScheduler s;
  TaskManager tm({{0, 2, {{3, 0}, {3, 0}}}}, 1, 1, s);
  tm.update(0, {{3, 0}});
  tm.reached_while_idle(0, {3, 0}, 0);
  EXPECT_EQ(tm.finished(), 1u);
}

TEST(TaskManager, RefusesAnEmptySource) {
  GreedyNearestScheduler s;
  EXPECT_THROW(TaskManager({}, 1, 1, s), std::invalid_argument);
  EXPECT_THROW(TaskManager(two_tasks(), 1, 0, s), std::invalid_argument);
}

}  // namespace
}  // namespace smart::lifelong
