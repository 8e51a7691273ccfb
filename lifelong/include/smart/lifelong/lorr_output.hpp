// Contract: a lifelong run written as the League of Robot Runners' output JSON (LoRR 2026
// Start-Kit, Input_Output_Format.md, "Output File"), so PlanViz and LoRR tooling can read a
// SMART-DDS run. Pure: it is told what happened (finished and planned actions by the run's
// ActionObserver hook, task events and planner calls as the run records them) and builds the
// JSON; no I/O.
// Discretised, and the file says so ("discretisation"): SMART-DDS robots move continuously, so
// - time is in ticks of kTickS = 0.1 s (LoRR's execution tick; the tick of its delays);
// - an executed action counts at the tick it finished (the robot's own report): a move when the
//   robot reached the next cell ("F"; its half-moves are one LoRR forward), a quarter turn when
//   it was done ("R" clockwise, "C" counter-clockwise; a half turn is two); every other tick is
//   a wait ("W"). So agentMaxCounter is 1: each LoRR action takes one tick. Two actions that
//   finish in one tick go to consecutive ticks, in order (never seen at these speeds);
// - plannerPaths: the same for the planned actions: a window appended at tick T puts the action
//   that ends at its step k at tick T + k (one tick per planned step, as agentMaxCounter 1 says),
//   a later window replacing what an earlier one planned from its first action on (the staged
//   plan; the commit cut dropped the rest);
// - locations as the Start-Kit's code writes them: row = location / width, col = location %
//   width, in paths, starts and task errands; orientation 0 east, 1 south, 2 west, 3 north.
// Events are LoRR's [tick, robot, task, errands done] at each errand reached; schedules are
// "tick:task" at each change of a robot's task (-1: none); errors are collisions as
// [task (-1), robot1, robot2, tick, description]; numPlannerErrors counts refused windows that
// were not late, numEntryTimeouts the late ones.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "smart/grid/action.hpp"
#include "smart/grid/grid.hpp"
#include "smart/grid/lorr.hpp"
#include "smart/monitor/results_format.hpp"

namespace smart::lifelong {

inline constexpr double kLorrTickS = 0.1;
inline constexpr int kLorrSegmentTicks = 1000;  // the Start-Kit's --outputActionWindow default

int64_t lorr_tick(double t_s);  // the tick that holds sim time t_s

// What a run does, as it does it (lifelong_execution.hpp calls these).
class ActionObserver {
 public:
  virtual ~ActionObserver() = default;
  virtual void executed(uint32_t robot, const grid::Action& a, double time_s) = 0;
  // `step`: its planned end in window steps from the window's first (plan time units).
  virtual void planned(uint32_t robot, const grid::Action& a, double appended_s, double step) = 0;
};

struct LorrCollision {
  uint32_t a = 0, b = 0;
  double t_s = 0;
};

struct LorrRunEnd {
  double duration_s = 0;
  uint64_t tasks_finished = 0;
  std::vector<std::vector<std::pair<int64_t, int64_t>>> delay_intervals;  // per robot, ticks
  std::vector<LorrCollision> collisions;
};

class LorrOutput final : public ActionObserver {
 public:
  LorrOutput(const grid::Grid& grid, const std::vector<grid::Cell>& starts,
             grid::Heading initial_heading, std::vector<grid::Task> source_tasks,
             int segment_ticks = kLorrSegmentTicks);
  void executed(uint32_t robot, const grid::Action& a, double time_s) override;
  void planned(uint32_t robot, const grid::Action& a, double appended_s, double step) override;
  // Task and window events (events.csv's rows): tasks, events, schedules, planner errors.
  void on_event(const results::EventRow& e);
  // A planning call (throughput.csv's rows): its wall time.
  void on_planner_call(const results::ThroughputRow& row);
  nlohmann::ordered_json json(const LorrRunEnd& end) const;

 private:
  struct Step {
    int64_t tick;
    char action;            // F, R, C
    uint32_t seq;           // of the grid action it comes from
    grid::Heading heading;  // after it
  };
  struct Robot {
    std::vector<Step> executed, planned;
    grid::Heading executed_heading;
    std::vector<std::pair<int64_t, int64_t>> schedule;  // (tick, task or -1)
  };
  static void add(std::vector<Step>& steps, grid::Heading& heading, const grid::Action& a,
                  int64_t tick, uint32_t seq);
  std::string path_string(const std::vector<Step>& steps, uint32_t robot, int64_t ticks) const;
  void schedule(uint32_t robot, int64_t tick, int64_t task);

  int32_t width_;
  std::vector<grid::Cell> starts_;
  grid::Heading initial_;
  std::vector<grid::Task> source_;
  int segment_ticks_;
  std::vector<Robot> robots_;
  nlohmann::ordered_json tasks_ = nlohmann::ordered_json::array();
  nlohmann::ordered_json events_ = nlohmann::ordered_json::array();
  std::vector<double> planner_s_;
  uint64_t planner_errors_ = 0, timeouts_ = 0;
};

}  // namespace smart::lifelong
