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

PlanSnapshot snapshot(const grid::ActionPlan& plan, const Adg& adg,
                      const ExecutionTracker& tracker) {
  PlanSnapshot s;
  const auto robots = static_cast<uint32_t>(plan.robots());
  s.activity.resize(robots, Activity::kDone);
  for (uint32_t r = 0; r < robots; ++r) {
    if (tracker.robot_done(r)) continue;
    const uint32_t next = tracker.finished(r);
    if (tracker.state(r, next) != ActionState::kStaged) {
      s.activity[r] = Activity::kMoving;
      continue;
    }
    s.activity[r] = Activity::kWaiting;
    const uint32_t node = plan.offset[r] + next;
    std::vector<uint32_t> blockers;
    for (uint32_t e = adg.in_begin[node]; e < adg.in_begin[node + 1]; ++e) {
      const uint32_t from = adg.in[e];
      const uint32_t other = robot_of(plan, from);
      if (tracker.state(other, from - plan.offset[other]) != ActionState::kFinished) {
        blockers.push_back(other);
      }
    }
    std::sort(blockers.begin(), blockers.end());
    blockers.erase(std::unique(blockers.begin(), blockers.end()), blockers.end());
    for (const uint32_t b : blockers) s.waits.push_back({r, b});
  }
  return s;
}

}  // namespace smart::monitor
