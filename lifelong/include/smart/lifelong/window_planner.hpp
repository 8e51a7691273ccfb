// Contract: where a lifelong run's windows are planned. The run (lifelong_execution.hpp) submits
// one request at a time (every robot's commit-cut cell and its errands left) and polls for the
// answer; poll() never blocks, so the run goes on while a planner works.
// - BuiltinPlanner plans inside submit() with PIBT (planning/pibt.hpp) and its distance tables,
//   then, if asked (`lns_passes`), makes PIBT's window better one robot at a time
//   (planning/window_lns.hpp): pure and deterministic; the wall clock it may be given only
//   measures it (lock-step runs).
// - ThreadedPlanner runs another planner's submit() on a worker thread (real-time runs: the
//   monitor keeps dispatching and recording while the window is planned; issue 27 item 5). It
//   owns the inner planner; nothing else touches it while a request is outstanding.
// - FallbackPlanner asks a first planner (e.g. an external one, tools/pipe_planner.hpp) and, when
//   it refuses, plans the window with a second (the built-in one: `--planner-fallback builtin`);
//   the first's reason travels in `replaced`. Both must answer within submit() (wrap the whole in
//   a ThreadedPlanner for real time).
// A planner that fails (PIBT refuses a request it cannot fit) answers with `error` set; the run
// records it as a refused window and robots stop safely at the cut.
#pragma once

#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/distance_cache.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "smart/planning/pibt.hpp"
#include "smart/planning/window_lns.hpp"

namespace smart::lifelong {

struct PlannedWindow {
  std::vector<std::vector<grid::Cell>> paths;  // per robot: window_steps + 1 cells, [0] = start
  std::string error;                           // non-empty: no window (why)
  double wall_ms = 0;                          // the planner's own time, if it measured it
  std::size_t distance_tables = 0;             // the planner's distance tables after the call
  std::string heuristic;                       // what ranks its moves (e.g. "guide paths")
  double heuristic_mb = 0;                     // the memory its heuristic holds
  std::string replaced;  // non-empty: another planner's window was refused (why) and this one
                         // stands in for it
};

class WindowPlanner {
 public:
  virtual ~WindowPlanner() = default;
  // Starts planning; the previous answer must have been polled (one request at a time).
  virtual void submit(planning::WindowRequest request) = 0;
  // The answer to the last request once it is there; empty while it is being planned.
  virtual std::optional<PlannedWindow> poll() = 0;
};

struct BuiltinPlannerOptions {
  double distance_budget_mb = 1024;  // distance tables (planning/distance_cache.hpp)
  uint64_t seed = 1;
  planning::HeuristicKind heuristic = planning::HeuristicKind::kAuto;
  std::size_t robots = 0;  // for kAuto (planning/goal_heuristic.hpp) and the tables kept
  int lns_passes = 0;      // rounds of planning/window_lns.hpp over PIBT's window; 0: none
};

class BuiltinPlanner final : public WindowPlanner {
 public:
  // `wall_ms`: a clock in ms that measures each call; empty: not measured.
  BuiltinPlanner(const grid::Grid& grid, const BuiltinPlannerOptions& options,
                 std::function<double()> wall_ms = {});
  void submit(planning::WindowRequest request) override;
  std::optional<PlannedWindow> poll() override;

 private:
  std::function<double()> wall_ms_;
  planning::DistanceCache distances_;
  std::unique_ptr<planning::GoalHeuristic> heuristic_;
  planning::Pibt pibt_;
  int lns_passes_;
  planning::WindowLns lns_;
  std::optional<PlannedWindow> answer_;
};

class FallbackPlanner final : public WindowPlanner {
 public:
  FallbackPlanner(std::unique_ptr<WindowPlanner> first, std::unique_ptr<WindowPlanner> second);
  void submit(planning::WindowRequest request) override;
  std::optional<PlannedWindow> poll() override;

 private:
  std::unique_ptr<WindowPlanner> first_, second_;
  std::optional<PlannedWindow> answer_;
};

class ThreadedPlanner final : public WindowPlanner {
 public:
  explicit ThreadedPlanner(std::unique_ptr<WindowPlanner> inner);
  ~ThreadedPlanner() override;  // waits for an outstanding request (bounded by the planner)
  void submit(planning::WindowRequest request) override;
  std::optional<PlannedWindow> poll() override;

 private:
  std::unique_ptr<WindowPlanner> inner_;
  std::future<PlannedWindow> answer_;
};

}  // namespace smart::lifelong
