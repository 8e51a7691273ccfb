#include "smart/monitor/node.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <map>
#include <memory>
#include <vector>

#include "ownership_edge.hpp"
#include "smart/convert/convert.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/action_window.hpp"
#include "smart/dds/participant_directory.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/monitor/ros_plan_view.hpp"

namespace smart::monitor {

uint64_t wall_clock_run_id() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
}

namespace {
using SteadyClock = std::chrono::steady_clock;
using std::chrono::milliseconds;
}  // namespace

// Named, not anonymous: MonitorNode::Impl (declared in the header) holds one, and g++ warns
// (-Wsubobject-linkage) when a unity build includes this file into another.
namespace node_writer {
// The supervisor's decisions, written to DDS. Windows are packed (Cyclone's write batching,
// dds/writer.hpp) and go out together when the pump's turn ends (flush) or, before a tick's
// answer, so that a host finds the windows the answer counts already sent.
class DdsRunWriter final : public RunWriter {
 public:
  DdsRunWriter(const dds::Participant& p, const dds::QosProfile& qos, const Grid& grid,
               double cell_m, int32_t strength)
      : grid_(grid), cell_m_(cell_m), actions_(p, qos, strength), clock_(p, qos, strength) {}

  // What the windows are cut from (the supervisor's execution, set once it exists).
  void set_source(const Execution& execution) { exec_ = &execution; }

  void publish_window(uint32_t robot, uint64_t run_id, ActionWindowRange w) override {
    dds::ActionWindowBuffer buf(robot, run_id, exec_->known(robot));
    for (uint32_t s = w.first; s < w.end; ++s) {
      buf.steps().push_back(wire::to_wire(exec_->action(robot, s), grid_, cell_m_));
    }
    actions_.write_batched(buf.view());
  }
  void action_finished(uint32_t robot, uint32_t seq, double sim_time_s) override {
    if (on_action_finished) on_action_finished(robot, seq, sim_time_s);
  }
  std::function<void(uint32_t, uint32_t, double)> on_action_finished;
  void switched(const PassingSwitch& s) override {
    if (on_switch) on_switch(s);
  }
  std::function<void(const PassingSwitch&)> on_switch;
  void answer_tick(const wire::Tick& answer) override {
    actions_.flush();
    clock_.write(wire::to_wire(answer, dds::kMonitorClockSource));
  }
  void flush() { actions_.flush(); }
  bool wait_for_acks(milliseconds timeout) { return clock_.wait_for_acks(timeout); }

 private:
  const Grid& grid_;
  const Execution* exec_ = nullptr;
  double cell_m_;
  dds::WireWriter<smart_msg_ActionWindow> actions_;
  dds::WireWriter<smart_msg_Clock> clock_;
};
}  // namespace node_writer
using node_writer::DdsRunWriter;

namespace {

SupervisorConfig with_run_id(SupervisorConfig c, int domain_id, double cell_m) {
  if (c.run_id == 0) c.run_id = wall_clock_run_id();
  c.domain_id = domain_id;
  c.cell_m = cell_m;
  c.reanswer_s = dds::kClockReannounceS;
  return c;
}
}  // namespace

struct MonitorNode::Impl {
  const dds::Participant& participant;
  const Instance* in;  // a plan's run; nullptr in a lifelong run
  const Grid& grid;
  MonitorOptions opt;
  SupervisorConfig config;
  MonitorAnnouncer announcer;  // before the writers: they take its ownership strength
  DdsRunWriter writer;
  RunSupervisor sup;
  // Progress and states only from the run's proven sim hosts and agents (with a run key), each
  // for the robots it speaks for (dds/admission.hpp, per robot): a stranger's or an insider's
  // samples for another robot never reach the readers nor seize an instance.
  std::unique_ptr<dds::WriterAdmission> from_hosts_progress, from_hosts_states;
  dds::WireReader<smart_msg_Progress> progress;
  dds::WireReader<smart_msg_RobotState> states;
  // Ticks and the sim host's status, heard only from its writers once it is known (issue 25: a
  // stronger or flooding writer hid the sim's status and bought a false success; a second sim's
  // ticks silenced the real one).
  SimBoundReader<smart_msg_Clock> clock_in;
  dds::WireReader<smart_msg_Clock>& clocks;
  SimBoundReader<smart_msg_SimStatus> status_in;
  dds::WireReader<smart_msg_SimStatus>& status;
  // Anything received is checked before it becomes an event (wire/validate.hpp).
  const std::size_t robots;
  const wire::Bounds bounds;
  wire::Rejections rejections;
  dds::ParticipantDirectory directory;
  std::map<dds_instance_handle_t, std::string> senders_named;
  SenderGate senders;
  std::optional<std::pair<smart_msg_SimStatus, dds_instance_handle_t>> early_status;
  uint32_t status_writers_seen = 0;  // status writers matched so far (total_count)
  uint32_t clock_writers_now = 0;    // hosts_matched(): clock writers matched now
  bool sim_was_known = false, sim_here = false;
  const SteadyClock::time_point wall0 = SteadyClock::now();
  std::optional<RosPlanView> plan_view;              // --ros-plan-hz
  std::vector<std::optional<common::Pose2D>> poses;  // last reported, for the plan view
  double plan_view_s = -1e9;

