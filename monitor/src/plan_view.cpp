#include "smart/monitor/plan_view.hpp"

#include <algorithm>

namespace smart::monitor {

std::vector<grid::WorldPoint> planned_path(const grid::ActionPlan& plan, const grid::Grid& grid,
                                           uint32_t robot, double cell_m) {
  std::vector<grid::WorldPoint> path{grid.to_world(plan.start[robot], cell_m)};
  for (uint32_t seq = 0; seq < plan.count(robot); ++seq) {
    const auto& a = plan.at(robot, seq);
    if (a.type == grid::ActionType::kMove) path.push_back(grid.to_world(a.to, cell_m));
  }
  return path;
}

namespace {

// The robot whose action is ADG node `node` (offsets are ascending).
uint32_t robot_of(const grid::ActionPlan& plan, uint32_t node) {
  const auto it = std::upper_bound(plan.offset.begin(), plan.offset.end(), node);
  return static_cast<uint32_t>(it - plan.offset.begin() - 1);
}

}  // namespace

PlanSnapshot snapshot(const grid::ActionPlan& plan, const Execution& execution,
                      const Type2Predecessors& predecessors) {
  PlanSnapshot s;
  const auto robots = static_cast<uint32_t>(plan.robots());
  s.activity.resize(robots, Activity::kDone);
  std::vector<uint32_t> from;
  for (uint32_t r = 0; r < robots; ++r) {
    if (execution.robot_done(r)) continue;
    const uint32_t next = execution.finished(r);
    if (next < execution.enqueued(r)) {
      s.activity[r] = Activity::kMoving;
      continue;
    }
    s.activity[r] = Activity::kWaiting;
    from.clear();
    predecessors(plan.offset[r] + next, from);
    std::vector<uint32_t> blockers;
    for (const uint32_t node : from) {
      const uint32_t other = robot_of(plan, node);
      if (node - plan.offset[other] >= execution.finished(other)) blockers.push_back(other);
    }
    std::sort(blockers.begin(), blockers.end());
    blockers.erase(std::unique(blockers.begin(), blockers.end()), blockers.end());
    for (const uint32_t b : blockers) s.waits.push_back({r, b});
  }
  return s;
}

PlanSnapshot snapshot(const grid::ActionPlan& plan, const Adg& adg,
                      const ExecutionTracker& tracker) {
  return snapshot(plan, tracker, [&adg](uint32_t node, std::vector<uint32_t>& out) {
    out.insert(out.end(), adg.in.begin() + adg.in_begin[node],
               adg.in.begin() + adg.in_begin[node + 1]);
  });
}

}  // namespace smart::monitor
