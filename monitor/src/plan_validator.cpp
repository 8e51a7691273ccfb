#include "smart/monitor/plan_validator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace smart::monitor {

namespace {

constexpr double kForever = std::numeric_limits<double>::infinity();

std::string fmt_time(double t) {
  std::ostringstream s;
  s << "t=" << t;
  return s.str();
}

struct Interval {
  std::size_t cell;  // grid index
  double arrive;
  double depart;
  int robot;
  int line;
  double arrival_at_goal;  // for parked intervals: when the robot got there
};

struct Traversal {
  std::size_t lo, hi;  // grid indices of the edge's cells, lo < hi
  bool forward;        // lo -> hi
  double start, end;
  int robot;
  int line;
  Cell from, to;
};

// Per robot checks; returns false when the path cannot be used for conflict checks.
bool check_path(const Plan& plan, const RobotPath& path, const Grid& grid,
                std::vector<Problem>& problems) {
  bool usable = true;
  const auto& steps = path.steps;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const auto& s = steps[k];
    if (!grid.inside(s.cell)) {
      problems.push_back({plan.source, s.line, path.robot,
                          "step " + std::to_string(k) + " at " + fmt_time(s.time) + " is " +
                              to_string(s.cell) + ", outside the " + std::to_string(grid.width()) +
                              "x" + std::to_string(grid.height()) +
                              " map; check --axis and that the plan belongs to this map"});
      usable = false;
      continue;
    }
    if (grid.blocked(s.cell)) {
      problems.push_back({plan.source, s.line, path.robot,
                          "step " + std::to_string(k) + " at " + fmt_time(s.time) +
                              " moves into the obstacle at " + to_string(s.cell) +
                              "; check --axis and that the plan belongs to this map"});
      usable = false;
    }
    if (k == 0) {
      if (s.time < 0) {
        problems.push_back(
            {plan.source, s.line, path.robot, "first step has negative time " + fmt_time(s.time)});
        usable = false;
      }
      continue;
    }
    const auto& p = steps[k - 1];
    if (!(s.time > p.time)) {
      problems.push_back({plan.source, s.line, path.robot,
                          "step " + std::to_string(k) + " has " + fmt_time(s.time) +
                              ", not after the previous step's " + fmt_time(p.time) +
                              "; times must strictly increase"});
      usable = false;
    }
    const int dist = std::abs(s.cell.x - p.cell.x) + std::abs(s.cell.y - p.cell.y);
    if (dist > 1) {
      problems.push_back({plan.source, s.line, path.robot,
                          "step " + std::to_string(k) + " jumps from " + to_string(p.cell) +
                              " to " + to_string(s.cell) + " at " + fmt_time(s.time) +
                              "; only moves to one of the 4 neighbours or waits are allowed"});
      usable = false;
    }
  }
  return usable;
}

void check_scenario(const Plan& plan, const Scenario& scen, std::vector<Problem>& problems) {
  if (plan.paths.size() > scen.agents.size()) {
    problems.push_back({plan.source, 0, -1,
                        "the plan has " + std::to_string(plan.paths.size()) +
                            " robots but the scenario " + scen.source + " only " +
                            std::to_string(scen.agents.size()) +
                            "; pass a scenario with enough agents or a larger --agents"});
  }
  std::size_t mismatched = 0, swapped_ok = 0;
  auto swap = [](Cell c) { return Cell{c.y, c.x}; };
  for (const auto& path : plan.paths) {
    if (path.steps.empty() || static_cast<std::size_t>(path.robot) >= scen.agents.size()) continue;
    const auto& a = scen.agents[static_cast<std::size_t>(path.robot)];
    const auto& first = path.steps.front();
    const auto& last = path.steps.back();
    bool bad = false;
    if (first.cell != a.start) {
      problems.push_back({plan.source, first.line, path.robot,
                          "starts at " + to_string(first.cell) + " but the scenario (line " +
                              std::to_string(a.line) + ") starts it at " + to_string(a.start)});
      bad = true;
    }
    if (last.cell != a.goal) {
      problems.push_back({plan.source, last.line, path.robot,
                          "ends at " + to_string(last.cell) + " but the scenario (line " +
                              std::to_string(a.line) + ") has its goal at " + to_string(a.goal)});
      bad = true;
    }
    if (bad) {
      ++mismatched;
      if (swap(first.cell) == a.start && swap(last.cell) == a.goal) ++swapped_ok;
    }
  }
  if (mismatched > 0 && swapped_ok == mismatched && plan.format != PlanFormat::kYaml) {
    // First, so that it is not lost below hundreds of follow-up problems.
    problems.insert(problems.begin(),
                    {plan.source, 0, -1,
                     "every mismatched start and goal matches the scenario with the axes "
                     "swapped: the plan is probably " +
                         std::string(plan.axis == AxisOrder::kXY ? "(row,col)" : "(x,y)") +
                         "; pass --axis " + (plan.axis == AxisOrder::kXY ? "rowcol" : "xy")});
  }
}

