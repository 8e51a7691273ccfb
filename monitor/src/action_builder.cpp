#include "smart/monitor/action_builder.hpp"

namespace smart::monitor {

void append_robot_actions(uint32_t robot, uint32_t first_seq, Heading& heading,
                          const std::vector<PathStep>& steps, std::vector<Action>& out) {
  uint32_t seq = first_seq;
  for (std::size_t k = 0; k + 1 < steps.size(); ++k) {
    const auto& a = steps[k];
    const auto& b = steps[k + 1];
    if (a.cell == b.cell) continue;  // a wait: no action
    const Heading dir = heading_of_step(a.cell, b.cell);
    const HalfCell ha = HalfCell::of(a.cell), hb = HalfCell::of(b.cell);
    if (dir != heading) {
      out.push_back({robot, seq++, ActionType::kRotate, dir, ha, ha, a.time, a.time});
      heading = dir;
    }
    const HalfCell mid = HalfCell::midpoint(a.cell, b.cell);
    const double t_mid = 0.5 * (a.time + b.time);
    out.push_back({robot, seq++, ActionType::kMove, dir, ha, mid, a.time, t_mid});
    out.push_back({robot, seq++, ActionType::kMove, dir, mid, hb, t_mid, b.time});
  }
}

ActionPlan build_actions(const Plan& plan, Heading initial_heading) {
  ActionPlan out;
  out.offset.reserve(plan.paths.size() + 1);
  out.offset.push_back(0);
  std::size_t moves = 0;
  for (const auto& p : plan.paths) moves += p.steps.size();
  out.actions.reserve(3 * moves);
  for (const auto& path : plan.paths) {
    Heading heading = initial_heading;
    out.initial_heading.push_back(initial_heading);
    out.start.push_back(path.steps.empty() ? HalfCell{} : HalfCell::of(path.steps.front().cell));
    const std::size_t first = out.actions.size();
    append_robot_actions(static_cast<uint32_t>(path.robot), 0, heading, path.steps, out.actions);
    for (std::size_t i = first; i < out.actions.size(); ++i) {
      ++(out.actions[i].type == ActionType::kMove ? out.moves : out.rotations);
    }
    out.offset.push_back(static_cast<uint32_t>(out.actions.size()));
  }
  return out;
}

}  // namespace smart::monitor
