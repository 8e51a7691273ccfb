#include "smart/monitor/node.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "smart/dds/action_window.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/writer.hpp"
#include "smart/monitor/execution_tracker.hpp"

namespace smart::monitor {

namespace {
constexpr uint32_t kSimSource = 0;
constexpr uint32_t kMonitorSource = 1;
using SteadyClock = std::chrono::steady_clock;

smart_msg_Location location(const Grid& grid, HalfCell h, double cell_m) {
  const auto w = grid.to_world(h, cell_m);
  return {w.x_m, w.y_m, h.x2, h.y2};
}
}  // namespace

struct MonitorNode::Impl {
  const dds::Participant& participant;
  const Instance& in;
  MonitorOptions opt;
  ExecutionTracker tracker;
  dds::Topic<smart_msg_ActionWindow> action_topic;
  dds::Topic<smart_msg_Progress> progress_topic;
  dds::Topic<smart_msg_RobotState> state_topic;
  dds::Topic<smart_msg_Clock> clock_topic;
  dds::Topic<smart_msg_SimStatus> status_topic;
  dds::Writer<smart_msg_ActionWindow> actions;
  dds::Writer<smart_msg_Clock> clock_out;
  dds::Reader<smart_msg_Progress> progress;
  dds::Reader<smart_msg_RobotState> states;
  dds::Reader<smart_msg_Clock> clocks;
  dds::Reader<smart_msg_SimStatus> status;
  std::vector<uint32_t> sent_end;
  uint64_t sent_end_total = 0;
  std::vector<uint8_t> waiting;
  MonitorResult res;
  double last_finish_sim_s = 0;
  double last_metrics_sim_s = 0;
  // Real time: when each robot's host (sim or agent) was last heard of (its state samples).
  std::vector<SteadyClock::time_point> robot_seen;

  Impl(const dds::Participant& p, const dds::QosProfile& qos, const Instance& instance,
       const MonitorOptions& o)
      : participant(p),
        in(instance),
        opt(o),
        tracker(instance.actions, instance.adg),
        action_topic(p, std::string(dds::kActionTopic)),
        progress_topic(p, std::string(dds::kProgressTopic)),
        state_topic(p, std::string(dds::kStateTopic)),
        clock_topic(p, std::string(dds::kClockTopic)),
        status_topic(p, std::string(dds::kSimStatusTopic)),
        actions(p, action_topic, qos.action.to_dds()),
        clock_out(p, clock_topic, qos.clock.to_dds()),
        progress(p, progress_topic, qos.progress.to_dds()),
        states(p, state_topic, qos.state.to_dds()),
        clocks(p, clock_topic, qos.clock.to_dds()),
        status(p, status_topic, qos.progress.to_dds()) {
    const std::size_t n = instance.actions.robots();
    sent_end.assign(n, 0);
    waiting.assign(n, 0);
    robot_seen.assign(n, SteadyClock::now());
    res.robots.resize(n);
    for (uint32_t r = 0; r < n; ++r) res.robots[r].actions = instance.actions.count(r);
    res.run_id =
        opt.run_id != 0
            ? opt.run_id
            : static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
    res.total_actions = instance.actions.actions.size();
  }

