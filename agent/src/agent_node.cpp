#include "smart/agent/agent_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>

#include "smart/convert/convert.hpp"
#include "smart/dds/participant_directory.hpp"

namespace smart::agent {

AgentNode::AgentNode(const dds::Participant& p, const dds::QosProfile& qos, std::size_t robots,
                     std::optional<wire::Bounds> bounds, const std::vector<uint32_t>& speaks_for)
    : robots_(robots),
      bounds_(bounds),
      from_monitor_windows_(dds::admit_roles(p, {"monitor"})),
      from_monitor_clock_(dds::admit_roles(p, {"monitor"})),
      actions_(p, qos, from_monitor_windows_),
      clocks_(p, qos, from_monitor_clock_),
      progress_(p, qos, speaks_for),
      states_(p, qos, speaks_for) {}

void AgentNode::host(Agent& agent, int64_t reported_finished, int64_t reported_executing) {
  const uint32_t robot = agent.robot_id();
  if (hosted_.size() <= robot) hosted_.resize(robot + 1);
  hosted_[robot] = {&agent, reported_finished, reported_executing};
}

std::pair<int64_t, int64_t> AgentNode::unhost(uint32_t robot) {
  const auto r = reported(robot);
  if (robot < hosted_.size()) hosted_[robot] = {};
  return r;
}

std::pair<int64_t, int64_t> AgentNode::reported(uint32_t robot) const {
  if (robot >= hosted_.size() || hosted_[robot].agent == nullptr) return {-1, -1};
  return {hosted_[robot].reported_finished, hosted_[robot].reported_executing};
}

void AgentNode::write(const smart_msg_Progress& p) { progress_.write(p); }
void AgentNode::write(const smart_msg_RobotState& s) { states_.write(s); }

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

// Samples the run's admission kept out of a reader since the last call: counted by sender.
template <class Reader>
void AgentNode::count_refused(const char* topic, dds::WriterAdmission& admission,
                              const Reader& reader) {
  for (const auto& [writer, n] : admission.take_refused()) {
    const auto who = reader.participant_of(writer);
    const std::string sender =
        who ? "participant " + dds::guid_prefix(*who) : std::string("a writer that left");
    if (rejections_.count(topic, dds::kNotRunMember, sender, n)) {
      spdlog::warn("{} samples from {} refused: {}", topic, sender, dds::kNotRunMember);
    }
  }
}

void AgentNode::set_link(const wire::LinkModel& link) {
  to_host_.reset();
  to_monitor_.reset();
  if (link.to_host.active()) to_host_.emplace(link.to_host, link.seed, 0);
  if (link.to_monitor.active()) to_monitor_.emplace(link.to_monitor, link.seed, 1);
}

namespace {
// Keeps `v` in arrival order (a stable insert: equal times keep their sending order).
template <class Delayed>
void insert_by_arrival(std::vector<Delayed>& v, Delayed d) {
  const auto at = std::upper_bound(v.begin(), v.end(), d.at_s,
                                   [](double t, const Delayed& x) { return t < x.at_s; });
  v.insert(at, std::move(d));
}
}  // namespace

// Windows of one robot received at the same time travel together: one draw for all of them.
// DDS keeps the last window per robot, so how many samples of one instant a reader sees depends
// on timing; the draws (and so a lock-step run) must not.
double AgentNode::window_arrival_s(uint32_t robot, double now_s) {
  auto [it, fresh] = window_draws_.try_emplace(robot, now_s, 0.0);
  if (fresh || it->second.first != now_s) {
    it->second = {now_s, to_host_->arrival_s(robot, now_s)};
  }
  return it->second.second;
}

void AgentNode::deliver_windows(double now_s) {
  std::size_t n = 0;
  for (; n < windows_in_flight_.size() && windows_in_flight_[n].at_s <= now_s; ++n) {
    auto& d = windows_in_flight_[n];
    if (Hosted* h = hosted(d.robot)) h->agent->on_window(d.run_id, d.actions);
  }
  windows_in_flight_.erase(windows_in_flight_.begin(), windows_in_flight_.begin() + long(n));
}

std::size_t AgentNode::take_windows(const Accept& accept, double now_s, const Unhosted& unhosted) {
  deliver_windows(now_s);
  count_refused("action", from_monitor_windows_, actions_);
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
    Hosted* h = hosted(m.robot_id);
    if (h == nullptr) {
      if (unhosted) unhosted(m.robot_id, m.run_id, wire::actions_from_wire(m));
      return;
    }
    if (!to_host_) {
      h->agent->on_window(m.run_id, wire::actions_from_wire(m));
      return;
    }
    insert_by_arrival(windows_in_flight_, Delayed{window_arrival_s(m.robot_id, now_s), m.robot_id,
                                                  m.run_id, wire::actions_from_wire(m)});
    deliver_windows(now_s);  // a zero delay arrives now
  });
}

