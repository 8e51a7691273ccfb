#include "smart/monitor/run_supervisor.hpp"

#include <algorithm>
#include <cmath>

namespace smart::monitor {

std::string_view to_string(Outcome o) {
  switch (o) {
    case Outcome::kRunning:
      return "running";
    case Outcome::kSuccess:
      return "success";
    case Outcome::kDeadlock:
      return "deadlock";
    case Outcome::kStalled:
      return "stalled";
    case Outcome::kTimeLimit:
      return "time limit";
    case Outcome::kHostLost:
      return "host lost";
    case Outcome::kStopped:
      return results::summary_key::kOutcomeStopped;
    case Outcome::kCollision:
      return "collision";
    case Outcome::kOffGoal:
      return "not at goal";
    case Outcome::kRefused:
      return "refused";
    case Outcome::kUnverified:
      return "unverified";
  }
  return "unknown";
}

RunSupervisor::RunSupervisor(const Instance& instance, const SupervisorConfig& config,
                             RunWriter& writer)
    : in_(&instance), config_(config), writer_(writer) {
  if (config.switchable) {
    auto orders = passing_orders(instance.actions, instance.grid, instance.adg.footprint);
    unreplayed_switches_ = apply_switches(orders, config.resume_switches);
    res_.switches = config.resume_switches;  // switches.csv lists the run's, before and after
    switchable_.emplace(instance.actions, std::move(orders), config.switch_options,
                        !config.resume_switches.empty());
    exec_ = &*switchable_;
    res_.execution = execution_name(config.switch_options);
  } else {
    tracker_.emplace(instance.actions, instance.adg);
    exec_ = &*tracker_;
  }
  const std::size_t n = instance.actions.robots();
  init(n);
  for (uint32_t r = 0; r < n; ++r) {
    const uint32_t count = instance.actions.count(r);
    res_.robots[r].actions = count;
    const auto goal = count ? instance.actions.at(r, count - 1).to : instance.actions.start[r];
    goal_.push_back(instance.grid.to_world(goal, config.cell_m));
  }
  res_.total_actions = instance.actions.actions.size();
  res_.action_finish_s.assign(res_.total_actions, std::nan(""));
}

RunSupervisor::RunSupervisor(Execution& execution, const SupervisorConfig& config,
                             RunWriter& writer)
    : config_(config), writer_(writer), exec_(&execution) {
  if (execution.switches() != nullptr) {
    res_.execution = execution_name(config.switch_options);
  }
  init(execution.robots());
}

void RunSupervisor::init(std::size_t n) {
  sent_ = wire::SyncCounter(n);
  waiting_.assign(n, 0);
  wait_cause_.assign(n, {});
  held_seq_.assign(n, kNoneHeld);
  robot_seen_s_.assign(n, 0.0);
  last_pose_.resize(n);
  seen_done_.assign(n, 0);
  res_.robots.resize(n);
  res_.goal_tolerance_m =
      config_.goal_tolerance_m > 0 ? config_.goal_tolerance_m : 0.25 * config_.cell_m;
  res_.run_id = config_.run_id;
  if (!config_.lockstep && config_.robot_radius_m > 0) {
    separation_.emplace(n, config_.robot_radius_m);
  }
}

// A lifelong run's time passes: its windows may grow (replanning); push what changed.
void RunSupervisor::advance_time(double time_s) {
  if (!exec_->lifelong() || over()) return;
  std::vector<uint32_t> sent(exec_->robots());
  for (uint32_t r = 0; r < sent.size(); ++r) sent[r] = static_cast<uint32_t>(sent_.mark(r));
  const auto changed = exec_->on_time(time_s, sent);
  take_switches();
  for (const uint32_t r : changed) publish_window(r);
  res_.total_actions = exec_->total();
}

void RunSupervisor::end(Outcome outcome, std::string error) {
  res_.outcome = outcome;
  res_.error = std::move(error);
}

void RunSupervisor::start(double now_s) {
  std::fill(robot_seen_s_.begin(), robot_seen_s_.end(), now_s);
  if (switchable_) switchable_->unpause();  // rebuilt (resume()): it may switch again
  take_switches();  // the first windows may follow switches made at once (anticipation)
  for (uint32_t r = 0; r < exec_->robots(); ++r) publish_window(r);
}

void RunSupervisor::take_switches() {
  const auto* all = exec_->switches();
  if (all == nullptr) return;
  for (; taken_switches_ < all->size(); ++taken_switches_) {
    res_.switches.push_back((*all)[taken_switches_]);
    writer_.switched((*all)[taken_switches_]);
  }
}

void RunSupervisor::publish_window(uint32_t robot) {
  const auto w = exec_->window(robot, config_.window_cap);
  writer_.publish_window(robot, res_.run_id, w);
  if (!w.empty()) sent_.raise(robot, w.end);
}

void RunSupervisor::on_clock(const wire::Tick& t, double now_s) {
  if (t.run_id != 0 && t.run_id != res_.run_id) return;
  if (!sim_seen_) {
    res_.first_progress_wall_s = now_s;
    if (res_.resumed && config_.lockstep) {
      // Metrics restart here: what happened before the resume is not known.
      res_.resumed_at_s = last_finish_sim_s_ = last_metrics_sim_s_ = t.sim_time_s;
    }
  }
  sim_seen_ = true;
  last_sim_sign_s_ = now_s;
  newest_tick_ = std::max(newest_tick_, t.tick);
  if (!config_.lockstep || over()) return;
  handshake_.on_tick(t);
  take_held_progress(now_s);
}

void RunSupervisor::on_progress(const ProgressEvent& p, double now_s) {
  if (over() || p.run_id != res_.run_id) return;
  if (!config_.lockstep) {
    // Real time (hardware, mixed runs): hosts run on their own clocks, so the run is timed on
    // the monitor's wall clock.
    res_.sim_time_s = now_s;
    apply_progress(p, now_s);
    return;
  }
  // Lock-step: progress belongs to the tick that announces it, whichever arrives first.
  hold_progress(p);
  take_held_progress(now_s);
}

// Taken as it arrived, the progress of one tick reached the execution in an order that DDS
// decides (reader batches, a host's held-back reports), and what a switchable execution decides
// on progress depends on it: a lookahead run on the LoRR game problem switched a chain at 20.6 s
// in one run and at 21.0 s in the next (docs/execution.md). Held, it is taken in robot order.
void RunSupervisor::hold_progress(const ProgressEvent& p) {
  // Progress no host could honestly send (no such robot, an action never enqueued) is rejected
  // now, so it cannot keep the tick from adding up.
  if (p.robot >= held_seq_.size() || p.finished_seq >= int64_t{exec_->enqueued(p.robot)}) {
    apply_progress(p, res_.sim_time_s);  // rejected, and described in notes()
    return;
  }
  int64_t& held = held_seq_[p.robot];
  const int64_t have = std::max(held, static_cast<int64_t>(exec_->finished(p.robot)) - 1);
  if (p.finished_seq <= have) return;  // stale: changes nothing
  if (held == kNoneHeld) held_robots_.push_back(p.robot);
  held_gain_ += static_cast<uint64_t>(p.finished_seq - have);
  held = p.finished_seq;
}

// Once the held progress adds up to the pending tick's sync_total: taken, and the tick answered.
void RunSupervisor::take_held_progress(double now_s) {
  const auto& tick = handshake_.pending();
  if (!tick || exec_->finished_total() + held_gain_ != tick->sync_total) return;
  std::sort(held_robots_.begin(), held_robots_.end());
  for (const uint32_t r : held_robots_) {
    apply_progress({r, res_.run_id, held_seq_[r]}, tick->sim_time_s);
    held_seq_[r] = kNoneHeld;
  }
  held_robots_.clear();
  held_gain_ = 0;
  try_answer(now_s);
}

void RunSupervisor::apply_progress(const ProgressEvent& p, double sim_time_s) {
  if (p.run_id != res_.run_id) return;
  const uint32_t before = p.robot < exec_->robots() ? exec_->finished(p.robot) : 0;
  const auto u = exec_->on_progress(p.robot, p.finished_seq, sim_time_s);
  if (u.result == ProgressResult::kRejected) {
    if (res_.rejected_progress++ < 5) notes_.push_back("progress rejected: " + u.reason);
    return;
  }
  if (u.result != ProgressResult::kAdvanced) return;
  last_finish_sim_s_ = sim_time_s;
  if (in_) {
    const uint32_t first = in_->actions.offset[p.robot];
    for (uint32_t s = before; s < exec_->finished(p.robot); ++s) {
      res_.action_finish_s[first + s] = sim_time_s;
      writer_.action_finished(p.robot, s, sim_time_s);
    }
  }
  take_switches();  // before the windows they change
  for (const uint32_t r : u.robots_changed) {
    publish_window(r);
    if (exec_->robot_done(r)) mark_done(r, sim_time_s);
  }
  res_.finished_actions = exec_->finished_total();
}

PlanSnapshot RunSupervisor::plan_snapshot() const {
  if (switchable_) {
    return snapshot(in_->actions, *switchable_, [this](uint32_t node, std::vector<uint32_t>& out) {
      switchable_->predecessors(node, out);
    });
  }
  return snapshot(in_->actions, in_->adg, *tracker_);
}

void RunSupervisor::try_answer(double now_s) {
  if (!handshake_.ready(exec_->finished_total())) return;
  const double sim_time_s = handshake_.pending()->sim_time_s;
  res_.sim_time_s = sim_time_s;
  advance_time(sim_time_s);
  update_waiting(sim_time_s);
  check_end();
  writer_.answer_tick(handshake_.answer(res_.run_id, sent_.total(), over()));
  handshake_.sent(now_s);
}

// Waiting = not done and nothing enqueued to execute, over the sim time since the last call.
void RunSupervisor::update_waiting(double sim_time_s) {
  const double dt = sim_time_s - last_metrics_sim_s_;
  last_metrics_sim_s_ = sim_time_s;
  for (uint32_t r = 0; r < waiting_.size(); ++r) {
    const bool w = !exec_->robot_done(r) && exec_->enqueued(r) == exec_->finished(r);
    if (w) {
      res_.robots[r].waiting_time_s += dt;
      if (!waiting_[r]) ++res_.robots[r].stops;
      count_wait_cause(r, dt, sim_time_s, !waiting_[r]);
    }
    waiting_[r] = w;
  }
}

// Asking reads the blocker's actions, a few cache misses a robot: asked every tick it took 15 %
// of the monitor's CPU on SMART's 1000-robot plan (docs/performance.md). So a robot is asked when
// it begins to wait and then every kWaitCauseRefreshS of sim time; each tick's wait goes to the
// cause it told last (the causes still sum to the waiting).
void RunSupervisor::count_wait_cause(uint32_t robot, double dt, double sim_time_s, bool began) {
  auto& told = wait_cause_[robot];
  if (began || sim_time_s >= told.next_s) {
    const auto cause = exec_->wait_cause(robot);
    if (!cause) return;
    told = {*cause, sim_time_s + kWaitCauseRefreshS};
  }
  if (!res_.waiting_by_cause_s) res_.waiting_by_cause_s.emplace();
  (*res_.waiting_by_cause_s)[static_cast<std::size_t>(told.cause)] += dt;
}

void RunSupervisor::check_end() {
  if (over()) return;
  if (exec_->complete()) {
    end(Outcome::kSuccess, "");
  } else if (exec_->deadlocked()) {
    end(Outcome::kDeadlock, "deadlock: no robot has an action it may execute, yet " +
                                std::to_string(exec_->total() - exec_->finished_total()) +
                                " actions remain; the action dependency graph cannot progress");
  } else if (res_.sim_time_s - last_finish_sim_s_ > config_.stall_timeout_s) {
    end(Outcome::kStalled, "stalled: no action finished for " +
                               std::to_string(config_.stall_timeout_s) +
                               " s of sim time; robots may be stuck against each other or a wall");
  } else if (config_.max_sim_time_s > 0 && res_.sim_time_s > config_.max_sim_time_s) {
    end(Outcome::kTimeLimit,
        "time limit: sim time passed " + std::to_string(config_.max_sim_time_s) + " s");
  }
}

void RunSupervisor::mark_done(uint32_t robot, double sim_time_s) {
  res_.robots[robot].finish_time_s = sim_time_s;
  seen_done_[robot] = 0;  // the pose that counts is one seen from now on
}

bool RunSupervisor::on_state(const StateEvent& s, double now_s) {
  if (s.run_id != res_.run_id && s.run_id != 0) return false;
  if (s.robot >= robot_seen_s_.size()) return false;
  robot_seen_s_[s.robot] = now_s;
  if (s.run_id != res_.run_id) return false;
  last_pose_[s.robot] = {s.x_m, s.y_m};
  if (exec_->robot_done(s.robot)) seen_done_[s.robot] = 1;
  if (separation_) {
    separation_->on_pose(s.robot, s.x_m, s.y_m, now_s);
    res_.pose_contacts = separation_->contacts();
    res_.pose_min_gap_m = separation_->min_gap_m();
    res_.first_pose_contact = separation_->first_contact();
  }
  return true;
}

void RunSupervisor::on_sim_status(const SimStatusEvent& s) {
  if (s.run_id != res_.run_id && s.run_id != 0) return;
  res_.have_sim_status = true;
  status_sim_time_s_ = std::max(status_sim_time_s_, s.sim_time_s);
  res_.robot_contacts = s.robot_contacts;
  if (s.first_contact_a >= 0 && s.first_contact_b >= 0) {
    // The status after a contact comes with the sim time it was sent (it is sent on change).
    if (!res_.first_collision) res_.first_collision_s = s.sim_time_s;
    res_.first_collision = {static_cast<uint32_t>(s.first_contact_a),
                            static_cast<uint32_t>(s.first_contact_b)};
  }
  res_.wall_contacts = s.wall_contacts;
  if (s.min_gap_m < 1e8) res_.min_gap_m = s.min_gap_m;
  if (s.peak_rss_mb > 0) {
    res_.host_peak_rss_mb = std::max(res_.host_peak_rss_mb.value_or(0.0), s.peak_rss_mb);
  }
}

bool RunSupervisor::has_final_sim_status() const {
  if (!res_.have_sim_status) return false;
  return !config_.lockstep || status_sim_time_s_ >= res_.sim_time_s;
}

void RunSupervisor::on_hosts_matched(uint32_t count, double now_s) {
  if (over()) return;
  if (count > 0 && !sim_seen_ && !config_.lockstep) {
    sim_seen_ = true;
    res_.first_progress_wall_s = now_s;
    std::fill(robot_seen_s_.begin(), robot_seen_s_.end(), now_s);
  }
  max_matched_ = std::max(max_matched_, count);
  // Lock-step: the one sim host holds every robot, so its writers leaving ends the run.
  if (config_.lockstep && sim_seen_ && count < max_matched_) {
    end(Outcome::kHostLost, "the sim host left (its DDS writers disappeared) after " +
                                std::to_string(res_.sim_time_s) + " s of sim time");
  }
}

void RunSupervisor::on_host_failure(const std::string& what) {
  if (!over()) end(Outcome::kHostLost, what);
}

void RunSupervisor::refuse(const std::string& why) {
  if (!over()) end(Outcome::kRefused, why);
}

void RunSupervisor::stop(const std::string& why) {
  if (!over()) end(Outcome::kStopped, why);
}

void RunSupervisor::poll(double now_s) {
  if (over()) return;
  if (!config_.lockstep) {
    res_.sim_time_s = now_s;
    advance_time(now_s);
    update_waiting(now_s);
    check_end();
    if (over()) return;
  }
  if (config_.lockstep && config_.reanswer_s > 0 &&
      handshake_.should_reanswer(now_s, config_.reanswer_s)) {
    writer_.answer_tick(*handshake_.last_answer());
    handshake_.sent(now_s);
  }
  check_liveness(now_s);
}

// A host that joined and then left, or went silent, is a failure, not a hang.
void RunSupervisor::check_liveness(double now_s) {
  if (!config_.lockstep && sim_seen_) {
    // Real time: hosts may restart (an agent process, a robot rebooting): a robot fails the
    // run only when nothing was heard of it for timeout_s; a restarted host resumes from its
    // window.
    last_sim_sign_s_ = now_s;
    for (uint32_t r = 0; r < robot_seen_s_.size(); ++r) {
      if (exec_->robot_done(r) || now_s - robot_seen_s_[r] <= config_.timeout_s) continue;
      return end(Outcome::kHostLost, "robot " + std::to_string(r) +
                                         ": nothing heard from its host (sim or agent) for " +
                                         std::to_string(config_.timeout_s) +
                                         " s; the process stopped or lost the network");
    }
  }
  const double join_s = config_.join_timeout_s > 0 ? config_.join_timeout_s : config_.timeout_s;
  // Lock-step start-up lasts until the tick after the sim's first step: the sim shards give
  // their exchanges of those periods the join window too (sim/shard_barrier.hpp).
  const bool starting = !sim_seen_ || (config_.lockstep && newest_tick_ < wire::kLastJoinTick);
  const double limit_s = starting ? join_s : config_.timeout_s;
  if (now_s - (sim_seen_ ? last_sim_sign_s_ : 0.0) <= limit_s) return;
  end(Outcome::kHostLost,
      sim_seen_ ? "the sim host went silent for " + std::to_string(limit_s) + " s after tick " +
                      std::to_string(newest_tick_) +
                      (handshake_.pending() ? " (not answered yet: its progress is not all in)"
                                            : " (answered)")
                : "no sim host joined domain " + std::to_string(config_.domain_id) + " within " +
                      std::to_string(join_s) +
                      " s; start `smart sim` with the same --domain, --qos, --network");
}

void RunSupervisor::finish(double now_s) {
  if (!over()) end(Outcome::kStopped, "stopped before the run ended");
  // Tell every host the run is over (at the last tick answered, so a waiting sim sees it),
  // unless the run belongs to another monitor.
  if (res_.outcome != Outcome::kRefused) {
    writer_.answer_tick(
        {res_.run_id, handshake_.last_answered(), res_.sim_time_s, sent_.total(), true});
  }
  res_.finished_actions = exec_->finished_total();
  res_.wall_time_s = now_s;
}

namespace {
std::string robot_list(const std::vector<uint32_t>& robots) {
  std::string out;
  for (std::size_t i = 0; i < robots.size() && i < 10; ++i) {
    out += (i ? ", " : "") + std::to_string(robots[i]);
  }
  if (robots.size() > 10) out += " and " + std::to_string(robots.size() - 10) + " more";
  return out;
}
}  // namespace

void RunSupervisor::conclude() {
  if (res_.outcome != Outcome::kSuccess) return;
  const double tol = res_.goal_tolerance_m;
  for (uint32_t r = 0; r < goal_.size(); ++r) {
    if (!seen_done_[r]) {
      res_.goal_unverified.push_back(r);
      continue;
    }
    const double d = std::hypot(last_pose_[r].x_m - goal_[r].x_m, last_pose_[r].y_m - goal_[r].y_m);
    if (d > tol) res_.off_goal.push_back(r);
  }
  if (auto why = collision_seen()) return end(Outcome::kCollision, std::move(*why));
  if (config_.require_sim_status && !has_final_sim_status()) {
    return end(Outcome::kUnverified,
               std::string("unverified: every action finished, but ") +
                   (res_.have_sim_status ? "the sim host's status at the run's end"
                                         : "no status from the run's sim host") +
                   " came in, so its collision counts are unknown; if samples were rejected "
                   "(rejected_samples), a participant that is not the sim host wrote them");
  }
  if (!res_.off_goal.empty()) {
    end(Outcome::kOffGoal, "not at goal: every action finished, but robots " +
                               robot_list(res_.off_goal) + " were last seen more than " +
                               std::to_string(tol) + " m from their goals");
  }
}

std::optional<std::string> RunSupervisor::collision_seen() const {
  if (res_.robot_contacts > 0) {
    const auto names = res_.first_collision
                           ? "robots " + std::to_string(res_.first_collision->first) + " and " +
                                 std::to_string(res_.first_collision->second)
                           : std::string("unknown robots");
    return "collision: every action finished, but the sim host saw " +
           std::to_string(res_.robot_contacts) + " robot-robot collisions, first " + names +
           "; a host executed actions out of order or something forged progress";
  }
  if (const auto& c = res_.first_pose_contact) {
    return "collision: every action finished, but the robots' reported poses show " +
           std::to_string(res_.pose_contacts) + " contact(s), first robots " +
           std::to_string(c->a) + " and " + std::to_string(c->b) + " at " + std::to_string(c->t_s) +
           " s; check the robots' sizes, pose calibration and the "
           "plan's spacing";
  }
  return std::nullopt;
}

std::size_t RunSupervisor::robots_done() const {
  std::size_t done = 0;
  for (uint32_t r = 0; r < exec_->robots(); ++r) done += exec_->robot_done(r) ? 1 : 0;
  return done;
}

std::vector<std::string> RunSupervisor::take_notes() {
  std::vector<std::string> out;
  out.swap(notes_);
  return out;
}

std::string RunSupervisor::resume(const std::vector<ProgressEvent>& reported) {
  if (exec_->lifelong()) {
    return "cannot resume a lifelong run: its graph and tasks lived in the monitor that stopped; "
           "start a new run";
  }
  std::vector<int64_t> target(exec_->robots(), -1);
  uint64_t run = 0;
  std::string error = resume_check(reported, target, run);
  if (error.empty() && unreplayed_switches_ > 0) {
    error = "cannot resume: " + std::to_string(unreplayed_switches_) + " of the " +
            std::to_string(config_.resume_switches.size()) +
            " switches given match no pair of this plan's passing orders; give the switches.csv "
            "of the run being resumed, with its plan, --agents and --execution";
  }
  if (error.empty() && run == 0) {
    error = "cannot resume: the hosts report no progress yet; start a new run";
  }
  if (error.empty()) {
    res_.run_id = run;
    resume_fixpoint(target);
    for (uint32_t r = 0; r < target.size() && error.empty(); ++r) {
      if (static_cast<int64_t>(exec_->finished(r)) - 1 == target[r]) continue;
      error = "cannot resume: robot " + std::to_string(r) + " reports action " +
              std::to_string(target[r]) + " finished, which this plan's dependency graph " +
              (switchable_ ? "with the switches given " : "") +
              "does not allow; use the plan, --agents and --initial-heading of the run being "
              "resumed" +
              (switchable_ ? ", and its live switches.csv (--resume-switches)" : "");
    }
  }
  if (!error.empty()) {
    end(Outcome::kHostLost, error);
    return error;
  }
  for (uint32_t r = 0; r < target.size(); ++r) {
    // The hosts hold windows up to at least what was finished (sync totals, idl/smart.idl).
    sent_.raise(r, exec_->finished(r));
    if (exec_->robot_done(r)) {
      res_.robots[r].finish_time_s = std::nan("");
      ++res_.robots_done_before_resume;
    }
  }
  res_.resumed = true;
  res_.finished_before_resume = res_.finished_actions = exec_->finished_total();
  notes_.push_back("resuming run " + std::to_string(run) + ": " +
                   std::to_string(exec_->finished_total()) + " of " +
                   std::to_string(exec_->total()) + " actions already finished");
  return {};
}

std::string RunSupervisor::resume_check(const std::vector<ProgressEvent>& reported,
                                        std::vector<int64_t>& target, uint64_t& run) const {
  for (const auto& p : reported) {
    if (p.robot >= target.size()) {
      return "cannot resume: progress for robot " + std::to_string(p.robot) + " but the plan has " +
             std::to_string(target.size()) +
             " robots; use the plan and --agents of the run being resumed";
    }
    if (run != 0 && p.run_id != run) {
      return "cannot resume: the hosts report two runs (" + std::to_string(run) + " and " +
             std::to_string(p.run_id) + "); restart the sim hosts and start a new run";
    }
    run = p.run_id;
    target[p.robot] = std::max<int64_t>(target[p.robot], p.finished_seq);
  }
  return {};
}

// Progress is only accepted for enqueued actions, and what robot A finished may have waited for
// robot B: feed each robot as far as is enqueued, again and again until nothing more is
// accepted (the execution respected the ADG, so everything is).
void RunSupervisor::resume_fixpoint(const std::vector<int64_t>& target) {
  for (bool changed = true; changed;) {
    changed = false;
    for (uint32_t r = 0; r < target.size(); ++r) {
      const int64_t upto = std::min<int64_t>(target[r], int64_t{exec_->enqueued(r)} - 1);
      if (upto <= int64_t{exec_->finished(r)} - 1) continue;
      if (exec_->on_progress(r, upto, 0).result == ProgressResult::kAdvanced) {
        changed = true;
      }
    }
  }
}

}  // namespace smart::monitor
