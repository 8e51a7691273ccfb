#include "shard_wire.hpp"

#include "smart/dds/sequence.hpp"

namespace smart::sim::detail {

namespace {

using dds::borrow;
using dds::copy_of;

smart_msg_RobotMotion to_wire(const RobotMotion& m) {
  return {m.x_m, m.y_m, m.yaw_rad, m.vx_mps, m.vy_mps, m.w_radps};
}
RobotMotion from_wire(const smart_msg_RobotMotion& m) {
  return {m.x_m, m.y_m, m.yaw_rad, m.vx_mps, m.vy_mps, m.w_radps};
}

smart_msg_QueuedAction to_wire(const agent::AgentAction& a) {
  return {a.seq,
          a.kind == agent::ActionKind::kMove ? smart_msg_ACTION_MOVE : smart_msg_ACTION_ROTATE,
          a.from_x_m,
          a.from_y_m,
          a.to_x_m,
          a.to_y_m,
          a.heading_rad};
}
agent::AgentAction from_wire(const smart_msg_QueuedAction& a) {
  return {a.seq,
          a.type == smart_msg_ACTION_MOVE ? agent::ActionKind::kMove : agent::ActionKind::kRotate,
          a.from_x_m,
          a.from_y_m,
          a.to_x_m,
          a.to_y_m,
          a.heading_rad};
}

// The scalar fields; the sequences are filled in by the caller.
smart_msg_RobotHandover to_wire(const RobotHandover& h) {
  const auto& p = h.physics;
  const auto& a = h.agent;
  smart_msg_RobotHandover m{};
  m.robot_id = h.robot;
  m.to_shard = h.to_shard;
  m.motion = to_wire(p.motion);
  m.target_left_mps = p.target_l_mps;
  m.target_right_mps = p.target_r_mps;
  m.ramp_from_left_mps = p.ramp_from_l_mps;
  m.ramp_from_right_mps = p.ramp_from_r_mps;
  m.wall_last_contact_s = p.wall_last_contact_s;
  m.awake = p.awake;
  m.command_linear_mps = a.last_command.linear_mps;
  m.command_angular_radps = a.last_command.angular_radps;
  m.queue_run_id = a.queue.run_id;
  m.queue_started = a.queue.started;
  m.finished_seq = static_cast<int32_t>(a.queue.finished_seq);
  m.duplicates = a.queue.duplicates;
  m.pose = {a.pose.pose.x_m, a.pose.pose.y_m, a.pose.pose.yaw_rad};
  m.pose_linear_mps = a.pose.linear_mps;
  m.pose_angular_radps = a.pose.angular_radps;
  m.pose_stamp_s = a.pose.stamp_s;
  m.pose_valid = a.pose.valid;
  m.wheel_left_mps = a.wheels.left_mps;
  m.wheel_right_mps = a.wheels.right_mps;
  m.stale = a.stale;
  m.had_pose = a.had_pose;
  m.watchdog_stops = a.watchdog_stops;
  m.now_s = a.now_s;
  m.stall_until_s = a.stall_until_s;
  m.stall_checked_seq = static_cast<int32_t>(a.stall_checked_seq);
  m.last_front_move = a.last_front_move;
  m.last_front_heading_rad = a.last_front_heading_rad;
  m.stalls = a.stalls;
  m.delay_until_s = a.delay_until_s;
  m.delay_tick = a.delay_tick;
  m.delays = a.delays;
  m.reported_finished = static_cast<int32_t>(h.reported_finished);
  m.reported_executing = static_cast<int32_t>(h.reported_executing);
  return m;
}

RobotHandover from_wire(const smart_msg_RobotHandover& m) {
  RobotHandover h;
  h.robot = m.robot_id;
  h.to_shard = m.to_shard;
  auto& p = h.physics;
  p = {from_wire(m.motion),
       m.target_left_mps,
       m.target_right_mps,
       m.ramp_from_left_mps,
       m.ramp_from_right_mps,
       m.wall_last_contact_s,
       m.awake,
       {}};
  for (uint32_t i = 0; i < m.pairs._length; ++i) {
    p.pair_last_contact_s.emplace_back(m.pairs._buffer[i].other, m.pairs._buffer[i].last_s);
  }
  auto& a = h.agent;
  a.last_command = {m.command_linear_mps, m.command_angular_radps};
  a.queue = {m.queue_run_id, m.queue_started, m.finished_seq, {}, m.duplicates};
  for (uint32_t i = 0; i < m.pending._length; ++i) {
    a.queue.pending.push_back(from_wire(m.pending._buffer[i]));
  }
  a.pose = {{m.pose.x_m, m.pose.y_m, m.pose.yaw_rad},
            m.pose_linear_mps,
            m.pose_angular_radps,
            m.pose_stamp_s,
            m.pose_valid};
  a.wheels = {m.wheel_left_mps, m.wheel_right_mps};
  a.stale = m.stale;
  a.had_pose = m.had_pose;
  a.watchdog_stops = m.watchdog_stops;
  a.now_s = m.now_s;
  a.stall_until_s = m.stall_until_s;
  a.stall_checked_seq = m.stall_checked_seq;
  a.last_front_move = m.last_front_move;
  a.last_front_heading_rad = m.last_front_heading_rad;
  a.stalls = m.stalls;
  a.delay_until_s = m.delay_until_s;
  a.delay_tick = m.delay_tick;
  a.delays = m.delays;
  h.reported_finished = m.reported_finished;
  h.reported_executing = m.reported_executing;
  return h;
}

}  // namespace

ExchangeBuffer::ExchangeBuffer(const Exchange& e) : progress_(e.progress), states_(e.states) {
  for (const auto& h : e.outbox.handovers) {
    handovers_.push_back(to_wire(h));
    auto& pairs = pairs_.emplace_back();
    for (const auto& [other, t] : h.physics.pair_last_contact_s) pairs.push_back({other, t});
    auto& pending = pending_.emplace_back();
    for (const auto& a : h.agent.queue.pending) pending.push_back(to_wire(a));
  }
  for (std::size_t i = 0; i < handovers_.size(); ++i) {
    borrow(handovers_[i].pairs, pairs_[i]);
    borrow(handovers_[i].pending, pending_[i]);
  }
  for (const auto& g : e.outbox.ghosts) ghosts_.push_back({g.robot, to_wire(g.motion)});
  msg_.shard = e.shard;
  msg_.shards = e.shards;
  msg_.run_id = e.run_id;
  msg_.tick = e.tick;
  msg_.last = e.last;
  borrow(msg_.handovers, handovers_);
  borrow(msg_.ghosts, ghosts_);
  borrow(msg_.progress, progress_);
  borrow(msg_.states, states_);
  msg_.finished_total = e.finished_total;
  msg_.robot_contacts = e.contacts.robot_robot_events;
  msg_.wall_contacts = e.contacts.robot_wall_events;
  msg_.min_gap_m = e.contacts.min_gap_m;
  msg_.first_contact_a = static_cast<int32_t>(e.contacts.first_pair_a);
  msg_.first_contact_b = static_cast<int32_t>(e.contacts.first_pair_b);
  msg_.peak_rss_mb = e.peak_rss_mb;
}

Exchange from_wire(const smart_msg_ShardExchange& m) {
  Exchange e;
  e.shard = m.shard;
  e.shards = m.shards;
  e.run_id = m.run_id;
  e.tick = m.tick;
  e.last = m.last;
  for (uint32_t i = 0; i < m.handovers._length; ++i) {
    e.outbox.handovers.push_back(from_wire(m.handovers._buffer[i]));
  }
  for (uint32_t i = 0; i < m.ghosts._length; ++i) {
    e.outbox.ghosts.push_back(
        {m.ghosts._buffer[i].robot_id, from_wire(m.ghosts._buffer[i].motion)});
  }
  e.progress = copy_of<smart_msg_Progress>(m.progress);
  e.states = copy_of<smart_msg_RobotState>(m.states);
  e.finished_total = m.finished_total;
  e.contacts.robot_robot_events = m.robot_contacts;
  e.contacts.robot_wall_events = m.wall_contacts;
  e.contacts.min_gap_m = m.min_gap_m;
  e.contacts.first_pair_a = m.first_contact_a;
  e.contacts.first_pair_b = m.first_contact_b;
  e.peak_rss_mb = m.peak_rss_mb;
  return e;
}

}  // namespace smart::sim::detail
