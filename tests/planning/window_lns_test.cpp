#include "smart/planning/window_lns.hpp"

#include <gtest/gtest.h>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "smart/planning/task_generator.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/window_checks.hpp"

namespace smart::planning {
namespace {

using grid::Cell;

grid::Grid warehouse() {
  const auto dir = test::benchmarks_dir() / "maps";
  return grid::parse_map(grid::read_text_file(dir / "warehouse-10-20-10-2-1.map", "map"), "w");
}

// Distance left through a robot's first errand at the window's end (0 once reached).
int left(DistanceCache& dist, const std::vector<Cell>& path, const std::vector<Cell>& goals) {
  if (goals.empty() || std::find(path.begin(), path.end(), goals[0]) != path.end()) return 0;
  return dist.distance(path.back(), goals[0]);
}

// 300 robots on the warehouse, windows of 10 steps of which 5 are kept (a commit cut), a new
// task as each is reached: every improved window is conflict-free, no robot ends a window
// farther from its errand than PIBT left it, and the fleet reaches more goals than with PIBT
// alone on the same tasks.
TEST(WindowLns, WindowsStayConflictFreeAndEveryRobotEndsNoFartherThanPibtLeftIt) {
  const auto g = warehouse();
  const std::size_t robots = 300;
  const auto tasks = generate_tasks(g, {}, 20 * robots, 1, 12);
  auto run = [&](bool improve) {
    DistanceCache dist(g);
    TableHeuristic heuristic(dist);
    Pibt pibt(g, heuristic, 3);
    WindowLns lns(g, dist);
    auto at = random_starts(g, robots, 11);
    std::vector<std::size_t> task(robots);
    for (std::size_t r = 0; r < robots; ++r) task[r] = r;
    std::size_t next_task = robots, done = 0;
    for (int window = 0; window < 60; ++window) {
      WindowRequest req{at, std::vector<std::vector<Cell>>(robots), 10};
      for (std::size_t r = 0; r < robots; ++r) req.goals[r] = tasks[task[r]].errands;
      auto w = pibt.plan(req);
      if (improve) {
        const auto before = w;
        lns.improve(req, w);
        test::expect_valid_window(g, w);
        if (::testing::Test::HasFatalFailure()) return done;
        for (std::size_t r = 0; r < robots; ++r) {
          EXPECT_LE(left(dist, w.paths[r], req.goals[r]), left(dist, before.paths[r], req.goals[r]))
              << "robot " << r << " window " << window;
        }
      }
      for (std::size_t r = 0; r < robots; ++r) {
        at[r] = w.paths[r][5];
        const auto& p = w.paths[r];
        if (std::find(p.begin(), p.begin() + 6, tasks[task[r]].errands[0]) != p.begin() + 6) {
          task[r] = next_task++;
          ++done;
        }
      }
    }
    if (improve) {
      EXPECT_GT(lns.stats().improved, 0u);
    }
    return done;
  };
  const auto pibt = run(false), improved = run(true);
  EXPECT_GT(improved, pibt + pibt / 10) << "PIBT " << pibt << " goals, improved " << improved;
}

// A greedy window sent robot 0 round the wall's long side, where it ends 3 cells short of its
// goal, because robot 1 (no errand, its path kept) crosses the short side's first cell at t = 1.
// Planned against robot 1's whole path, robot 0 waits a step and follows it the short way.
TEST(WindowLns, ARobotWaitsAStepRatherThanDetour) {
  const auto g =
      grid::parse_map("type octile\nheight 3\nwidth 7\nmap\n.......\n.@@@@@.\n.......\n", "c");
  DistanceCache dist(g);
  WindowLns lns(g, dist);
  const WindowRequest req{{{0, 1}, {1, 0}}, {{{6, 0}}, {}}, 9};
  WindowPlan w;
  w.paths = {{{0, 1}, {0, 2}, {1, 2}, {2, 2}, {3, 2}, {4, 2}, {5, 2}, {5, 2}, {5, 2}, {5, 2}},
             {{1, 0}, {0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}, {6, 0}, {6, 1}, {6, 2}}};
  const auto other = w.paths[1];
  lns.improve(req, w);
  test::expect_valid_window(g, w);
  EXPECT_EQ(w.paths[0][1], (Cell{0, 1}));  // waits for (0,0) to clear
  EXPECT_EQ(w.paths[0].back(), (Cell{6, 0}));
  EXPECT_EQ(w.paths[1], other);
  EXPECT_EQ(lns.stats().improved, 1u);
  EXPECT_EQ(lns.stats().saved, 3);
}

TEST(WindowLns, LeavesAWindowThatCannotBeBetterAsItIs) {
  const auto g = grid::parse_map("type octile\nheight 1\nwidth 5\nmap\n.....\n", "c");
  DistanceCache dist(g);
  WindowLns lns(g, dist);
  const WindowRequest req{{{0, 0}, {4, 0}}, {{{2, 0}}, {}}, 3};
  WindowPlan w;
  w.paths = {{{0, 0}, {1, 0}, {2, 0}, {2, 0}}, {{4, 0}, {4, 0}, {4, 0}, {4, 0}}};
  const auto before = w.paths;
  lns.improve(req, w);
  EXPECT_EQ(w.paths, before);
  EXPECT_EQ(w.moves, 2u);
  EXPECT_EQ(lns.stats().replanned, 1u);  // robot 1 has no errand: left as it is
  EXPECT_EQ(lns.stats().improved, 0u);
}

// A second errand's distance table is a BFS over the map: made only for a robot whose first
// errand is within the window's reach (6 s a window for LoRR's 2500-robot warehouse otherwise).
TEST(WindowLns, LooksAtASecondErrandOnlyWhenTheFirstIsWithinReach) {
  const auto g = planning::generate_empty_map(12, 1);
  DistanceCache dist(g);
  WindowLns lns(g, dist);
  WindowPlan far;
  far.paths = {std::vector<Cell>(4, Cell{0, 0})};
  lns.improve({{{0, 0}}, {{{11, 0}, {5, 0}}}, 3}, far);
  EXPECT_EQ(dist.computed(), 1u);  // the first errand's only: 11 steps away, the window is 3
  EXPECT_EQ(far.paths[0].back(), (Cell{3, 0}));
  WindowPlan near;
  near.paths = {std::vector<Cell>(6, Cell{0, 0})};
  lns.improve({{{0, 0}}, {{{2, 0}, {0, 0}}}, 5}, near);
  EXPECT_EQ(dist.computed(), 3u);
  EXPECT_EQ(near.paths[0], (std::vector<Cell>{{0, 0}, {1, 0}, {2, 0}, {1, 0}, {0, 0}, {0, 0}}));
}

TEST(WindowLns, RefusesWindowsThatDoNotFit) {
  const auto g = grid::parse_map("type octile\nheight 1\nwidth 4\nmap\n....\n", "c");
  DistanceCache dist(g);
  WindowLns lns(g, dist);
  WindowPlan w;
  w.paths = {{{0, 0}, {1, 0}}};
  EXPECT_THROW(lns.improve({{{0, 0}}, {{{3, 0}}}, 2}, w), std::invalid_argument);  // too short
  EXPECT_THROW(lns.improve({{{1, 0}}, {{{3, 0}}}, 1}, w), std::invalid_argument);  // not its start
  EXPECT_THROW(lns.improve({{{0, 0}, {2, 0}}, {{}, {}}, 1}, w), std::invalid_argument);
  try {
    lns.improve({{{0, 0}}, {{{3, 0}}}, 3}, w);
    FAIL() << "a path of the wrong length was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("robot 0's path"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smart::planning
