// Contract: what a viewer of a run should see besides the robots' poses (pure; the monitor's ROS 2
// edge, ros_plan_view.hpp, draws it for rviz2):
// - planned_path(): a robot's planned path, the world points of its start and of every move's
//   end (half-cells, grid.to_world), rotations skipped;
// - snapshot(): each robot's activity now — done (every action finished), waiting (its next
//   action is held back by the ADG: an unfinished Type-2 predecessor, i.e. another robot must
//   pass a shared cell first) or moving (its next action is with the robot) — and the current
//   Type-2 waits as (robot, the robot it waits for) pairs, one per blocking robot.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "smart/grid/action.hpp"
#include "smart/grid/grid.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/execution_tracker.hpp"

namespace smart::monitor {

enum class Activity : uint8_t { kMoving, kWaiting, kDone };

struct WaitEdge {
  uint32_t robot = 0;      // the waiting robot
  uint32_t for_robot = 0;  // the robot that must pass first
  bool operator==(const WaitEdge&) const = default;
};

struct PlanSnapshot {
  std::vector<Activity> activity;  // per robot
  std::vector<WaitEdge> waits;     // by robot, then blocking robot
};

std::vector<grid::WorldPoint> planned_path(const grid::ActionPlan& plan, const grid::Grid& grid,
                                           uint32_t robot, double cell_m);

// The Type-2 predecessors (node ids) of an action, as the run orders them now: the ADG's
// (a plain run) or the current passing orders (switchable_tracker.hpp).
using Type2Predecessors = std::function<void(uint32_t node, std::vector<uint32_t>& out)>;

PlanSnapshot snapshot(const grid::ActionPlan& plan, const Execution& execution,
                      const Type2Predecessors& predecessors);
PlanSnapshot snapshot(const grid::ActionPlan& plan, const Adg& adg,
                      const ExecutionTracker& tracker);

}  // namespace smart::monitor
