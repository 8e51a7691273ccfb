#include "smart/convert/validate.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <utility>

namespace smart::wire {

namespace {

using Field = std::pair<const char*, double>;

std::string first_not_finite(std::initializer_list<Field> fields, const std::string& where = "") {
  for (const auto& [name, value] : fields) {
    if (!std::isfinite(value)) return "not a finite number: " + where + name;
  }
  return {};
}

std::string robot_range(uint32_t robot, std::size_t robots) {
  if (robots == 0 || robot < robots) return {};
  return "robot " + std::to_string(robot) + " is not in this fleet of " + std::to_string(robots) +
         " robots (check --agents on every process of the run)";
}

std::string outside(double x, double y, const std::optional<Bounds>& b, const std::string& what) {
  if (!b || (x >= b->min_x_m && x <= b->max_x_m && y >= b->min_y_m && y <= b->max_y_m)) return {};
  return what + " lies outside the map";
}

// The action type as its bytes hold it: a forged value is no enumerator of smart_msg_ActionType,
// and loading it as that type is undefined behaviour (UBSan reported it on the forged window).
template <class Step>
uint32_t raw_type(const Step& s) {
  static_assert(sizeof(s.type) == sizeof(uint32_t));
  uint32_t v = 0;
  std::memcpy(&v, &s.type, sizeof v);
  return v;
}

std::string check_step(const smart_msg_ActionStep& s, const std::string& at,
                       const std::optional<Bounds>& bounds) {
  if (const auto t = raw_type(s); t != smart_msg_ACTION_MOVE && t != smart_msg_ACTION_ROTATE) {
    return "unknown action type at " + at;
  }
  auto why = first_not_finite({{"from.x_m", s.from.x_m},
                               {"from.y_m", s.from.y_m},
                               {"to.x_m", s.to.x_m},
                               {"to.y_m", s.to.y_m},
                               {"heading_rad", s.heading_rad},
                               {"plan_time_s", s.plan_time_s}},
                              at + ".");
  if (why.empty()) why = outside(s.from.x_m, s.from.y_m, bounds, at + ".from");
  if (why.empty()) why = outside(s.to.x_m, s.to.y_m, bounds, at + ".to");
  return why;
}

std::string check_motion(const smart_msg_RobotMotion& m, const std::optional<Bounds>& bounds,
                         const std::string& at) {
  auto why = first_not_finite({{"x_m", m.x_m},
                               {"y_m", m.y_m},
                               {"yaw_rad", m.yaw_rad},
                               {"vx_mps", m.vx_mps},
                               {"vy_mps", m.vy_mps},
                               {"w_radps", m.w_radps}},
                              at + ".motion.");
  return why.empty() ? outside(m.x_m, m.y_m, bounds, at) : why;
}

template <class Seq>
bool well_formed(const Seq& s, uint32_t max) {
  return s._length <= max && (s._length == 0 || s._buffer != nullptr);
}

std::string check_queued(const smart_msg_QueuedAction& a, const std::optional<Bounds>& bounds,
                         const std::string& at) {
  if (const auto t = raw_type(a); t != smart_msg_ACTION_MOVE && t != smart_msg_ACTION_ROTATE) {
    return "unknown action type at " + at;
  }
  auto why = first_not_finite({{"from_x_m", a.from_x_m},
                               {"from_y_m", a.from_y_m},
                               {"to_x_m", a.to_x_m},
                               {"to_y_m", a.to_y_m},
                               {"heading_rad", a.heading_rad}},
                              at + ".");
  if (why.empty()) why = outside(a.from_x_m, a.from_y_m, bounds, at + ".from");
  return why.empty() ? outside(a.to_x_m, a.to_y_m, bounds, at + ".to") : why;
}

std::string check_handover(const smart_msg_RobotHandover& h, uint32_t shards, std::size_t robots,
                           const std::optional<Bounds>& bounds, const std::string& at) {
  if (auto why = robot_range(h.robot_id, robots); !why.empty()) return why;
  if (h.to_shard >= shards) return at + " goes to a shard that is not in this sim";
  if (auto why = check_motion(h.motion, bounds, at); !why.empty()) return why;
  if (auto why = first_not_finite({{"target_left_mps", h.target_left_mps},
                                   {"target_right_mps", h.target_right_mps},
                                   {"ramp_from_left_mps", h.ramp_from_left_mps},
                                   {"ramp_from_right_mps", h.ramp_from_right_mps},
                                   {"command_linear_mps", h.command_linear_mps},
                                   {"command_angular_radps", h.command_angular_radps},
                                   {"pose.x_m", h.pose.x_m},
                                   {"pose.y_m", h.pose.y_m},
                                   {"pose.yaw_rad", h.pose.yaw_rad},
                                   {"wheel_left_mps", h.wheel_left_mps},
                                   {"wheel_right_mps", h.wheel_right_mps},
                                   {"stall_until_s", h.stall_until_s},
                                   {"delay_until_s", h.delay_until_s}},
                                  at + ".");
      !why.empty()) {
    return why;
  }
  if (!well_formed(h.pairs, static_cast<uint32_t>(robots)) ||
      !well_formed(h.pending, smart_msg_MAX_WINDOW_ACTIONS)) {
    return at + " has a malformed or too long sequence";
  }
  for (uint32_t i = 0; i < h.pairs._length; ++i) {
    if (auto why = robot_range(h.pairs._buffer[i].other, robots); !why.empty()) return why;
  }
  for (uint32_t i = 0; i < h.pending._length; ++i) {
    const auto& a = h.pending._buffer[i];
    if (auto why = check_queued(a, bounds, at + ".pending[" + std::to_string(i) + "]");
        !why.empty()) {
      return why;
    }
  }
  return {};
}

}  // namespace

Bounds bounds_of(const grid::Grid& grid, double cell_m) {
  return {-cell_m, -cell_m, grid.width() * cell_m, grid.height() * cell_m};
}

std::string check_window(const smart_msg_ActionWindow& w, std::size_t robots,
                         const std::optional<Bounds>& bounds) {
  if (auto why = robot_range(w.robot_id, robots); !why.empty()) return why;
  const uint32_t n = w.actions._length;
  if (n > smart_msg_MAX_WINDOW_ACTIONS) return "window longer than MAX_WINDOW_ACTIONS";
  if (n > 0 && w.actions._buffer == nullptr) return "window without its actions";
  for (uint32_t i = 0; i < n; ++i) {
    const auto& s = w.actions._buffer[i];
    const std::string at = "actions[" + std::to_string(i) + "]";
    if (i > 0 && s.seq != w.actions._buffer[i - 1].seq + 1) return "seqs not consecutive at " + at;
    if (s.seq >= w.total_actions) return "seq past total_actions at " + at;
    if (auto why = check_step(s, at, bounds); !why.empty()) return why;
  }
  return {};
}

std::string check_state(const smart_msg_RobotState& s, std::size_t robots,
                        const std::optional<Bounds>& bounds) {
  if (auto why = robot_range(s.robot_id, robots); !why.empty()) return why;
  auto why = first_not_finite({{"sim_time_s", s.sim_time_s},
                               {"pose.x_m", s.pose.x_m},
                               {"pose.y_m", s.pose.y_m},
                               {"pose.yaw_rad", s.pose.yaw_rad},
                               {"linear_mps", s.linear_mps},
                               {"angular_radps", s.angular_radps},
                               {"wheel_left_mps", s.wheel_left_mps},
                               {"wheel_right_mps", s.wheel_right_mps}});
  return why.empty() ? outside(s.pose.x_m, s.pose.y_m, bounds, "pose") : why;
}

std::string check_progress(const smart_msg_Progress& p, std::size_t robots) {
  if (auto why = robot_range(p.robot_id, robots); !why.empty()) return why;
  if (p.finished_seq < smart_msg_NO_SEQ || p.executing_seq < smart_msg_NO_SEQ) {
    return "seq below NO_SEQ";
  }
  return {};
}

std::string check_clock(const smart_msg_Clock& c) {
  if (auto why = first_not_finite({{"sim_time_s", c.sim_time_s}}); !why.empty()) return why;
  return c.sim_time_s < 0 ? "negative sim_time_s" : "";
}

std::string check_status(const smart_msg_SimStatus& s, std::size_t robots) {
  auto why = first_not_finite({{"sim_time_s", s.sim_time_s},
                               {"min_gap_m", s.min_gap_m},
                               {"wall_time_s", s.wall_time_s},
                               {"peak_rss_mb", s.peak_rss_mb}});
  if (!why.empty()) return why;
  for (const int32_t r : {s.first_contact_a, s.first_contact_b}) {
    if (r < -1 || r >= static_cast<int64_t>(robots)) {
      return "first_contact robot " + std::to_string(r) + " is not one of the " +
             std::to_string(robots) + " robots of this run";
    }
  }
  if (s.robot_contacts > 0 && s.first_contact_a < 0) {
    return "robot_contacts " + std::to_string(s.robot_contacts) + " without the robots involved";
  }
  return {};
}

std::string check_monitor_info(const smart_msg_MonitorInfo& m) {
  if (m.run_id == 0) return "run id 0 (no run)";
  if (m.pid <= 0) return "pid " + std::to_string(m.pid) + " is not a process id";
  if (m.strength < smart_msg_MONITOR_STRENGTH_MIN) {
    return "strength " + std::to_string(m.strength) +
           " is below MONITOR_STRENGTH_MIN: not a monitor";
  }
  auto why = check_printable("host name", m.host, sizeof(m.host));
  return why.empty() ? check_printable("run name", m.run, sizeof(m.run)) : why;
}

std::string check_printable(const char* what, const char* text, std::size_t size) {
  for (std::size_t i = 0; i < size && text[i] != '\0'; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c > 0x7e) {
      return std::string(what) + " has a non-printable byte (" + std::to_string(c) + " at " +
             std::to_string(i) + ")";
    }
  }
  return {};
}

