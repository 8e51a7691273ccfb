// Contract: the planning contract an external lifelong planner speaks (issue 28; specified for
// users in docs/planner-protocol.md, which this file implements), and the check every window from
// outside passes before the live ADG sees it. Pure: strings in, strings and verdicts out.
// - encode_start: the first line a planner reads: protocol name, the map (rows of '.' and '@'),
//   robots, window steps.
// - decode_ready: the planner's answer to the start line, {"type": "ready", "name": ...}: it has
//   read the map and is ready for requests (the name is recorded with the run's results).
// - encode_request: one window to plan: its number, the cut's sim time, the time budget, and per
//   robot the commit cut's end state (cell, heading) and the errands left.
// - decode_reply: one line from the planner. A reply for an earlier window is stale (skipped: it
//   came late); anything else that is not a reply to `window` with a timed path per robot is
//   malformed, and the reason names the field, robot and step.
// - check_window: a window is refused unless every robot has steps + 1 cells, starts on its cut
//   cell, stays on free cells of the map, moves at most one cell a step, and no two robots share a
//   cell at a step or swap cells between steps (the MAPF vertex and edge conflicts). Not
//   monitor/plan_validator.hpp: that one checks timed plan files against a scenario, with
//   intervals and advice about axes and files; a window is steps + 1 unit steps from a cut, and
//   its reasons are for whoever wrote the planner.
// Cells are [x, y]: x the column, y the row (MovingAI; row 0 at the top).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/planning/pibt.hpp"

namespace smart::lifelong {

inline constexpr std::string_view kPlanProtocol = "smart-plan/1";

std::string encode_start(const grid::Grid& grid, std::size_t robots, int window_steps);
struct ReadyLine {
  bool ok = false;
  std::string name;    // ok: the planner's name ("" if it gave none)
  std::string reason;  // !ok: what is wrong
};
ReadyLine decode_ready(std::string_view line);

std::string encode_request(uint64_t window, double time_s, double budget_s,
                           const planning::WindowRequest& request);

struct PlanReply {
  enum class Kind { kWindow, kStale, kPlannerError, kMalformed };
  Kind kind = Kind::kMalformed;
  std::vector<std::vector<grid::Cell>> paths;  // kWindow
  std::string reason;                          // kPlannerError (the planner's words), kMalformed
};

PlanReply decode_reply(std::string_view line, uint64_t window, std::size_t robots);

// Empty: the window may be appended. Otherwise why not (the first problem found).
std::string check_window(const grid::Grid& grid, const planning::WindowRequest& request,
                         const std::vector<std::vector<grid::Cell>>& paths);

}  // namespace smart::lifelong
