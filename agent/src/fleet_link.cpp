#include "smart/agent/fleet_link.hpp"

namespace smart::agent {

AgentAction from_wire(const smart_msg_ActionStep& s) {
  AgentAction a;
  a.seq = s.seq;
  a.kind = s.type == smart_msg_ACTION_ROTATE ? ActionKind::kRotate : ActionKind::kMove;
  a.from_x_m = s.from.x_m;
  a.from_y_m = s.from.y_m;
  a.to_x_m = s.to.x_m;
  a.to_y_m = s.to.y_m;
  a.heading_rad = s.heading_rad;
  return a;
}

smart_msg_RobotState make_robot_state(uint32_t robot, uint64_t run_id, double time_s,
                                      const PoseSample& p, WheelSpeeds w, std::size_t queue) {
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

FleetLink::FleetLink(const dds::Participant& p, const dds::QosProfile& qos)
    : action_topic_(p, std::string(dds::kActionTopic)),
      progress_topic_(p, std::string(dds::kProgressTopic)),
      state_topic_(p, std::string(dds::kStateTopic)),
      clock_topic_(p, std::string(dds::kClockTopic)),
      status_topic_(p, std::string(dds::kSimStatusTopic)),
      actions_(p, action_topic_, qos.action.to_dds()),
      clocks_(p, clock_topic_, qos.clock.to_dds()),
      states_in_(p, state_topic_, qos.state.to_dds()),
      progress_(p, progress_topic_, qos.progress.to_dds()),
      states_(p, state_topic_, qos.state.to_dds()),
      clock_out_(p, clock_topic_, qos.clock.to_dds()),
      status_out_(p, status_topic_, qos.progress.to_dds()) {}

std::size_t FleetLink::take_windows(const std::function<void(const ReceivedWindow&)>& fn) {
  ReceivedWindow w;
  return actions_.take_each([&](const smart_msg_ActionWindow& m) {
    w.robot_id = m.robot_id;
    w.run_id = m.run_id;
    w.total_actions = m.total_actions;
    w.actions.clear();
    for (uint32_t i = 0; i < m.actions._length; ++i)
      w.actions.push_back(from_wire(m.actions._buffer[i]));
    w.end_seq = w.actions.empty() ? 0 : w.actions.back().seq + 1;
    fn(w);
  });
}

std::size_t FleetLink::take_states(const std::function<void(const smart_msg_RobotState&)>& fn) {
  return states_in_.take_each(fn);
}

std::optional<smart_msg_Clock> FleetLink::take_monitor_clock() {
  std::optional<smart_msg_Clock> best;
  clocks_.take_each([&](const smart_msg_Clock& c) {
    if (c.source_id != kMonitorClockSource) return;
    if (!best || c.tick >= best->tick) best = c;
  });
  return best;
}

void FleetLink::publish_progress(uint32_t robot, uint64_t run_id, int64_t finished,
                                 int64_t executing) {
  progress_.write(smart_msg_Progress{robot, run_id, static_cast<int32_t>(finished),
                                     static_cast<int32_t>(executing)});
}

void FleetLink::publish_state(const smart_msg_RobotState& s) { states_.write(s); }
void FleetLink::publish_clock(const smart_msg_Clock& c) { clock_out_.write(c); }
void FleetLink::publish_sim_status(const smart_msg_SimStatus& s) { status_out_.write(s); }

}  // namespace smart::agent
