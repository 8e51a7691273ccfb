#include "smart/planning/pibt.hpp"

#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/guide_paths.hpp"
#include "smart/planning/task_generator.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/window_checks.hpp"

namespace smart::planning {
namespace {

using grid::Cell;

void expect_valid(const grid::Grid& g, const WindowPlan& w) { test::expect_valid_window(g, w); }

grid::Grid warehouse() {
  const auto dir = test::benchmarks_dir() / "maps";
  return grid::parse_map(grid::read_text_file(dir / "warehouse-10-20-10-2-1.map", "map"), "w");
}

// 40 windows of 10 steps for 300 robots on the warehouse, a new task as each is reached.
void keep_reaching_goals(const grid::Grid& g, GoalHeuristic& heuristic) {
  Pibt pibt(g, heuristic, 3);
  const std::size_t robots = 300;
  auto at = random_starts(g, robots, 11);
  const auto tasks = generate_tasks(g, {}, 4 * robots, 1, 12);
  std::vector<std::size_t> task(robots);
  for (std::size_t r = 0; r < robots; ++r) task[r] = r;
  std::size_t next_task = robots, done = 0;
  std::vector<std::size_t> done_by(robots, 0);
  for (int window = 0; window < 40; ++window) {
    WindowRequest req{at, std::vector<std::vector<Cell>>(robots), 10};
    for (std::size_t r = 0; r < robots; ++r) req.goals[r] = tasks[task[r]].errands;
    const auto w = pibt.plan(req);
    expect_valid(g, w);
    if (::testing::Test::HasFatalFailure()) return;
    for (std::size_t r = 0; r < robots; ++r) {
      at[r] = w.paths[r].back();
      bool reached = false;
      for (const Cell c : w.paths[r]) reached = reached || c == tasks[task[r]].errands[0];
      if (reached && next_task < tasks.size()) {
        task[r] = next_task++;
        ++done_by[r];
        ++done;
      }
    }
  }
  // 400 steps for 300 robots on a 161x63 warehouse: PIBT keeps everyone moving.
  EXPECT_GT(done, robots * 2);
  for (std::size_t r = 0; r < robots; ++r) EXPECT_GE(done_by[r], 1u) << "robot " << r << " starved";
}

TEST(Pibt, WindowsAreConflictFreeAndEveryRobotKeepsReachingGoals) {
  const auto g = warehouse();
  DistanceCache dist(g);
  TableHeuristic tables(dist);
  keep_reaching_goals(g, tables);
}

// The same with a guide path per robot (maps too large for tables): still nobody starves.
TEST(Pibt, GuidePathsKeepEveryRobotReachingGoals) {
  const auto g = warehouse();
  GuidePaths paths(g);
  keep_reaching_goals(g, paths);
}

TEST(Pibt, GuidePathsPlanTheSameOnOneThreadOrTwo) {
  const auto g = warehouse();
  const auto starts = random_starts(g, 200, 21);
  const auto tasks = generate_tasks(g, {}, 200, 2, 22);
  WindowRequest req{starts, {}, 12};
  for (const auto& t : tasks) req.goals.push_back(t.errands);
  GuidePaths one(g, 8, 50, 1), two(g, 8, 50, 2);  // 50 searches a window: some robots wait
  Pibt a(g, one, 4), b(g, two, 4);
  for (int w = 0; w < 5; ++w) {
    const auto pa = a.plan(req), pb = b.plan(req);
    ASSERT_EQ(pa.paths, pb.paths) << "window " << w;
    for (std::size_t r = 0; r < starts.size(); ++r) req.start[r] = pa.paths[r][6];
  }
}

TEST(Pibt, DeterministicForASeed) {
  const auto g = generate_random_map(24, 24, 0.15, 5);
  auto run = [&](uint64_t seed) {
    DistanceCache dist(g);
    TableHeuristic tables(dist);
    Pibt pibt(g, tables, seed);
    const auto starts = random_starts(g, 60, 1);
    const auto tasks = generate_tasks(g, {}, 60, 2, 2);
    WindowRequest req{starts, {}, 15};
    for (const auto& t : tasks) req.goals.push_back(t.errands);
    auto a = pibt.plan(req);
    req.start.clear();
    for (const auto& p : a.paths) req.start.push_back(p.back());
    return std::make_pair(a.paths, pibt.plan(req).paths);
  };
  EXPECT_EQ(run(9), run(9));
  EXPECT_NE(run(9), run(10));
}

TEST(Pibt, ARobotInTheWayIsPushedAside) {
  // A corridor with a side pocket: robot 1 idles in the corridor, robot 0 must pass it. (A
  // robot idling at the dead end of a corridor that is someone's goal cannot be pushed out: PIBT
  // promises reachability in biconnected graphs only, the paper's Theorem 2.)
  const auto g = grid::parse_map("type octile\nheight 2\nwidth 7\nmap\n.......\n@@.@@@@\n", "c");
  DistanceCache dist(g);
  TableHeuristic tables(dist);
  Pibt pibt(g, tables, 1);
  const auto w = pibt.plan({{{0, 0}, {2, 0}}, {{{4, 0}}, {}}, 8});
  expect_valid(g, w);
  EXPECT_EQ(w.paths[0].back(), (Cell{4, 0}));
  EXPECT_EQ(w.paths[1][0], (Cell{2, 0}));
}

TEST(Pibt, RefusesRequestsThatDoNotFit) {
  const auto g = grid::parse_map("type octile\nheight 1\nwidth 4\nmap\n..@.\n", "c");
  DistanceCache dist(g);
  TableHeuristic tables(dist);
  Pibt pibt(g, tables, 1);
  EXPECT_THROW(pibt.plan({{{0, 0}, {0, 0}}, {{}, {}}, 3}), std::invalid_argument);
  EXPECT_THROW(pibt.plan({{{2, 0}}, {{}}, 3}), std::invalid_argument);
  try {
    pibt.plan({{{0, 0}}, {{{3, 0}}}, 3});
    FAIL() << "an unreachable goal was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot reach its goal (x=3,y=0)"), std::string::npos);
  }
}

}  // namespace
}  // namespace smart::planning