  Impl(const dds::Participant& p, const dds::QosProfile& qos, const Instance* in, const Grid& grid,
       Execution* lifelong, const MonitorOptions& o)
      : participant(p),
        in(in),
        grid(grid),
        opt(o),
        config(with_run_id(o.run, static_cast<int>(p.domain_id()), o.cell_m)),
        announcer(p, qos, config.run_id, o.resume),
        writer(p, qos, grid, o.cell_m, announcer.strength()),
        sup(in ? RunSupervisor(*in, config, writer) : RunSupervisor(*lifelong, config, writer)),
        from_hosts_progress(dds::WriterAdmission::per_robot(p, {"sim", "agent"})),
        from_hosts_states(dds::WriterAdmission::per_robot(p, {"sim", "agent"})),
        progress(p, qos, *from_hosts_progress),
        states(p, qos, *from_hosts_states),
        clock_in(p, qos),
        clocks(clock_in.reader()),
        status_in(p, qos),
        status(status_in.reader()),
        robots(sup.execution().robots()),
        bounds(wire::bounds_of(grid, o.cell_m)),
        directory(p),
        senders(robots) {
    writer.set_source(sup.execution());
    writer.on_action_finished = o.on_action_finished;
    writer.on_switch = o.on_switch;
  }

  // True when the sample passed; otherwise it is counted and (rate-limited) logged.
  template <class Reader>
  bool valid(const char* topic, const std::string& why, const Reader& reader,
             dds_instance_handle_t from, uint64_t samples = 1) {
    if (why.empty()) return true;
    const auto& who = sender(reader, from);
    if (rejections.count(topic, why, who, samples)) {
      spdlog::warn("monitor: {} sample from {} rejected: {}", topic, who, why);
    }
    return false;
  }

  // Who wrote a refused sample, looked up once per writer (a flood costs no discovery reads).
  template <class Reader>
  const std::string& sender(const Reader& reader, dds_instance_handle_t from) {
    if (senders_named.size() > 4096) senders_named.clear();
    auto [it, fresh] = senders_named.try_emplace(from);
    if (fresh) it->second = directory.describe(reader.participant_of(from));
    return it->second;
  }

  double now_s() const { return std::chrono::duration<double>(SteadyClock::now() - wall0).count(); }

  void read_clocks() {
    clock_in.refresh(senders, [&](dds_instance_handle_t writer, uint64_t n) {
      valid("clock", "clock ticks from a participant that is not this run's sim host", clocks,
            writer, n);
    });
    clocks.take_each_from([&](const smart_msg_Clock& c, dds_instance_handle_t from) {
      if (!valid("clock", wire::check_clock(c), clocks, from) ||
          c.source_id != dds::kSimClockSource)
        return;
      if (!valid("clock", senders.clock(from, clocks), clocks, from)) return;
      clock_in.admit(senders);  // bound before the answer, which tells the world the sim is known
      sup.on_clock(wire::from_wire(c), now_s());
    });
  }