  // Rebuilds the tracker from the hosts' last progress (see MonitorOptions::resume); returns an
  // error message, empty on success.
  std::string resume_from_progress() {
    const auto timeout = std::chrono::milliseconds(static_cast<int64_t>(opt.timeout_s * 1000));
    if (!progress.wait_for_writers(1, timeout)) {
      return "cannot resume: no sim host or agent joined domain " +
             std::to_string(participant.domain_id()) + " within " + std::to_string(opt.timeout_s) +
             " s; resume only a run whose hosts are still up";
    }
    std::vector<int64_t> target(tracker.robots(), -1);
    uint64_t run = 0;
    std::string error;
    auto take = [&] {
      return progress.take_each([&](const smart_msg_Progress& p) {
        if (!error.empty()) return;
        if (p.robot_id >= target.size()) {
          error = "cannot resume: progress for robot " + std::to_string(p.robot_id) +
                  " but the plan has " + std::to_string(target.size()) +
                  " robots; use the plan and --agents of the run being resumed";
          return;
        }
        if (run != 0 && p.run_id != run) {
          error = "cannot resume: the hosts report two runs (" + std::to_string(run) + " and " +
                  std::to_string(p.run_id) + "); restart the sim hosts and start a new run";
          return;
        }
        run = p.run_id;
        target[p.robot_id] = std::max<int64_t>(target[p.robot_id], p.finished_seq);
      });
    };
    // The writers' kept samples arrive after the match, over a few round trips: collect until
    // nothing new came for 0.5 s. (A lock-step sim is paused meanwhile; a real-time one keeps
    // reporting, and progress is cumulative, so the newest sample per robot wins either way.)
    dds::WaitSet waitset(participant);
    waitset.attach_status(progress.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
    const auto deadline = SteadyClock::now() + timeout;
    auto last_new = SteadyClock::now();
    bool any = false;
    while (SteadyClock::now() < deadline && error.empty()) {
      waitset.wait(std::chrono::milliseconds(50));
      if (take() > 0) {
        any = true;
        last_new = SteadyClock::now();
      } else if (any && SteadyClock::now() - last_new > std::chrono::milliseconds(500)) {
        break;
      }
    }
    if (!error.empty()) return error;
    if (run == 0) return "cannot resume: the hosts report no progress yet; start a new run";
    res.run_id = run;
    // Progress is only accepted for enqueued actions, and what robot A finished may have waited
    // for robot B: feed each robot as far as is enqueued, again and again until nothing more is
    // accepted (the execution respected the ADG, so everything is).
    for (bool changed = true; changed;) {
      changed = false;
      for (uint32_t r = 0; r < target.size(); ++r) {
        const int64_t upto = std::min<int64_t>(target[r], int64_t{tracker.enqueued(r)} - 1);
        if (upto <= int64_t{tracker.finished(r)} - 1) continue;
        if (tracker.on_progress(r, upto).result == ExecutionTracker::Result::kAdvanced) {
          changed = true;
        }
      }
    }
    for (uint32_t r = 0; r < target.size(); ++r) {
      if (static_cast<int64_t>(tracker.finished(r)) - 1 != target[r]) {
        return "cannot resume: robot " + std::to_string(r) + " reports action " +
               std::to_string(target[r]) +
               " finished, which this plan's dependency graph does not allow; use the plan, "
               "--agents and --initial-heading of the run being resumed";
      }
      // The hosts hold windows up to at least what was finished (sync totals, idl/smart.idl).
      sent_end[r] = tracker.finished(r);
      sent_end_total += sent_end[r];
      if (tracker.robot_done(r)) {
        res.robots[r].finish_time_s = std::nan("");
        ++res.robots_done_before_resume;
      }
    }
    res.resumed = true;
    res.finished_before_resume = tracker.finished_total();
    res.finished_actions = tracker.finished_total();
    spdlog::info("monitor: resuming run {}: {} of {} actions already finished", run,
                 tracker.finished_total(), tracker.total());
    return {};
  }

  void publish_window(uint32_t r) {
    const auto w = tracker.window(r, opt.window_cap);
    dds::ActionWindowBuffer buf(r, res.run_id, in.actions.count(r));
    for (uint32_t s = w.first; s < w.end; ++s) {
      const Action& a = in.actions.at(r, s);
      smart_msg_ActionStep step{};
      step.seq = s;
      step.type = a.type == ActionType::kMove ? smart_msg_ACTION_MOVE : smart_msg_ACTION_ROTATE;
      step.from = location(in.grid, a.from, opt.cell_m);
      step.to = location(in.grid, a.to, opt.cell_m);
      step.heading_rad = yaw_rad(a.heading);
      step.plan_time_s = a.start_time;
      buf.steps().push_back(step);
    }
    actions.write(buf.view());
    if (!w.empty() && w.end > sent_end[r]) {
      sent_end_total += w.end - sent_end[r];
      sent_end[r] = w.end;
    }
  }

  void take_progress(double sim_time_s) {
    progress.take_each([&](const smart_msg_Progress& p) {
      if (p.run_id != res.run_id) return;  // an earlier run's history
      const auto u = tracker.on_progress(p.robot_id, p.finished_seq);
      if (u.result == ExecutionTracker::Result::kRejected) {
        if (res.rejected_progress++ < 5) spdlog::warn("monitor: progress rejected: {}", u.reason);
        return;
      }
      if (u.result != ExecutionTracker::Result::kAdvanced) return;
      last_finish_sim_s = sim_time_s;
      for (const uint32_t r : u.robots_changed) {
        publish_window(r);
        if (tracker.robot_done(r)) res.robots[r].finish_time_s = sim_time_s;
      }
    });
    res.finished_actions = tracker.finished_total();
  }

  void take_observations() {
    states.take_each([&](const smart_msg_RobotState& s) {
      if (s.run_id != res.run_id && s.run_id != 0) return;
      if (s.robot_id < robot_seen.size()) robot_seen[s.robot_id] = SteadyClock::now();
      if (!opt.on_state || s.run_id != res.run_id) return;
      opt.on_state({s.sim_time_s, s.robot_id, s.pose.x_m, s.pose.y_m, s.pose.yaw_rad, s.linear_mps,
                    s.angular_radps, s.wheel_left_mps, s.wheel_right_mps, s.queue_length});
    });
    status.take_each([&](const smart_msg_SimStatus& s) {
      if (s.run_id != res.run_id && s.run_id != 0) return;
      res.have_sim_status = true;
      res.robot_contacts = s.robot_contacts;
      res.wall_contacts = s.wall_contacts;
      if (s.min_gap_m < 1e8) res.min_gap_m = s.min_gap_m;
      if (s.peak_rss_mb > 0) {
        res.host_peak_rss_mb = std::max(res.host_peak_rss_mb.value_or(0.0), s.peak_rss_mb);
      }
    });
  }

  // Waiting = not done and nothing enqueued to execute, over the sim time since the last call.
  void update_waiting(double sim_time_s) {
    const double dt = sim_time_s - last_metrics_sim_s;
    last_metrics_sim_s = sim_time_s;
    for (uint32_t r = 0; r < waiting.size(); ++r) {
      const bool w = !tracker.robot_done(r) && tracker.enqueued(r) == tracker.finished(r);
      if (w) {
        res.robots[r].waiting_time_s += dt;
        if (!waiting[r]) ++res.robots[r].stops;
      }
      waiting[r] = w;
    }
  }

  std::size_t robots_done() const {
    std::size_t d = 0;
    for (uint32_t r = 0; r < waiting.size(); ++r) d += tracker.robot_done(r) ? 1 : 0;
    return d;
  }

  // True (and the result set) when the run is over.
  bool check_end() {
    if (tracker.complete()) {
      res.success = true;
      return true;
    }
    if (tracker.deadlocked()) {
      res.deadlock = true;
      res.error = "deadlock: no robot has an action it may execute, yet " +
                  std::to_string(tracker.total() - tracker.finished_total()) +
                  " actions remain; the action dependency graph cannot progress";
      return true;
    }
    if (res.sim_time_s - last_finish_sim_s > opt.stall_timeout_s) {
      res.stalled = true;
      res.error = "stalled: no action finished for " + std::to_string(opt.stall_timeout_s) +
                  " s of sim time; robots may be stuck against each other or a wall";
      return true;
    }
    if (opt.max_sim_time_s > 0 && res.sim_time_s > opt.max_sim_time_s) {
      res.error = "time limit: sim time passed " + std::to_string(opt.max_sim_time_s) + " s";
      return true;
    }
    return false;
  }

  void answer(uint64_t tick, double sim_time_s, bool stop) {
    clock_out.write(
        smart_msg_Clock{kMonitorSource, res.run_id, tick, sim_time_s, sent_end_total, stop});
  }
};

MonitorNode::MonitorNode(const dds::Participant& participant, const dds::QosProfile& qos,
                         const Instance& instance, const MonitorOptions& options)
    : impl_(std::make_unique<Impl>(participant, qos, instance, options)) {}

MonitorNode::~MonitorNode() = default;

MonitorResult MonitorNode::run(const std::atomic<bool>& stop_requested,
                               const ProgressCallback& on_progress) {
  auto& I = *impl_;
  const auto wall0 = SteadyClock::now();
  auto wall_s = [&] { return std::chrono::duration<double>(SteadyClock::now() - wall0).count(); };
  dds::WaitSet waitset(I.participant);
  waitset.attach_status(I.progress.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(I.clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  // Lock-step takes progress only once its tick's clock is in. Until then, waking on progress
  // would spin: the samples stay unread, so the waitset stays triggered (this was 3 ms of CPU
  // per tick at 1000 robots, in series with the sim).
  dds::WaitSet clock_waitset(I.participant);
  clock_waitset.attach_status(I.clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 2);

  if (I.opt.resume) {
    if (auto error = I.resume_from_progress(); !error.empty()) {
      I.res.error = std::move(error);
      I.res.sim_lost = true;
      return I.res;
    }
  }
  for (uint32_t r = 0; r < I.in.actions.robots(); ++r) I.publish_window(r);
  spdlog::info("monitor: run {}: {} robots, {} actions, {} Type-2 edges; waiting for the sim",
               I.res.run_id, I.in.actions.robots(), I.tracker.total(), I.in.adg.stats.type2);

  bool sim_seen = false;
  uint32_t max_matched = 0;
  double last_sim_sign_s = 0;
  // The latest sim tick not yet handled (lock-step: to answer). A plain struct and a flag
  // rather than std::optional: g++ 12 warns falsely about optional<C struct> here.
  smart_msg_Clock pending{};
  bool have_pending = false;
  uint64_t last_tick = 0;
  auto last_report = SteadyClock::now();
  auto last_host_check = SteadyClock::now();
  auto last_liveness_check = SteadyClock::now();
  bool over = false;
  while (!over) {
    if (stop_requested.load()) {
      I.res.error = "stopped by signal";
      break;
    }
    if (I.opt.lockstep && !have_pending) {
      clock_waitset.wait(std::chrono::milliseconds(20));
    } else {
      waitset.wait(std::chrono::milliseconds(20));
    }
    I.clocks.take_each([&](const smart_msg_Clock& c) {
      if (c.source_id != kSimSource) return;
      if (c.run_id != 0 && c.run_id != I.res.run_id) return;
      if (!sim_seen) {
        I.res.first_progress_wall_s = wall_s();
        if (I.res.resumed && I.opt.lockstep) {
          // Metrics restart here: what happened before the resume is not known.
          I.res.resumed_at_s = I.last_finish_sim_s = I.last_metrics_sim_s = c.sim_time_s;
        }
      }
      sim_seen = true;
      last_sim_sign_s = wall_s();
      if (!have_pending || c.tick >= pending.tick) pending = c;
      have_pending = true;
    });
    // Lock-step: progress is only taken against the tick that announced it, so every finish
    // time is that tick's sim time, whatever order the topics arrive in (bit-identical runs).
    I.take_observations();

    if (I.opt.lockstep && have_pending) {
      I.take_progress(pending.sim_time_s);
      if (I.tracker.finished_total() == pending.sync_total) {
        I.res.sim_time_s = pending.sim_time_s;
        I.update_waiting(pending.sim_time_s);
        over = I.check_end();
        last_tick = pending.tick;
        I.answer(pending.tick, pending.sim_time_s, over);
        have_pending = false;
      }
    } else if (!I.opt.lockstep) {
      // Real time (hardware, mixed runs): hosts run on their own clocks, so the run is timed
      // on this process's wall clock from the start.
      have_pending = false;
      const double now = wall_s();
      I.res.sim_time_s = now;
      I.take_progress(now);
      I.update_waiting(now);
      over = I.check_end();
    }
    if (over) break;
    // A host that joined and then left, or went silent, is a failure, not a hang.
    const uint32_t matched = I.progress.subscription_matched().current_count;
    if (matched > 0 && !sim_seen && !I.opt.lockstep) {
      sim_seen = true;
      I.res.first_progress_wall_s = wall_s();
      std::fill(I.robot_seen.begin(), I.robot_seen.end(), SteadyClock::now());
    }
    if (sim_seen) last_sim_sign_s = I.opt.lockstep ? last_sim_sign_s : wall_s();
    max_matched = std::max(max_matched, matched);
    // Lock-step: the one sim host holds every robot, so its writers leaving ends the run.
    if (I.opt.lockstep && sim_seen && matched < max_matched) {
      I.res.sim_lost = true;
      I.res.error = "the sim host left (its DDS writers disappeared) after " +
                    std::to_string(I.res.sim_time_s) + " s of sim time";
      break;
    }
    // Real time: hosts may restart (an agent process, a robot rebooting): a robot fails the run
    // only when nothing was heard of it for timeout_s; a restarted host resumes from its window.
    if (!I.opt.lockstep && sim_seen &&
        SteadyClock::now() - last_liveness_check > std::chrono::milliseconds(100)) {
      last_liveness_check = SteadyClock::now();
      const auto limit = std::chrono::duration<double>(I.opt.timeout_s);
      for (uint32_t r = 0; r < I.robot_seen.size(); ++r) {
        if (I.tracker.robot_done(r) || SteadyClock::now() - I.robot_seen[r] <= limit) continue;
        I.res.sim_lost = true;
        I.res.error = "robot " + std::to_string(r) + ": nothing heard from its host (sim or " +
                      "agent) for " + std::to_string(I.opt.timeout_s) +
                      " s; the process stopped or lost the network";
        break;
      }
      if (I.res.sim_lost) break;
    }
    if (I.opt.host_check && SteadyClock::now() - last_host_check > std::chrono::milliseconds(100)) {
      last_host_check = SteadyClock::now();
      if (auto problem = I.opt.host_check(); !problem.empty()) {
        I.res.sim_lost = true;
        I.res.error = std::move(problem);
        break;
      }
    }
    const double silent = wall_s() - (sim_seen ? last_sim_sign_s : 0.0);
    if (silent > I.opt.timeout_s) {
      I.res.sim_lost = true;
      I.res.error = sim_seen
                        ? "the sim host went silent for " + std::to_string(I.opt.timeout_s) + " s"
                        : "no sim host joined domain " + std::to_string(I.participant.domain_id()) +
                              " within " + std::to_string(I.opt.timeout_s) +
                              " s; start `smart sim` with the same --domain, --qos, "
                              "--network";
      break;
    }
    if (on_progress && SteadyClock::now() - last_report > std::chrono::milliseconds(100)) {
      last_report = SteadyClock::now();
      I.res.wall_time_s = wall_s();
      on_progress(I.res, I.robots_done());
    }
  }
  // Tell every host the run is over, and make sure it was delivered.
  I.answer(last_tick, I.res.sim_time_s, true);
  I.clock_out.wait_for_acks(std::chrono::milliseconds(1000));
  // The sim's final status follows its stop; give it a moment.
  const auto drain_until = SteadyClock::now() + std::chrono::milliseconds(300);
  while (SteadyClock::now() < drain_until && !I.res.sim_lost) {
    waitset.wait(std::chrono::milliseconds(20));
    I.take_observations();
  }
  I.res.finished_actions = I.tracker.finished_total();
  I.res.wall_time_s = wall_s();
  return I.res;
}

}  // namespace smart::monitor
