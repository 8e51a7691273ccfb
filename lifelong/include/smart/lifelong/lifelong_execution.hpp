// Contract: a lifelong run as the monitor executes it (monitor/execution.hpp): tasks stream in
// (task_manager.hpp), a planner plans windows from the commit cut, and the ADG grows while the
// robots execute (monitor/live_adg.hpp). Pure: the run supervisor tells it the time (sim time in
// lock-step, the monitor's wall time in real time); the planner's wall time is measured only
// through the clock it is given, and never decides anything.
// Replanning (on_time): when it is due (every period_s, and with min_unfinished k > 0 also as
// soon as a robot with a task has at most k unfinished actions: Hönig et al. 2019's event-based
// policy), the commit cut keeps what was sent and at least `lookahead` unfinished actions per
// robot (closed, never on a midpoint), everything beyond it is dropped (never sent), new tasks are
// revealed and assigned, and the planner plans `window_steps` timesteps from every robot's cut cell
// toward its errands. The clock never stops for the planner: the cut's actions keep running. In
// lock-step the window is appended once `budget_s` of sim time has passed since the cut (a fixed
// charge per call, so a run is the same for a seed whatever the machine's speed); in real time it
// is appended as soon as the planner answers (window_planner.hpp: a ThreadedPlanner plans while
// the monitor goes on dispatching). Robots that run out of actions stop on the cut's cells (never
// mid-edge) until the window arrives. A window the graph refuses (live_adg.hpp) is logged as a
// refused event; robots then stop safely at the cut and the next call replans. The run is complete
// when the time reaches duration_s. Records: task and window events, a throughput row per call
// (results_format.hpp), planner calls and wall time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "smart/lifelong/lorr_output.hpp"
#include "smart/lifelong/scheduler.hpp"
#include "smart/lifelong/task_manager.hpp"
#include "smart/lifelong/window_planner.hpp"
#include "smart/monitor/execution.hpp"
#include "smart/monitor/live_adg.hpp"

namespace smart::lifelong {

struct LifelongOptions {
  double duration_s = 600;           // the run ends here (sim time, or wall time in real time)
  double period_s = 1.0;             // replanning period
  uint32_t min_unfinished = 0;       // event-based replanning trigger k; 0: periodic only
  int window_steps = 10;             // planned timesteps per window
  uint32_t lookahead = 8;            // unfinished actions the cut keeps per robot (at least)
  double budget_s = 0;               // lock-step: sim time charged per planning call
  std::size_t task_pool = 0;         // revealed unfinished tasks; 0: one per robot
  double distance_budget_mb = 1024;  // the planner's distance tables (one per goal cell)
  planning::HeuristicKind heuristic = planning::HeuristicKind::kAuto;
  int lns_passes = 0;  // the built-in planner's (window_planner.hpp BuiltinPlannerOptions)
  uint64_t seed = 1;
  grid::Heading initial_heading = grid::Heading::kEast;
  // Passing orders may switch while the run goes (issue 29, live_adg.hpp); empty: plan order.
  std::optional<monitor::SwitchOptions> switching = {};
};

struct LifelongStats {
  uint64_t planner_calls = 0;
  double planner_total_ms = 0, planner_max_ms = 0;
  uint64_t windows_refused = 0;
  uint64_t appended_actions = 0, type2_edges = 0;
  uint64_t tasks_finished = 0, tasks_revealed = 0;
  uint64_t distance_tables = 0;  // held by the planner's cache (one per goal cell seen, bounded)
  std::string heuristic;         // what the planner ranks moves by (its last answer)
  double heuristic_mb = 0;       // the planner's heuristic memory (tables, or landmarks + paths)
};

class LifelongExecution final : public monitor::Execution {
 public:
  // The built-in planner, planning inside on_time(); `wall_ms` measures it (e.g. a steady clock
  // in ms); empty: not measured.
  LifelongExecution(const grid::Grid& grid, const std::vector<grid::Cell>& starts,
                    std::vector<grid::Task> tasks, const LifelongOptions& options,
                    std::function<double()> wall_ms = {});
  // Any planner (window_planner.hpp), e.g. the built-in one on a thread for real-time runs.
  LifelongExecution(const grid::Grid& grid, const std::vector<grid::Cell>& starts,
                    std::vector<grid::Task> tasks, const LifelongOptions& options,
                    std::unique_ptr<WindowPlanner> planner);

  monitor::ProgressUpdate on_progress(uint32_t robot, int64_t finished_seq, double time_s) override;
  std::vector<uint32_t> on_time(double time_s, const std::vector<uint32_t>& sent) override;
  monitor::ActionWindowRange window(uint32_t robot, uint32_t cap) const override {
    return adg_.window(robot, cap);
  }
  std::size_t robots() const override { return adg_.robots(); }
  uint32_t finished(uint32_t r) const override { return adg_.finished(r); }
  uint32_t enqueued(uint32_t r) const override { return adg_.enqueued(r); }
  uint32_t known(uint32_t r) const override { return adg_.end(r); }
  const grid::Action& action(uint32_t r, uint32_t seq) const override {
    return adg_.action(r, seq);
  }
  bool robot_done(uint32_t) const override { return false; }
  std::size_t finished_total() const override { return adg_.finished_total(); }
  std::size_t total() const override { return adg_.appended_total(); }
  bool complete() const override { return now_s_ >= options_.duration_s; }
  bool deadlocked() const override { return adg_.deadlocked(); }
  bool lifelong() const override { return true; }
  const std::vector<monitor::PassingSwitch>* switches() const override { return adg_.switches(); }
  std::optional<monitor::WaitCause> wait_cause(uint32_t r) const override {
    return adg_.wait_cause(r);
  }

  const LifelongStats& stats() const { return stats_; }
  TaskManager& tasks() { return tasks_; }
  const monitor::LiveAdg& adg() const { return adg_; }
  // Told every action as it finishes (robots' reports) and as it is appended (planned); null:
  // nobody (the LoRR output, lorr_output.hpp, when asked for). Must outlive the run.
  void observe(ActionObserver* observer) { observer_ = observer; }
  std::vector<results::EventRow> take_events();
  std::vector<results::ThroughputRow> take_throughput();

 private:
  bool due(double time_s) const;
  void plan(double time_s, const std::vector<uint32_t>& sent);
  std::vector<uint32_t> arrive(double time_s);
  std::vector<uint32_t> append(const PlannedWindow& window, double time_s);
  void refuse(double time_s, const std::string& why);

  LifelongOptions options_;
  ActionObserver* observer_ = nullptr;
  monitor::LiveAdg adg_;
  GreedyNearestScheduler scheduler_;
  TaskManager tasks_;
  std::unique_ptr<WindowPlanner> planner_;
  struct Pending {
    double release_s = 0;
    results::ThroughputRow row;           // the cut's figures; the planner's time on arrival
    std::optional<PlannedWindow> window;  // empty while the planner works
  };
  std::optional<Pending> pending_;
  double now_s_ = 0;
  double next_plan_s_ = 0;
  std::vector<double> finish_times_;  // tasks finished in the last minute (throughput)
  LifelongStats stats_;
  std::vector<results::EventRow> events_;
  std::vector<results::ThroughputRow> throughput_;
};

}  // namespace smart::lifelong