std::string reason_class(const std::string& reason) {
  std::string out;
  out.reserve(reason.size());
  for (const char c : reason) {
    const bool digit = std::isdigit(static_cast<unsigned char>(c)) != 0;
    if (!digit) {
      out += c;
    } else if (out.empty() || out.back() != '#') {
      out += '#';
    }
  }
  return out;
}

bool Rejections::count(const std::string& topic, const std::string& reason,
                       const std::string& sender, uint64_t samples) {
  auto& classes = counts_[topic];
  auto cls = reason_class(reason);
  if (!classes.count(cls) && classes.size() >= kMaxClasses) cls = "other reasons";
  classes[cls] += samples;
  auto& examples = examples_[topic][cls];
  if (examples.size() < kExamples) examples.push_back(reason);
  if (!sender.empty()) {
    const bool known = senders_.count(sender) > 0;
    auto& who = senders_[known || senders_.size() < kMaxSenders ? sender : "other senders"];
    who.samples[topic] += samples;
    if (who.first_reason.empty()) who.first_reason = topic + ": " + reason;
  }
  total_ += samples;
  const uint64_t n = ++per_topic_[topic];
  return n <= 5 || n % 1000 == 0;
}

}  // namespace smart::wire

namespace smart::wire {

std::string check_exchange(const smart_msg_ShardExchange& e, std::size_t robots,
                           const std::optional<Bounds>& bounds) {
  if (e.shards < 2 || e.shards > smart_msg_MAX_SHARDS || e.shard >= e.shards) {
    return "shard " + std::to_string(e.shard) + " of " + std::to_string(e.shards) +
           " is not a shard of a sharded sim (2 to MAX_SHARDS shards, numbered from 0)";
  }
  const auto cap = static_cast<uint32_t>(std::max<std::size_t>(robots, 1));
  if (!well_formed(e.handovers, cap) || !well_formed(e.ghosts, cap) ||
      !well_formed(e.progress, cap) || !well_formed(e.states, cap)) {
    return "a sequence is malformed or longer than the fleet";
  }
  for (uint32_t i = 0; i < e.handovers._length; ++i) {
    const auto at = "handovers[" + std::to_string(i) + "]";
    if (auto why = check_handover(e.handovers._buffer[i], e.shards, robots, bounds, at);
        !why.empty()) {
      return why;
    }
  }
  for (uint32_t i = 0; i < e.ghosts._length; ++i) {
    const auto& g = e.ghosts._buffer[i];
    if (auto why = robot_range(g.robot_id, robots); !why.empty()) return why;
    if (auto why = check_motion(g.motion, bounds, "ghosts[" + std::to_string(i) + "]");
        !why.empty()) {
      return why;
    }
  }
  for (uint32_t i = 0; i < e.progress._length; ++i) {
    if (auto why = check_progress(e.progress._buffer[i], robots); !why.empty()) return why;
  }
  for (uint32_t i = 0; i < e.states._length; ++i) {
    if (auto why = check_state(e.states._buffer[i], robots, bounds); !why.empty()) return why;
  }
  return first_not_finite({{"min_gap_m", e.min_gap_m}, {"peak_rss_mb", e.peak_rss_mb}});
}

}  // namespace smart::wire
