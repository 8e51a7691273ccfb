// Contract: turns a valid plan into per-robot action lists (SMART §IV-B, Hönig et al. 2019):
// - each robot starts facing `initial_heading`; before a move whose direction differs from the
//   current heading, one in-place ROTATE action to the new heading (90° or 180°);
// - waits produce no action;
// - each move A->B becomes two MOVE half-moves, A->mid and mid->B, through the edge midpoint,
//   so a robot can always stop between cells (this removes the deadlock of rotation cycles).
// Plan times: a move from time t0 to t1 gives half-moves [t0, (t0+t1)/2] and [(t0+t1)/2, t1];
// a rotation before it takes [t0, t0]. Actions are stored flat, robot by robot; robot r's
// actions are actions[offset[r] .. offset[r+1]) with seq = index within the robot.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/grid/action.hpp"
#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

ActionPlan build_actions(const Plan& plan, Heading initial_heading = Heading::kEast);

// Appends to `out` one robot's actions for timed steps (steps[0] is where it stands), seqs from
// `first_seq`, starting with `heading`, which is left as the heading after the last action
// (lifelong windows continue from where the previous window's actions end, live_adg.hpp).
// Appending to the caller's vector lets a 10 000-robot window share one allocation.
void append_robot_actions(uint32_t robot, uint32_t first_seq, Heading& heading,
                          const std::vector<PathStep>& steps, std::vector<Action>& out);

}  // namespace smart::monitor
