// Contract: a lifelong run's tasks, as the League of Robot Runners Start-Kit manages them
// (src/TaskManager.cpp, Input_Output_Format.md), told the time, never reading a clock:
// - reveal: tasks are revealed in the source's order, cycling through it when it runs out (task
//   id k repeats source task k mod N), until `pool` revealed tasks are unfinished (LoRR:
//   numTasksReveal x teamSize);
// - assign: robots without a task are offered the revealed tasks nobody holds (scheduler.hpp);
//   a task is never taken from its robot (LoRR allows reassigning a task before it is opened;
//   the default here never reassigns, so no task is ever reassigned, opened or not);
// - errands: a robot completes its task's next errand when it reaches that errand's cell (the
//   monitor calls on_reached() when an action ending on a cell finishes); the first errand
//   opens the task, the last finishes it and frees the robot;
// - every event (revealed, assigned, opened, errand, finished) is recorded with its time, to be
//   taken (and streamed to events.csv) by the edge; finished tasks likewise (tasks.csv), so
//   memory holds only unfinished tasks however long the run.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <unordered_map>
#include <vector>

#include "smart/grid/lorr.hpp"
#include "smart/lifelong/scheduler.hpp"
#include "smart/monitor/results_format.hpp"

namespace smart::lifelong {

class TaskManager {
 public:
  // Throws std::invalid_argument for no tasks or a pool of 0.
  TaskManager(std::vector<grid::Task> source, std::size_t robots, std::size_t pool,
              Scheduler& scheduler);

  // Reveal up to the pool, then assign free robots standing at `cells` (per robot).
  void update(double time_s, const std::vector<grid::Cell>& cells);
  // `robot` stands on `cell` after an action: true when that was its next errand.
  bool on_reached(uint32_t robot, grid::Cell cell, double time_s);

  // A robot standing still on `cell` (no action left to finish there) completes every errand of
  // its task it stands on, in order (a task assigned to a robot already on its first errand).
  void reached_while_idle(uint32_t robot, grid::Cell cell, double time_s);
  // The errands the robot has left, in order (empty: no task).
  std::vector<grid::Cell> goals(uint32_t robot) const;
  std::optional<uint64_t> task_of(uint32_t robot) const { return held_[robot]; }
  std::size_t robots_with_task() const;
  uint64_t finished() const { return finished_; }
  uint64_t revealed() const { return next_id_; }
  // Finished task count at each minute boundary is for throughput; this is the raw record.
  std::vector<results::EventRow> take_events();
  std::vector<results::TaskRow> take_finished();
  std::vector<results::TaskRow> unfinished() const;  // at the run's end

 private:
  struct Open {
    results::TaskRow row;
    std::vector<grid::Cell> errands;
  };
  void event(double t, const char* what, uint64_t task, std::optional<uint32_t> robot,
             std::optional<uint32_t> errand);

  std::vector<grid::Task> source_;
  std::size_t pool_;
  Scheduler& scheduler_;
  std::vector<std::optional<uint64_t>> held_;  // per robot
  std::unordered_map<uint64_t, Open> open_;    // revealed, not finished
  std::deque<uint64_t> order_;                 // revealed order of open_ (for the scheduler)
  uint64_t next_id_ = 0;
  uint64_t finished_ = 0;
  std::vector<results::EventRow> events_;
  std::vector<results::TaskRow> done_;
};

}  // namespace smart::lifelong
