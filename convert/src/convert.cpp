#include "smart/convert/convert.hpp"

namespace smart::wire {

namespace {
smart_msg_Location location(const grid::Grid& grid, grid::HalfCell h, double cell_m) {
  const auto w = grid.to_world(h, cell_m);
  return {w.x_m, w.y_m, h.x2, h.y2};
}
}  // namespace

smart_msg_ActionStep to_wire(const grid::Action& a, const grid::Grid& grid, double cell_m) {
  smart_msg_ActionStep step{};
  step.seq = a.seq;
  step.type = a.type == grid::ActionType::kMove ? smart_msg_ACTION_MOVE : smart_msg_ACTION_ROTATE;
  step.from = location(grid, a.from, cell_m);
  step.to = location(grid, a.to, cell_m);
  step.heading_rad = grid::yaw_rad(a.heading);
  step.plan_time_s = a.start_time;
  return step;
}

agent::AgentAction from_wire(const smart_msg_ActionStep& s) {
  agent::AgentAction a;
  a.seq = s.seq;
  a.kind =
      s.type == smart_msg_ACTION_ROTATE ? agent::ActionKind::kRotate : agent::ActionKind::kMove;
  a.from_x_m = s.from.x_m;
  a.from_y_m = s.from.y_m;
  a.to_x_m = s.to.x_m;
  a.to_y_m = s.to.y_m;
  a.heading_rad = s.heading_rad;
  return a;
}

std::vector<agent::AgentAction> actions_from_wire(const smart_msg_ActionWindow& w) {
  std::vector<agent::AgentAction> out;
  out.reserve(w.actions._length);
  for (uint32_t i = 0; i < w.actions._length; ++i) out.push_back(from_wire(w.actions._buffer[i]));
  return out;
}

smart_msg_RobotState robot_state(uint32_t robot, uint64_t run_id, double time_s,
                                 const agent::PoseSample& p, agent::WheelSpeeds w,
                                 std::size_t queue) {
  smart_msg_RobotState s{};
  s.robot_id = robot;
  s.run_id = run_id;
  s.sim_time_s = time_s;
  s.pose = {p.pose.x_m, p.pose.y_m, p.pose.yaw_rad};
  s.linear_mps = p.linear_mps;
  s.angular_radps = p.angular_radps;
  s.wheel_left_mps = w.left_mps;
  s.wheel_right_mps = w.right_mps;
  s.queue_length = static_cast<uint32_t>(queue);
  return s;
}

smart_msg_Progress progress(uint32_t robot, uint64_t run_id, int64_t finished, int64_t executing) {
  return {robot, run_id, static_cast<int32_t>(finished), static_cast<int32_t>(executing)};
}

smart_msg_Clock to_wire(const Tick& t, uint32_t source_id) {
  return {source_id, t.run_id, t.tick, t.sim_time_s, t.sync_total, t.stop};
}

Tick from_wire(const smart_msg_Clock& c) {
  return {c.run_id, c.tick, c.sim_time_s, c.sync_total, c.stop};
}

}  // namespace smart::wire
