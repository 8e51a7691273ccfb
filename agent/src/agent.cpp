#include "smart/agent/agent.hpp"

#include <cmath>

#include "smart/agent/uncertainty.hpp"

namespace smart::agent {

namespace {
// The model this robot drives with: its top speed scaled by its speed factor.
RobotModel with_speed_factor(RobotModel m, uint32_t robot) {
  m.max_speed_mps *= speed_factor(m.uncertainty, robot);
  return m;
}
}  // namespace

Agent::Agent(AgentConfig config, DriveBackend& drive, PoseSource& pose)
    : config_(std::move(config)),
      drive_(drive),
      pose_(pose),
      controller_(with_speed_factor(config_.model, config_.robot_id), config_.period_s) {}

LifecycleResult Agent::named(LifecycleResult r) const {
  if (!r.ok()) r.message = "robot " + std::to_string(config_.robot_id) + ": " + r.message;
  return r;
}

LifecycleResult Agent::configure() {
  if (state_ != LifecycleState::kUnconfigured) return LifecycleResult::success();
  auto r = drive_.configure();
  if (r.ok()) state_ = LifecycleState::kInactive;
  return named(std::move(r));
}

LifecycleResult Agent::activate() {
  if (state_ == LifecycleState::kUnconfigured) {
    if (auto r = configure(); !r.ok()) return r;
  }
  auto r = drive_.activate();
  if (r.ok()) state_ = LifecycleState::kActive;
  return named(std::move(r));
}

LifecycleResult Agent::deactivate() {
  if (state_ == LifecycleState::kUnconfigured) return LifecycleResult::success();
  auto r = drive_.deactivate();
  controller_.reset();
  command_ = {};
  state_ = LifecycleState::kInactive;
  return named(std::move(r));
}

ActionQueue::Result Agent::on_window(uint64_t run_id, const std::vector<AgentAction>& window) {
  return queue_.apply(run_id, window);
}

AgentSnapshot Agent::snapshot() const {
  return {controller_.last(),
          queue_.snapshot(),
          pose_sample_,
          command_,
          stale_,
          had_pose_,
          watchdog_stops_,
          now_s_,
          stall_until_s_,
          stall_checked_seq_,
          last_front_move_,
          last_front_heading_rad_,
          stalls_,
          delay_until_s_,
          delay_tick_,
          delays_};
}

void Agent::restore(const AgentSnapshot& s) {
  controller_.restore(s.last_command);
  queue_.restore(s.queue);
  pose_sample_ = s.pose;
  command_ = s.wheels;
  stale_ = s.stale;
  had_pose_ = s.had_pose;
  watchdog_stops_ = s.watchdog_stops;
  now_s_ = s.now_s;
  stall_until_s_ = s.stall_until_s;
  stall_checked_seq_ = s.stall_checked_seq;
  last_front_move_ = s.last_front_move;
  last_front_heading_rad_ = s.last_front_heading_rad;
  stalls_ = s.stalls;
  delay_until_s_ = s.delay_until_s;
  delay_tick_ = s.delay_tick;
  delays_ = s.delays;
}

void Agent::write(Twist t) {
  command_ = controller_.wheels(t);
  drive_.set_wheel_speeds(command_);
}

void Agent::step(double now_s) {
  if (state_ != LifecycleState::kActive) return;
  now_s_ = now_s;
  pose_sample_ = pose_.read();
  const bool stale = !pose_sample_.valid || now_s - pose_sample_.stamp_s > config_.pose_timeout_s;
  if (stale) {
    // Watchdog: without a fresh pose the robot is driving blind; stop now, not gradually.
    // Waiting for a source's first pose (start-up) is not a stop: nothing was lost.
    if (!stale_ && had_pose_) ++watchdog_stops_;
    stale_ = true;
    drive_.stop();
    controller_.reset();
    command_ = {};
    return;
  }
  stale_ = false;
  had_pose_ = true;
  write(update());
}

void Agent::maybe_stall() {
  const AgentAction& a = queue_.front();
  const auto seq = static_cast<int64_t>(a.seq);
  if (seq == stall_checked_seq_) return;
  // An action starts from rest unless it continues a run of moves along one heading (those are
  // driven without stopping).
  const bool continues_run = a.kind == ActionKind::kMove && last_front_move_ &&
                             std::abs(last_front_heading_rad_ - a.heading_rad) < 1e-9;
  stall_checked_seq_ = seq;
  last_front_move_ = a.kind == ActionKind::kMove;
  last_front_heading_rad_ = a.heading_rad;
  if (!continues_run &&
      stalls_before(config_.model.uncertainty, config_.robot_id, static_cast<uint32_t>(seq))) {
    stall_until_s_ = now_s_ + config_.model.uncertainty.stall_s;
    ++stalls_;
  }
}

void Agent::maybe_delay() {
  const auto& u = config_.model.uncertainty;
  if (!u.delays()) return;
  const auto tick = static_cast<int64_t>(std::floor(now_s_ / kDelayTickS + 1e-9));
  if (tick <= delay_tick_) return;
  delay_tick_ = tick;
  if (delayed()) return;  // one event at a time
  if (const double d = delay_at(u, config_.robot_id, static_cast<uint64_t>(tick)); d > 0) {
    delay_until_s_ = now_s_ + d;
    ++delays_;
  }
}

Twist Agent::update() {
  maybe_delay();
  if (delayed()) {
    bool stopped = false;
    return controller_.brake(&stopped);  // a safe stop where it is, even between cells
  }
  // A few actions may end within one period (a rotation already aligned, a passed half-move).
  for (int guard = 0; guard < 64; ++guard) {
    if (queue_.empty()) {
      bool stopped = false;
      return controller_.brake(&stopped);
    }
    maybe_stall();
    if (stalled()) {
      bool stopped = false;
      return controller_.brake(&stopped);
    }
    const AgentAction& a = queue_.front();
    if (a.kind == ActionKind::kRotate) {
      bool done = false;
      const Twist t = controller_.rotate(pose_sample_, a.heading_rad, &done);
      if (!done) return t;
      queue_.finish_front();
      continue;
    }
    // Merge the run of consecutive moves along this heading.
    const auto& q = queue_.pending();
    std::size_t last = 0;
    while (last + 1 < q.size() && q[last + 1].kind == ActionKind::kMove &&
           std::abs(q[last + 1].heading_rad - a.heading_rad) < 1e-9) {
      ++last;
    }
    const Segment seg{a.from_x_m, a.from_y_m, q[last].to_x_m, q[last].to_y_m, a.heading_rad};
    // Half-moves whose end the robot has passed are finished (all but the run's last).
    const double along = Controller::progress_m(pose_sample_.pose, seg);
    while (queue_.pending().size() > 1 && last > 0) {
      const AgentAction& f = queue_.front();
      const double end_along = (f.to_x_m - seg.start_x_m) * std::cos(seg.heading_rad) +
                               (f.to_y_m - seg.start_y_m) * std::sin(seg.heading_rad);
      if (along < end_along) break;
      queue_.finish_front();
      --last;
    }
    bool done = false;
    const Twist t = controller_.drive(pose_sample_, seg, &done);
    if (!done || last > 0) return t;
    queue_.finish_front();
  }
  bool stopped = false;
  return controller_.brake(&stopped);
}

}  // namespace smart::agent