  // Samples an admission kept out, counted against their senders: non-members, and members
  // writing for robots they do not speak for.
  template <class Reader>
  void count_refused(const char* topic, dds::WriterAdmission& admission, const Reader& reader) {
    for (const auto& [writer, n] : admission.take_refused()) {
      valid(topic, dds::kNotRunMember, reader, writer, n);
    }
    for (const auto& [writer, n] : admission.take_misspoken()) {
      const auto speaks = admission.speaks(writer);
      valid(topic, speaks ? dds::speaks_only(*speaks) : "for a robot it does not speak for", reader,
            writer, n);
    }
  }

  void read_progress() {
    count_refused("progress", *from_hosts_progress, progress);
    progress.take_each_from([&](const smart_msg_Progress& p, dds_instance_handle_t from) {
      if (!valid("progress", wire::check_progress(p, robots), progress, from)) return;
      if (!valid("progress", senders.progress(p, from, progress), progress, from)) return;
      sup.on_progress({p.robot_id, p.run_id, p.finished_seq}, now_s());
    });
    senders.release_held_back(progress, [&](const smart_msg_Progress& p) {
      sup.on_progress({p.robot_id, p.run_id, p.finished_seq}, now_s());
    });
  }

  void read_observations() {
    count_refused("state", *from_hosts_states, states);
    states.take_each_from([&](const smart_msg_RobotState& s, dds_instance_handle_t from) {
      if (!valid("state", wire::check_state(s, robots, bounds), states, from)) return;
      if (!sup.on_state({s.robot_id, s.run_id, s.pose.x_m, s.pose.y_m}, now_s())) return;
      if (plan_view) poses[s.robot_id] = common::Pose2D{s.pose.x_m, s.pose.y_m, s.pose.yaw_rad};
      if (!opt.on_state) return;
      // One time base for states.csv: the sim clock in lock-step; in real time the monitor's
      // run clock (hosts' clocks differ: a JetBot stamps host uptime, a sim host its own start).
      const double t_s = config.lockstep ? s.sim_time_s : now_s();
      opt.on_state({t_s, s.robot_id, s.pose.x_m, s.pose.y_m, s.pose.yaw_rad, s.linear_mps,
                    s.angular_radps, s.wheel_left_mps, s.wheel_right_mps, s.queue_length});
    });
    if (const auto m = status.subscription_matched().total_count; m != status_writers_seen) {
      status_writers_seen = m;
      senders.remember_status_writers(status);
    }
    status_in.refresh(senders, [&](dds_instance_handle_t writer, uint64_t n) {
      valid("sim_status", "sim status from a participant that is not this run's sim host", status,
            writer, n);
    });
    status.take_each_from([&](const smart_msg_SimStatus& s, dds_instance_handle_t from) {
      if (!valid("sim_status", wire::check_status(s, robots), status, from)) return;
      if (!senders.sim_known()) {
        early_status = {s, from};  // the newest; placed once the sim host's first tick is in
        return;
      }
      take_status(s, from);
    });
    if (early_status && senders.sim_known()) {
      const auto [s, from] = *early_status;
      early_status.reset();
      take_status(s, from);
    }
  }

  void take_status(const smart_msg_SimStatus& s, dds_instance_handle_t from) {
    if (!valid("sim_status", senders.status(from, status), status, from)) return;
    sup.on_sim_status({s.run_id, s.robot_contacts, s.wall_contacts, s.min_gap_m, s.peak_rss_mb,
                       s.first_contact_a, s.first_contact_b, s.sim_time_s});
  }

  void log_notes() {
    for (const auto& note : sup.take_notes()) spdlog::warn("monitor: {}", note);
  }

  // The hosts' kept progress (transient local) arrives after the match, over a few round
  // trips: collect until nothing new came for 0.5 s. (A lock-step sim is paused meanwhile; a
  // real-time one keeps reporting, and progress is cumulative, so the newest sample wins.)
  bool resume() {
    const auto timeout = milliseconds(static_cast<int64_t>(opt.run.timeout_s * 1000));
    std::string error;
    std::vector<ProgressEvent> reported;
    if (!progress.wait_for_writers(1, timeout)) {
      error = "cannot resume: no sim host or agent joined domain " +
              std::to_string(participant.domain_id()) + " within " +
              std::to_string(opt.run.timeout_s) + " s; resume only a run whose hosts are still up";
    } else {
      collect_progress(reported, timeout);
    }
    if (error.empty()) error = sup.resume(reported);
    if (!error.empty()) sup.on_host_failure(error);
    log_notes();
    return error.empty();
  }