void check_vertex_conflicts(const Plan& plan, const Grid& grid, std::vector<Interval>& intervals,
                            std::vector<Problem>& problems) {
  std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.arrive < b.arrive;
  });
  const auto width = static_cast<std::size_t>(grid.width());
  auto cell_of = [&](std::size_t idx) {
    return Cell{static_cast<int32_t>(idx % width), static_cast<int32_t>(idx / width)};
  };
  std::size_t i = 0;
  while (i < intervals.size()) {
    std::size_t holder = i;  // interval with the latest departure so far at this cell
    std::size_t j = i + 1;
    for (; j < intervals.size() && intervals[j].cell == intervals[i].cell; ++j) {
      const auto& h = intervals[holder];
      const auto& n = intervals[j];
      if (n.arrive < h.depart && n.robot != h.robot) {
        const Cell c = cell_of(n.cell);
        // Arriving at the same time as the parked robot is a plain vertex conflict.
        if (h.depart == kForever && h.arrival_at_goal < n.arrive) {
          problems.push_back({plan.source, n.line, n.robot,
                              "enters " + to_string(c) + " at " + fmt_time(n.arrive) +
                                  " where robot " + std::to_string(h.robot) +
                                  " is parked at its goal since " + fmt_time(h.arrival_at_goal) +
                                  "; robots stay at their goal, so the plan must route around "
                                  "it or let it arrive later"});
        } else {
          problems.push_back({plan.source, n.line, n.robot,
                              "vertex conflict with robot " + std::to_string(h.robot) + " at " +
                                  to_string(c) + " at " + fmt_time(n.arrive) +
                                  ": both robots are there at once"});
        }
      }
      if (n.depart > h.depart) holder = j;
    }
    i = j;
  }
}

void check_swap_conflicts(const Plan& plan, std::vector<Traversal>& moves,
                          std::vector<Problem>& problems) {
  std::sort(moves.begin(), moves.end(), [](const Traversal& a, const Traversal& b) {
    if (a.lo != b.lo) return a.lo < b.lo;
    if (a.hi != b.hi) return a.hi < b.hi;
    return a.start < b.start;
  });
  std::size_t i = 0;
  while (i < moves.size()) {
    std::size_t j = i;
    while (j < moves.size() && moves[j].lo == moves[i].lo && moves[j].hi == moves[i].hi) ++j;
    for (std::size_t a = i; a < j; ++a) {
      for (std::size_t b = a + 1; b < j && moves[b].start < moves[a].end; ++b) {
        if (moves[a].forward == moves[b].forward || moves[a].robot == moves[b].robot) continue;
        problems.push_back({plan.source, moves[b].line, moves[b].robot,
                            "swap conflict with robot " + std::to_string(moves[a].robot) +
                                ": it moves " + to_string(moves[b].from) + "->" +
                                to_string(moves[b].to) + " while robot " +
                                std::to_string(moves[a].robot) + " moves the other way, at " +
                                fmt_time(moves[b].start)});
      }
    }
    i = j;
  }
}

}  // namespace

std::vector<Problem> validate_plan(const Plan& plan, const Grid& grid, const Scenario* scen) {
  std::vector<Problem> problems;
  std::vector<Interval> intervals;
  std::vector<Traversal> moves;
  for (const auto& path : plan.paths) {
    if (path.steps.empty()) {
      problems.push_back({plan.source, path.line, path.robot, "path has no steps"});
      continue;
    }
    if (!check_path(plan, path, grid, problems)) continue;
    const auto& steps = path.steps;
    double arrive = 0.0;  // the first cell is held from time 0
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const bool leaves = k + 1 < steps.size() && steps[k + 1].cell != steps[k].cell;
      const bool last = k + 1 == steps.size();
      if (leaves || last) {
        // The interval of the cell held since `arrive`; for the move, the last step at the cell.
        // NOLINTNEXTLINE(bugprone-narrowing-conversions): clang-tidy 14 misreads infinity
        const double depart = last ? kForever : steps[k + 1].time;
        intervals.push_back(
            {grid.index(steps[k].cell), arrive, depart, path.robot, steps[k].line, arrive});
        if (leaves) {
          const auto a = grid.index(steps[k].cell), b = grid.index(steps[k + 1].cell);
          moves.push_back({std::min(a, b), std::max(a, b), a < b, steps[k].time, steps[k + 1].time,
                           path.robot, steps[k + 1].line, steps[k].cell, steps[k + 1].cell});
          arrive = steps[k + 1].time;
        }
      }
    }
  }
  if (scen != nullptr) check_scenario(plan, *scen, problems);
  check_vertex_conflicts(plan, grid, intervals, problems);
  check_swap_conflicts(plan, moves, problems);
  return problems;
}

}  // namespace smart::monitor
