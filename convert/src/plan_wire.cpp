#include "smart/convert/plan_wire.hpp"

#include <algorithm>
#include <cstdio>
#include <tuple>

#include "smart/convert/validate.hpp"
#include "smart/dds/sequence.hpp"

namespace smart::wire {

namespace {

smart_msg_GridCell to_wire(grid::Cell c) { return {c.x, c.y}; }
grid::Cell from_wire(const smart_msg_GridCell& c) { return {c.x, c.y}; }

std::string cell_text(const smart_msg_GridCell& c) {
  return "(x=" + std::to_string(c.x) + ",y=" + std::to_string(c.y) + ")";
}

// Why `c` is no cell of `grid`, or "".
std::string off_map(const smart_msg_GridCell& c, const grid::Grid& grid) {
  if (grid.inside(from_wire(c))) return {};
  return cell_text(c) + " is off the " + std::to_string(grid.width()) + "x" +
         std::to_string(grid.height()) + " map";
}

std::string count_mismatch(const char* what, uint32_t n, std::size_t robots) {
  return std::string(what) + " has " + std::to_string(n) + " entries for " +
         std::to_string(robots) + " robots (one per robot)";
}

}  // namespace

std::string describe_planner(const smart_msg_PlannerInfo& p) {
  return std::string("planner '") + p.name + "' (pid " + std::to_string(p.pid) + " on " + p.host +
         ")";
}

std::string check_planner_info(const smart_msg_PlannerInfo& p) {
  if (p.planner_id == 0) return "planner id 0";
  if (p.pid <= 0) return "pid " + std::to_string(p.pid) + " is not a process id";
  auto why = check_printable("planner name", p.name, sizeof(p.name));
  return why.empty() ? check_printable("host name", p.host, sizeof(p.host)) : why;
}

std::size_t choose_planner(const std::vector<smart_msg_PlannerInfo>& heard) {
  const auto it = std::min_element(heard.begin(), heard.end(), [](const auto& a, const auto& b) {
    return std::tie(a.started_ms, a.planner_id) < std::tie(b.started_ms, b.planner_id);
  });
  return static_cast<std::size_t>(it - heard.begin());
}

PlanProblemBuffer::PlanProblemBuffer(uint64_t run_id, const smart_msg_PlannerInfo& chosen,
                                     const grid::Grid& grid, std::size_t robots, int window_steps) {
  blocked_.reserve(static_cast<std::size_t>(grid.width()) * grid.height());
  for (int32_t y = 0; y < grid.height(); ++y) {
    for (int32_t x = 0; x < grid.width(); ++x) blocked_.push_back(grid.blocked({x, y}) ? 1 : 0);
  }
  msg_.run_id = run_id;
  msg_.planner = chosen;
  msg_.width = static_cast<uint32_t>(grid.width());
  msg_.height = static_cast<uint32_t>(grid.height());
  msg_.robots = static_cast<uint32_t>(robots);
  msg_.window_steps = static_cast<uint32_t>(window_steps);
}

const smart_msg_PlanProblem& PlanProblemBuffer::view() {
  dds::borrow(msg_.blocked, blocked_);
  return msg_;
}

std::string check_problem(const smart_msg_PlanProblem& p) {
  if (p.run_id == 0) return "run id 0 (no run)";
  if (auto why = check_planner_info(p.planner); !why.empty()) return "planner: " + why;
  const uint64_t cells = uint64_t{p.width} * p.height;
  if (p.width == 0 || p.height == 0 || cells > smart_msg_MAX_PLAN_CELLS) {
    return "map " + std::to_string(p.width) + "x" + std::to_string(p.height) +
           " is empty or larger than MAX_PLAN_CELLS";
  }
  if (p.blocked._length != cells) {
    return "blocked has " + std::to_string(p.blocked._length) + " bytes for a " +
           std::to_string(p.width) + "x" + std::to_string(p.height) + " map";
  }
  for (uint32_t i = 0; i < p.blocked._length; ++i) {
    if (p.blocked._buffer[i] > 1) return "blocked[" + std::to_string(i) + "] is neither 0 nor 1";
  }
  if (p.robots == 0 || p.robots > smart_msg_MAX_PLAN_ROBOTS) {
    return "robots " + std::to_string(p.robots) + " is not 1..MAX_PLAN_ROBOTS";
  }
  if (p.window_steps == 0 || p.window_steps > smart_msg_MAX_PLAN_STEPS) {
    return "window_steps " + std::to_string(p.window_steps) + " is not 1..MAX_PLAN_STEPS";
  }
  return {};
}

grid::Grid grid_of(const smart_msg_PlanProblem& p) {
  return grid::Grid(static_cast<int32_t>(p.width), static_cast<int32_t>(p.height),
                    dds::copy_of<uint8_t>(p.blocked));
}

void PlanRequestBuffer::set(uint64_t run_id, uint64_t planner_id, uint64_t window, double budget_s,
                            const planning::WindowRequest& request) {
  starts_.clear();
  errands_.clear();
  headings_.clear();
  counts_.clear();
  for (std::size_t r = 0; r < request.start.size(); ++r) {
    starts_.push_back(to_wire(request.start[r]));
    headings_.push_back(r < request.heading.size() ? static_cast<uint8_t>(request.heading[r]) : 0);
    const auto& goals = r < request.goals.size() ? request.goals[r] : std::vector<grid::Cell>{};
    counts_.push_back(static_cast<uint32_t>(goals.size()));
    for (const auto c : goals) errands_.push_back(to_wire(c));
  }
  msg_.run_id = run_id;
  msg_.planner_id = planner_id;
  msg_.window = window;
  msg_.time_s = request.time_s;
  msg_.budget_s = budget_s;
  msg_.steps = static_cast<uint32_t>(request.steps);
}

const smart_msg_PlanRequest& PlanRequestBuffer::view() {
  dds::borrow(msg_.starts, starts_);
  dds::borrow(msg_.headings, headings_);
  dds::borrow(msg_.errand_counts, counts_);
  dds::borrow(msg_.errands, errands_);
  return msg_;
}

std::string check_request(const smart_msg_PlanRequest& r, const grid::Grid& grid,
                          std::size_t robots) {
  if (r.window == 0) return "window 0 (windows count from 1)";
  if (r.steps == 0 || r.steps > smart_msg_MAX_PLAN_STEPS) {
    return "steps " + std::to_string(r.steps) + " is not 1..MAX_PLAN_STEPS";
  }
  if (r.starts._length != robots) return count_mismatch("starts", r.starts._length, robots);
  if (r.headings._length != robots) return count_mismatch("headings", r.headings._length, robots);
  if (r.errand_counts._length != robots) {
    return count_mismatch("errand_counts", r.errand_counts._length, robots);
  }
  uint64_t errands = 0;
  for (uint32_t i = 0; i < robots; ++i) {
    const auto who = "robot " + std::to_string(i) + ": ";
    if (auto why = off_map(r.starts._buffer[i], grid); !why.empty()) return who + "start " + why;
    if (r.headings._buffer[i] > 3) return who + "heading is not 0..3";
    if (r.errand_counts._buffer[i] > smart_msg_MAX_PLAN_ERRANDS) {
      return who + std::to_string(r.errand_counts._buffer[i]) + " errands, over MAX_PLAN_ERRANDS";
    }
    errands += r.errand_counts._buffer[i];
  }
  if (errands != r.errands._length) {
    return "errand_counts add up to " + std::to_string(errands) + " but errands has " +
           std::to_string(r.errands._length);
  }
  for (uint32_t i = 0; i < r.errands._length; ++i) {
    if (auto why = off_map(r.errands._buffer[i], grid); !why.empty()) {
      return "errands[" + std::to_string(i) + "]: " + why;
    }
  }
  return {};
}

planning::WindowRequest request_of(const smart_msg_PlanRequest& r) {
  planning::WindowRequest out;
  out.steps = static_cast<int>(r.steps);
  out.time_s = r.time_s;
  uint32_t next = 0;
  for (uint32_t i = 0; i < r.starts._length; ++i) {
    out.start.push_back(from_wire(r.starts._buffer[i]));
    out.heading.push_back(static_cast<grid::Heading>(r.headings._buffer[i]));
    auto& goals = out.goals.emplace_back();
    for (uint32_t k = 0; k < r.errand_counts._buffer[i]; ++k) {
      goals.push_back(from_wire(r.errands._buffer[next++]));
    }
  }
  return out;
}

void PlanReplyBuffer::head(uint64_t planner_id, uint64_t run_id, uint64_t window) {
  msg_.planner_id = planner_id;
  msg_.run_id = run_id;
  msg_.window = window;
  msg_.error[0] = '\0';
  msg_.steps = 0;
  cells_.clear();
}

void PlanReplyBuffer::set_paths(uint64_t planner_id, uint64_t run_id, uint64_t window,
                                const std::vector<std::vector<grid::Cell>>& paths) {
  head(planner_id, run_id, window);
  if (!paths.empty() && !paths.front().empty()) {
    msg_.steps = static_cast<uint32_t>(paths.front().size() - 1);
  }
  for (const auto& path : paths) {
    for (const auto c : path) cells_.push_back(to_wire(c));
  }
}

void PlanReplyBuffer::set_error(uint64_t planner_id, uint64_t run_id, uint64_t window,
                                const std::string& error) {
  head(planner_id, run_id, window);
  std::snprintf(msg_.error, sizeof(msg_.error), "%s", error.empty() ? "error" : error.c_str());
  for (char& c : msg_.error) {  // the receiver refuses what it cannot print
    if (c != '\0' &&
        (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e)) {
      c = '?';
    }
  }
}

const smart_msg_PlanReply& PlanReplyBuffer::view() {
  dds::borrow(msg_.cells, cells_);
  return msg_;
}

std::string check_reply(const smart_msg_PlanReply& r, std::size_t robots, uint32_t steps) {
  if (auto why = check_printable("error", r.error, sizeof(r.error)); !why.empty()) return why;
  if (r.error[0] != '\0') {
    return r.cells._length == 0 ? std::string() : "an error and cells in one reply";
  }
  if (r.steps != steps) {
    return "steps " + std::to_string(r.steps) + " where the request asked for " +
           std::to_string(steps);
  }
  const uint64_t want = uint64_t{robots} * (uint64_t{steps} + 1);
  if (r.cells._length != want) {
    return "cells has " + std::to_string(r.cells._length) + " entries, not " +
           std::to_string(robots) + " robots x " + std::to_string(steps + 1) + " steps";
  }
  return {};
}

std::vector<std::vector<grid::Cell>> paths_of(const smart_msg_PlanReply& r) {
  std::vector<std::vector<grid::Cell>> out;
  const uint32_t per = r.steps + 1;
  if (r.error[0] != '\0' || per == 0) return out;
  out.reserve(r.cells._length / per);
  for (uint32_t i = 0; i + per <= r.cells._length; i += per) {
    auto& path = out.emplace_back();
    path.reserve(per);
    for (uint32_t k = 0; k < per; ++k) path.push_back(from_wire(r.cells._buffer[i + k]));
  }
  return out;
}

}  // namespace smart::wire
