// Contract: a lifelong planner in any language, run as a child process that speaks
// newline-delimited JSON on its stdin and stdout (lifelong/plan_protocol.hpp; for users:
// docs/planner-protocol.md). The edge: it starts `sh -c COMMAND`, writes the start line and waits
// (at most 30 s) for the planner's ready line, and per
// window writes a request and reads lines until the reply to it, within `timeout_s` of wall time
// (writing included). Replies to earlier windows (late ones) are skipped. Every reply passes
// check_window. A window is refused, with the reason as PlannedWindow::error and in the log, when
// the reply collides, jumps, leaves the map, starts elsewhere than the cut, is malformed, longer
// than the bound, or late; once the planner has closed its output or exited, every later window
// is refused at once with that reason. submit() blocks for at most timeout_s: lock-step runs call
// it inline (the sim waits for the monitor), real-time runs on a ThreadedPlanner.
// Memory: one reply line at a time, at most `max_reply_bytes` (longer lines are dropped as read).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "smart/common/piped_process.hpp"
#include "smart/grid/grid.hpp"
#include "smart/lifelong/window_planner.hpp"

namespace smart::tools {

struct PipePlannerOptions {
  std::string command;
  double timeout_s = 2.0;       // wall seconds per window, request and reply
  double budget_s = 0;          // told to the planner: sim seconds it is charged per call
  std::size_t max_reply_bytes;  // 0: from robots and steps (32 bytes a cell and 64 KiB)
};

class PipePlanner final : public lifelong::WindowPlanner {
 public:
  // Starts the command, writes the start line and reads the ready line; throws
  // std::runtime_error naming the command when it exits, answers wrongly or not within 30 s.
  PipePlanner(const grid::Grid& grid, std::size_t robots, int window_steps,
              PipePlannerOptions options);
  void submit(planning::WindowRequest request) override;
  std::optional<lifelong::PlannedWindow> poll() override;
  const std::string& name() const { return name_; }

 private:
  std::string exchange(const planning::WindowRequest& request, lifelong::PlannedWindow& out);
  std::string closed();

  const grid::Grid& grid_;
  std::size_t robots_;
  PipePlannerOptions options_;
  common::PipedProcess process_;
  std::string name_;  // as the planner's ready line gave it
  uint64_t window_ = 0;
  std::string gone_;  // why the planner answers no more (empty: it may)
  std::optional<lifelong::PlannedWindow> answer_;
};

}  // namespace smart::tools