  void collect_progress(std::vector<ProgressEvent>& out, milliseconds timeout) {
    dds::WaitSet waitset(participant);
    waitset.attach_status(progress.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
    const auto deadline = SteadyClock::now() + timeout;
    auto last_new = SteadyClock::now();
    while (SteadyClock::now() < deadline) {
      waitset.wait(milliseconds(50));
      const auto n = progress.take_each([&](const smart_msg_Progress& p) {
        out.push_back({p.robot_id, p.run_id, p.finished_seq});
      });
      if (n > 0) {
        last_new = SteadyClock::now();
      } else if (!out.empty() && SteadyClock::now() - last_new > milliseconds(500)) {
        return;
      }
    }
  }

  // Real time: every host's progress writers. Lock-step: the sim host is there while its clock
  // writer is (issue 25: any writer that matched and left ended the run as "the sim host left");
  // looked up again only when a clock writer came or went.
  uint32_t hosts_matched() {
    if (!config.lockstep) {
      const auto writers = progress.matched_writers();  // a stranger's writer is no host
      return static_cast<uint32_t>(std::count_if(writers.begin(), writers.end(), [&](auto h) {
        return from_hosts_progress->admitted(h);
      }));
    }
    const auto now = clocks.subscription_matched().current_count;
    if (now != clock_writers_now || senders.sim_known() != sim_was_known) {
      clock_writers_now = now;
      sim_was_known = senders.sim_known();
      sim_here = senders.sim_clock_matched(clocks);
    }
    return sim_here ? 1 : 0;
  }

  // One turn of the pump: read everything that came, let the supervisor decide.
  void pump() {
    read_clocks();
    read_observations();
    // Lock-step takes progress only once its tick is in (the samples wait in the reader).
    if (sup.wants_progress()) read_progress();
    const double now = now_s();
    sup.poll(now);
    sup.on_hosts_matched(hosts_matched(), now);
    if (auto refusal = announcer.poll()) sup.refuse(*refusal);
    writer.flush();  // the windows decided in this turn
    log_notes();
  }

  void start_plan_view() {
    if (opt.ros_plan_hz <= 0 || !in) return;
    plan_view.emplace(participant, *in, opt.cell_m, opt.robot_radius_m, opt.ros_namespace);
    poses.assign(robots, std::nullopt);
    plan_view->publish_paths();
  }

  // Finished actions for live views, when the count changed since the last report.
  std::optional<std::size_t> reported_finished, reported_robots;
  double robots_reported_s = -1;
  void report_finished() {
    const auto& t = sup.execution();
    if (opt.on_finished && reported_finished != t.finished_total()) {
      reported_finished = t.finished_total();
      opt.on_finished({sup.result().sim_time_s, t.finished_total(), t.total()});
    }
    if (opt.on_robots_finished && reported_robots != t.finished_total() &&
        now_s() - robots_reported_s >= 1.0) {
      reported_robots = t.finished_total();
      robots_reported_s = now_s();
      std::vector<uint32_t> finished(t.robots());
      for (uint32_t r = 0; r < finished.size(); ++r) finished[r] = t.finished(r);
      opt.on_robots_finished(finished);
    }
  }

  void publish_plan_view(bool now) {
    if (!plan_view || (!now && now_s() - plan_view_s < 1.0 / opt.ros_plan_hz)) return;
    plan_view_s = now_s();
    plan_view->publish(sup.plan_snapshot(), poses, plan_view_s);
  }

  // Tell every host the run is over, make sure it was delivered, and take the sim's final
  // states and status, which follow its stop; then the verdict.
  MonitorResult finish() {
    sup.finish(now_s());
    writer.flush();
    writer.wait_for_acks(milliseconds(1000));
    const auto t0 = SteadyClock::now();
    while (draining(SteadyClock::now() - t0)) {
      drain_waitset().wait(milliseconds(20));
      read_observations();
    }
    sup.conclude();
    publish_plan_view(true);
    MonitorResult r = sup.result();
    r.wall_time_s = now_s();
    r.rejected_samples = rejections.counts();
    r.rejected_examples = rejections.examples();
    for (const auto& [who, what] : rejections.senders()) {
      r.suspected_intruders.push_back({who, what.samples, what.first_reason});
    }
    name_suspects(r);
    return r;
  }

  // The final states and status follow the stop: take what comes for 0.3 s, and in a run that
  // needs the sim's word, until its final status is in, while the sim host's clock writer is
  // still matched (it leaves once it has written), at most timeout_s.
  bool draining(SteadyClock::duration since) {
    if (sup.result().outcome == Outcome::kHostLost) return false;
    if (since < milliseconds(300)) return true;
    if (!config.require_sim_status || sup.has_final_sim_status()) return false;
    return since < std::chrono::duration<double>(config.timeout_s) &&
           senders.sim_clock_matched(clocks);
  }

  // A failed run whose monitor refused samples names their senders: they may be the cause
  // (issue 25: a stall blamed on "robots stuck against each other" hid the intruder).
  static void name_suspects(MonitorResult& r) {
    if (r.success() || r.outcome == Outcome::kRefused || r.suspected_intruders.empty()) return;
    r.error += "; meanwhile samples were refused from ";
    for (std::size_t i = 0; i < r.suspected_intruders.size() && i < 3; ++i) {
      const auto& s = r.suspected_intruders[i];
      r.error += (i ? ", " : "") + s.sender + " (first: " + s.first_reason + ")";
    }
    if (r.suspected_intruders.size() > 3) r.error += " and others (suspected_intruders)";
  }

  dds::WaitSet& drain_waitset() {
    if (!drain_) {
      drain_ = std::make_unique<dds::WaitSet>(participant);
      drain_->attach_status(status.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
      drain_->attach_status(states.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
    }
    return *drain_;
  }
  std::unique_ptr<dds::WaitSet> drain_;
};

MonitorNode::MonitorNode(const dds::Participant& participant, const dds::QosProfile& qos,
                         const Instance& instance, const MonitorOptions& options)
    : impl_(std::make_unique<Impl>(participant, qos, &instance, instance.grid, nullptr, options)) {}

MonitorNode::MonitorNode(const dds::Participant& participant, const dds::QosProfile& qos,
                         const Grid& grid, Execution& lifelong, const MonitorOptions& options)
    : impl_(std::make_unique<Impl>(participant, qos, nullptr, grid, &lifelong, options)) {}

MonitorNode::~MonitorNode() = default;

MonitorResult MonitorNode::run(const std::atomic<bool>& stop_requested,
                               const ProgressCallback& on_progress) {
  auto& I = *impl_;
  // Lock-step waits on ticks alone until one is pending: waking on progress not yet taken
  // would spin (3 ms of CPU per tick at 1000 robots, in series with the sim).
  dds::WaitSet any(I.participant), ticks(I.participant);
  any.attach_status(I.progress.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  any.attach_status(I.clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  ticks.attach_status(I.clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  const auto refusal =
      I.announcer.settle([&] { return I.progress.subscription_matched().current_count > 0; }, 1.0);
  if (refusal) {
    I.sup.refuse(*refusal);
    return I.finish();
  }
  I.announcer.owned();  // from here on a later claim never stops this run (issue 25)
  if (I.opt.resume && !I.resume()) return I.sup.result();
  I.sup.start(I.now_s());
  I.writer.flush();
  I.start_plan_view();
  // The run's name and id as summary.json has them ("run", "run_id"), so logs and results match.
  spdlog::info("monitor: run {} (run_id {}): {} robots, {} actions; waiting for the sim",
               I.participant.run(), I.sup.result().run_id, I.sup.result().robots.size(),
               I.sup.execution().total());
  double last_check_s = 0;
  while (!I.sup.over()) {
    if (stop_requested.load()) {
      I.sup.stop("stopped by signal");
      break;
    }
    (I.sup.wants_progress() ? any : ticks).wait(milliseconds(20));
    I.pump();
    if (I.now_s() - last_check_s < 0.1) continue;
    last_check_s = I.now_s();
    I.publish_plan_view(false);
    if (I.opt.host_check) {
      if (auto problem = I.opt.host_check(); !problem.empty()) I.sup.on_host_failure(problem);
    }
    if (on_progress) {
      auto r = I.sup.result();
      r.wall_time_s = last_check_s;
      on_progress(r, I.sup.robots_done());
    }
    I.report_finished();
  }
  return I.finish();
}

}  // namespace smart::monitor
