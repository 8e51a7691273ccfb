// Contract: the action vocabulary of an executed plan (SMART §IV-B; built by monitor/
// action_builder.hpp): an in-place ROTATE to a heading, or a MOVE half-move between half cells
// holding a heading. Actions are stored flat, robot by robot: robot r's actions are
// actions[offset[r] .. offset[r+1]) with seq = index within the robot. Plan times in timesteps.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::grid {

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

}  // namespace smart::grid