// Progress whose arrival time has come is written; returns the actions newly reported.
uint64_t AgentNode::write_progress(double now_s) {
  uint64_t newly_finished = 0;
  std::size_t n = 0;
  for (; n < progress_in_flight_.size() && progress_in_flight_[n].at_s <= now_s; ++n) {
    const auto& d = progress_in_flight_[n];
    Hosted& h = hosted_[d.robot];
    if (d.finished > h.reported_finished) {
      newly_finished += static_cast<uint64_t>(d.finished - h.reported_finished);
      h.reported_finished = d.finished;  // progress is cumulative: an older one changes nothing
    }
    h.reported_executing = d.executing;
    progress_.write_batched(wire::progress(d.robot, d.run_id, d.finished, d.executing));
  }
  progress_.flush();
  progress_in_flight_.erase(progress_in_flight_.begin(), progress_in_flight_.begin() + long(n));
  return newly_finished;
}

uint64_t AgentNode::publish_progress(double now_s, const ProgressFilter& write_here) {
  if (to_monitor_) {
    queued_.resize(hosted_.size(), {-1, -1});
    for (uint32_t robot = 0; robot < hosted_.size(); ++robot) {
      const Hosted& h = hosted_[robot];
      if (h.agent == nullptr || h.agent->run_id() == 0) continue;
      const std::pair now{h.agent->finished_seq(), h.agent->executing_seq()};
      if (now == queued_[robot]) continue;
      queued_[robot] = now;
      insert_by_arrival(progress_in_flight_, Delayed{to_monitor_->arrival_s(robot, now_s),
                                                     robot,
                                                     h.agent->run_id(),
                                                     {},
                                                     now.first,
                                                     now.second});
    }
    return write_progress(now_s);
  }
  uint64_t newly_finished = 0;
  for (uint32_t robot = 0; robot < hosted_.size(); ++robot) {
    Hosted& h = hosted_[robot];
    if (h.agent == nullptr || h.agent->run_id() == 0) continue;
    const int64_t finished = h.agent->finished_seq(), executing = h.agent->executing_seq();
    if (finished == h.reported_finished && executing == h.reported_executing) continue;
    if (finished > h.reported_finished) {
      newly_finished += static_cast<uint64_t>(finished - h.reported_finished);
    }
    const auto sample = wire::progress(robot, h.agent->run_id(), finished, executing);
    if (!write_here || write_here(sample)) progress_.write_batched(sample);
    h.reported_finished = finished;
    h.reported_executing = executing;
  }
  progress_.flush();
  return newly_finished;
}

void AgentNode::republish_progress() {
  for (uint32_t robot = 0; robot < hosted_.size(); ++robot) {
    const Hosted& h = hosted_[robot];
    if (h.agent == nullptr || h.agent->run_id() == 0) continue;
    if (h.reported_finished < 0 && h.reported_executing < 0) continue;  // nothing reported yet
    progress_.write_batched(
        wire::progress(robot, h.agent->run_id(), h.reported_finished, h.reported_executing));
  }
  progress_.flush();
}

void AgentNode::publish_state(uint32_t robot, uint64_t run_id, double time_s,
                              const PoseSample& pose, WheelSpeeds wheels) {
  const Hosted* h = hosted(robot);
  const std::size_t queue = h ? h->agent->queue_length() : 0;
  states_.write_batched(wire::robot_state(robot, run_id, time_s, pose, wheels, queue));
}

void AgentNode::flush_states() { states_.flush(); }

std::optional<wire::Tick> AgentNode::take_monitor_clock() {
  std::optional<wire::Tick> newest;
  count_refused("clock", from_monitor_clock_, clocks_);
  clocks_.take_each_from([&](const smart_msg_Clock& c, dds_instance_handle_t from) {
    if (c.source_id != dds::kMonitorClockSource || !from_monitor("clock", from, false)) return;
    if (!newest || c.tick >= newest->tick) newest = wire::from_wire(c);
  });
  return newest;
}

}  // namespace smart::agent
