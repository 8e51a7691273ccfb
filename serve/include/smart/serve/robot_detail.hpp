// Contract: what the viewer shows of one robot, from the run's instance (plan, actions, ADG)
// and, when the run wrote it, actions.csv (when each action finished). Pure.
// - its planned path in the world frame (start, then every cell it moves to);
// - its Type-2 dependencies both ways, grouped by the other robot: `waits_for` (another robot's
//   action must finish before one of this robot's, SMART §IV-B) and `waited_by`;
// - `steps`, one per action in order: type, finish_s (sim time; null: not finished), `in`
//   [[robot, action, finish_s]] (the Type-2 predecessors and when each finished) and `out`
//   [[robot, action, ready_s]] (the successors and when the other robot had finished everything
//   before that action: from then until this action finishes, it waits for this robot).
// A switchable run (issue 29) is shown with the edges it ended with (`ended`: adg.hpp
// apply_switches + adg_of_orders); an edge the plan did not have carries a 4th element, true
// (the flipped edge, drawn differently).
// With these a replay tells at any time t the current action (the first with finish_s > t), who
// the robot waits for now (`in` of the current action not finished by t) and who waits for it
// now (`out` of its unfinished actions whose ready_s <= t).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "smart/monitor/instance.hpp"
#include "smart/monitor/results_format.hpp"

namespace smart::serve {

// actions.csv (monitor/results.hpp) -> finish time by ADG node, NaN where none. Throws
// std::invalid_argument naming the line of a row that is malformed or not in the plan.
std::vector<double> parse_action_times(std::string_view csv, const monitor::ActionPlan& actions);

// Finished actions over time from the finish times (any order, NaN skipped): {"t_s": [...],
// "finished": [...]}, a step curve of at most max_points points (the last one exact).
nlohmann::json finished_curve(std::vector<double> finish_s, std::size_t max_points = 400);

// Every robot's start and goal cell centre in metres (the plan's first cell and the last one its
// moves reach): {"starts": [[x_m, y_m], ...], "goals": [...]}, for the viewer's marks.
nlohmann::json starts_and_goals(const monitor::Instance& instance, double cell_m);

// The ADG a switchable run ended with: the plan's passing orders with switches.csv's rows
// replayed (monitor/adg.hpp apply_switches; finish_s by node tells which of a pair's stays a row
// meant). Rows naming a location off the map, or robots not adjacent there, are skipped:
// `unmatched` counts them.
monitor::Adg ended_adg(const monitor::Instance& instance,
                       const std::vector<results::SwitchRow>& switches,
                       const std::vector<double>& finish_s, std::size_t* unmatched = nullptr);

// Throws std::out_of_range when robot is not in the instance. finish_s: by ADG node, or empty
// (then every finish_s and ready_s is null).
nlohmann::json robot_detail(const monitor::Instance& instance, uint32_t robot, double cell_m,
                            const std::vector<double>& finish_s = {},
                            const monitor::Adg* ended = nullptr);

}  // namespace smart::serve
