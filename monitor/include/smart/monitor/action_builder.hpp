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

#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

enum class ActionType : uint8_t { kMove = 0, kRotate = 1 };

struct Action {
  uint32_t robot = 0;
  uint32_t seq = 0;
  ActionType type = ActionType::kMove;
  Heading heading = Heading::kEast;  // held during a move; reached by a rotation
  HalfCell from;
  HalfCell to;  // == from for a rotation
  double start_time = 0;
  double end_time = 0;
};

struct ActionPlan {
  std::vector<Action> actions;
  std::vector<uint32_t> offset;  // robots + 1 entries
  std::vector<Heading> initial_heading;
  std::vector<HalfCell> start;  // per robot
  std::size_t moves = 0;        // half-moves
  std::size_t rotations = 0;

  std::size_t robots() const { return offset.empty() ? 0 : offset.size() - 1; }
  uint32_t count(uint32_t robot) const { return offset[robot + 1] - offset[robot]; }
  const Action& at(uint32_t robot, uint32_t seq) const { return actions[offset[robot] + seq]; }
};

ActionPlan build_actions(const Plan& plan, Heading initial_heading = Heading::kEast);

}  // namespace smart::monitor
