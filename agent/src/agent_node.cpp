#include "smart/agent/agent_node.hpp"

#include <spdlog/spdlog.h>

#include <cstring>

#include "smart/wire/convert.hpp"

namespace smart::agent {

AgentNode::AgentNode(const dds::Participant& p, const dds::QosProfile& qos, std::size_t robots,
                     std::optional<wire::Bounds> bounds)
    : robots_(robots),
      bounds_(bounds),
      actions_(p, qos),
      clocks_(p, qos),
      progress_(p, qos),
      states_(p, qos) {}

void AgentNode::host(Agent& agent) {
  if (hosted_.size() <= agent.robot_id()) hosted_.resize(agent.robot_id() + 1);
  hosted_[agent.robot_id()].agent = &agent;
}

AgentNode::Hosted* AgentNode::hosted(uint32_t robot) {
  return robot < hosted_.size() && hosted_[robot].agent != nullptr ? &hosted_[robot] : nullptr;
}

bool AgentNode::from_monitor(const char* topic, dds_instance_handle_t from, bool window) {
  const auto p = window ? actions_.publication(from) : clocks_.publication(from);
  std::string why;
  if (!p || p->strength < dds::kMonitorStrengthMin) {
    why = "not a monitor's writer (ownership strength below MONITOR_STRENGTH_MIN)";
  } else if (window || !monitor_) {
    monitor_ = p->participant;  // the strongest monitor's (exclusive ownership of windows)
  } else if (std::memcmp(monitor_->v, p->participant.v, sizeof(p->participant.v)) != 0) {
    why = "clock answer from a monitor whose windows this host does not follow";
  }
  if (why.empty()) return true;
  if (rejections_.count(topic, why)) spdlog::warn("{} sample rejected: {}", topic, why);
  return false;
}

std::size_t AgentNode::take_windows(const Accept& accept) {
  return actions_.take_each_from([&](const smart_msg_ActionWindow& m, dds_instance_handle_t from) {
    if (!from_monitor("action", from, true)) return;
    if (auto why = wire::check_window(m, robots_, bounds_); !why.empty()) {
      if (rejections_.count("action", why)) {
        spdlog::warn("window for robot {} (run {}) rejected: {}", m.robot_id, m.run_id, why);
      }
      return;
    }
    const uint32_t n = m.actions._length;
    const WindowInfo info{m.robot_id, m.run_id, m.total_actions,
                          n == 0 ? 0 : m.actions._buffer[n - 1].seq + 1, n == 0};
    if (accept && !accept(info)) return;
    if (Hosted* h = hosted(m.robot_id)) h->agent->on_window(m.run_id, wire::actions_from_wire(m));
  });
}

uint64_t AgentNode::publish_progress() {
  uint64_t newly_finished = 0;
  for (uint32_t robot = 0; robot < hosted_.size(); ++robot) {
    Hosted& h = hosted_[robot];
    if (h.agent == nullptr || h.agent->run_id() == 0) continue;
    const int64_t finished = h.agent->finished_seq(), executing = h.agent->executing_seq();
    if (finished == h.reported_finished && executing == h.reported_executing) continue;
    if (finished > h.reported_finished) {
      newly_finished += static_cast<uint64_t>(finished - h.reported_finished);
    }
    progress_.write(wire::progress(robot, h.agent->run_id(), finished, executing));
    h.reported_finished = finished;
    h.reported_executing = executing;
  }
  return newly_finished;
}

void AgentNode::republish_progress() {
  for (uint32_t robot = 0; robot < hosted_.size(); ++robot) {
    const Hosted& h = hosted_[robot];
    if (h.agent == nullptr || h.agent->run_id() == 0) continue;
    if (h.reported_finished < 0 && h.reported_executing < 0) continue;  // nothing reported yet
    progress_.write(
        wire::progress(robot, h.agent->run_id(), h.reported_finished, h.reported_executing));
  }
}

void AgentNode::publish_state(uint32_t robot, uint64_t run_id, double time_s,
                              const PoseSample& pose, WheelSpeeds wheels) {
  const Hosted* h = hosted(robot);
  const std::size_t queue = h ? h->agent->queue_length() : 0;
  states_.write(wire::robot_state(robot, run_id, time_s, pose, wheels, queue));
}

std::optional<wire::Tick> AgentNode::take_monitor_clock() {
  std::optional<wire::Tick> newest;
  clocks_.take_each_from([&](const smart_msg_Clock& c, dds_instance_handle_t from) {
    if (c.source_id != dds::kMonitorClockSource || !from_monitor("clock", from, false)) return;
    if (!newest || c.tick >= newest->tick) newest = wire::from_wire(c);
  });
  return newest;
}

}  // namespace smart::agent
