// Contract: how a run goes, decided in one pure state machine (no DDS, no clocks read, no
// threads, no I/O), in the manner of rmf_traffic's blockade Moderator: the monitor's DDS edge
// (node.hpp) converts what it receives into events, and the supervisor's decisions go out
// through a RunWriter (windows to publish, answers to the sim's ticks).
//
// Events: on_clock (a sim tick), on_progress, on_state, on_sim_status, on_hosts_matched (how
// many host writers are matched), on_host_failure (a watchdog of the edge), stop (a signal),
// poll(now) (timers). Every event carries the wall time now_s (seconds since the run started),
// the only clock the supervisor knows besides the sim time in ticks.
//
// Run policy, in one place:
// - Lock-step: a tick's progress is held until it adds up to the tick's sync_total
//   (wire/lockstep.hpp), then taken at the tick's sim time in robot order, each robot's newest
//   report only, and the tick is answered: what the execution decides on progress (switches,
//   anticipation) and so the run is bit-identical whatever order samples arrive in.
//   The sim host's writers leaving, or no tick for timeout_s, loses the run (join_timeout_s until
//   tick wire::kLastJoinTick is in: start-up, as the sim shards wait). With no newer tick
//   for reanswer_s, the last answer goes out again (wire::MonitorHandshake::should_reanswer).
// - Real time: progress is taken on arrival at the wall time; a robot fails the run only when
//   nothing was heard of it (its states) for timeout_s, so a host may restart within it.
// - Either: the execution is complete when every action finished; deadlock when no robot has an
// enqueued action
//   left yet some remain; stalled after stall_timeout_s of sim time without a finished action;
//   time limit past max_sim_time_s; no host at all within timeout_s.
// - Success means success (conclude(), once the hosts' final reports are in): a complete run is
//   a success only when no robot-robot collision was reported and every robot's last pose seen
//   after its last action finished lies within goal_tolerance_m of its goal; otherwise the
//   outcome is collision or not-at-goal and the error names the robots. A robot whose pose was
//   not seen after it finished (a lost sample) is listed as unverified, not failed.
// - A run with require_sim_status (every simulated run) is a success only with the sim host's
//   final status (lock-step: one stamped at the run's last tick), else it is unverified: an
//   intruder that hides the sim's status must not buy a success (issue 25).
// - Real time with robot_radius_m: the robots' reported poses are watched for contacts
//   (separation_watch.hpp); a contact they show fails a complete run as a collision: sampled
//   poses are evidence, not proof, but a success must not hide evidence of a collision.
// - Progress of another run is ignored; progress the tracker rejects (out of range, never
//   enqueued) is counted and described in notes(); stale (duplicate, older) progress is harmless.
// - resume(): rebuild the tracker from the hosts' last progress (a fixpoint: what robot A
//   finished may have waited for robot B, so each robot is fed as far as is enqueued, again
//   and again, until nothing more is accepted). A switchable run is rebuilt on the passing
//   orders the stopped monitor had reached (config.resume_switches replayed), switching nothing
//   while it is fed (SwitchableTracker::paused): what it then sends is what the stopped
//   monitor had sent, so no robot is sent into a location another holds an entry to.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "smart/monitor/execution_tracker.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/monitor/plan_view.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/monitor/separation_watch.hpp"
#include "smart/monitor/switchable_tracker.hpp"
#include "smart/wire/lockstep.hpp"

namespace smart::monitor {

enum class Outcome {
  kRunning,
  kSuccess,
  kDeadlock,
  kStalled,
  kTimeLimit,
  kHostLost,
  kStopped,
  kCollision,   // every action finished, but robots collided
  kOffGoal,     // every action finished, but a robot is not at its goal
  kRefused,     // another monitor owns the run
  kUnverified,  // every action finished, but the run's sim host never gave its final word
};
std::string_view to_string(Outcome outcome);

using results::StateRow;  // a states.csv row (results_format.hpp)

struct RobotMetrics {
  double finish_time_s = 0;   // sim time its last action finished (0: no actions)
  double waiting_time_s = 0;  // not done, nothing enqueued to execute (waiting for others)
  uint32_t stops = 0;         // times it became blocked that way
  uint32_t actions = 0;
};

struct MonitorResult {
  Outcome outcome = Outcome::kRunning;
  bool success() const { return outcome == Outcome::kSuccess; }
  std::string error;  // why the run failed (empty on success)
  uint64_t run_id = 0;
  double sim_time_s = 0;
  double wall_time_s = 0;
  double first_progress_wall_s = 0;  // wall time from start until the sim first reported
  std::size_t finished_actions = 0;
  std::size_t total_actions = 0;
  std::vector<RobotMetrics> robots;
  // The robots' waiting split by why they waited (execution.hpp WaitCause; sums to their
  // waiting_time_s), when the execution tells (lifelong runs).
  std::optional<std::array<double, kWaitCauses>> waiting_by_cause_s;
  // Sim time each action finished, by ADG node (ActionPlan::offset[robot] + seq); NaN: not
  // finished, or finished before a resume. What a viewer needs to show a robot's current
  // action and who it waits for at any time of a replay (actions.csv).
  std::vector<double> action_finish_s;
  uint64_t robot_contacts = 0;
  uint64_t wall_contacts = 0;
  std::optional<double> min_gap_m;
  // Real time: what the robots' reported poses show (separation_watch.hpp), sampled.
  uint64_t pose_contacts = 0;
  std::optional<double> pose_min_gap_m;
  std::optional<PoseContact> first_pose_contact;
  std::optional<double> host_peak_rss_mb;  // largest peak memory a sim host reported
  // Resumed runs: finish and waiting times before the resume are unknown (finish_time_s NaN
  // for robots already done; AET and makespan then unknown).
  bool resumed = false;
  double resumed_at_s = 0;                 // sim time of the first tick after the resume
  std::size_t finished_before_resume = 0;  // actions
  std::size_t robots_done_before_resume = 0;
  bool have_sim_status = false;
  std::optional<std::pair<uint32_t, uint32_t>> first_collision;  // robots, from the sim host
  // A switchable run (issue 29): "switchable" (or "switchable-opt": SwitchOptions::anticipate),
  // and every switch of a passing order; else "adg".
  std::string execution = "adg";
  std::vector<PassingSwitch> switches;
  double first_collision_s = 0;  // sim time of the status that first reported it
  double goal_tolerance_m = 0;
  std::vector<uint32_t> off_goal;         // robots seen away from their goal after finishing
  std::vector<uint32_t> goal_unverified;  // robots not seen after finishing
  uint64_t rejected_progress = 0;
  // Samples the edge dropped before they became events (convert/validate.hpp): topic -> reason
  // class -> count, a few verbatim reasons per class, and who sent them (bounded).
  std::map<std::string, std::map<std::string, uint64_t>> rejected_samples;
  std::map<std::string, std::map<std::string, std::vector<std::string>>> rejected_examples;
  struct Suspect {
    std::string sender;                       // participant GUID prefix (host, pid, process)
    std::map<std::string, uint64_t> samples;  // topic -> refused samples
    std::string first_reason;
  };
  std::vector<Suspect> suspected_intruders;
};

struct SupervisorConfig {
  bool lockstep = true;
  uint32_t window_cap = 32;  // look-ahead: most actions in one window
  // Wall time without any sign of the sim host (lock-step), or of a robot's host (real time).
  double timeout_s = 30.0;
  // Wall time for the first sign of a sim host; 0: timeout_s. `smart run` gives the sim host it
  // starts longer (a loaded machine starts it slowly; its exit is noticed at once anyway).
  double join_timeout_s = 0;
  double stall_timeout_s = 300.0;  // sim time without any finished action
  double max_sim_time_s = 0;       // 0: no limit
  uint64_t run_id = 1;
  int domain_id = 0;  // named in "no host joined" errors
  double cell_m = 1.0;
  // How far from its goal cell's centre a finished robot may stand; 0: a quarter cell, well
  // beyond a controller's stop tolerance (centimetres) and well short of a neighbouring cell.
  double goal_tolerance_m = 0;
  // Real time: the robots' radius, to watch their reported poses for contacts; 0: not watched.
  double robot_radius_m = 0;
  // A simulated run: success needs the sim host's final status (results: sim_status_received).
  bool require_sim_status = false;
  // Lock-step: the last answer goes out again after this much wall time without a newer tick
  // (the monitor node sets the clock's re-announce period of idl/smart.idl); 0: never.
  double reanswer_s = 0;
  // A plan's run: passing orders may switch while it goes (issue 29, switchable_tracker.hpp).
  bool switchable = false;
  SwitchOptions switch_options = {};
  // Resuming a switchable run (resume()): the switches the stopped monitor had made, in order
  // (its live switches.csv), replayed onto the plan's passing orders before the tracker is built.
  std::vector<PassingSwitch> resume_switches = {};
};

// Samples as the supervisor sees them (the edge converts the wire types).
struct ProgressEvent {
  uint32_t robot = 0;
  uint64_t run_id = 0;
  int64_t finished_seq = -1;
};
struct StateEvent {
  uint32_t robot = 0;
  uint64_t run_id = 0;
  double x_m = 0, y_m = 0;  // world frame (grid/grid.hpp)
};
struct SimStatusEvent {
  uint64_t run_id = 0;
  uint64_t robot_contacts = 0;
  uint64_t wall_contacts = 0;
  double min_gap_m = 0;
  double peak_rss_mb = 0;
  int64_t first_contact_a = -1, first_contact_b = -1;  // -1: no collision
  double sim_time_s = 0;                               // when the sim host wrote it
};

// Where the supervisor's decisions go (the DDS edge; a recording fake in tests).
class RunWriter {
 public:
  virtual ~RunWriter() = default;
  // Publish robot's window: actions [window.first, window.end) of its plan.
  virtual void publish_window(uint32_t robot, uint64_t run_id, ExecutionTracker::Window w) = 0;
  virtual void answer_tick(const wire::Tick& answer) = 0;
  // A plan's action `seq` of `robot` finished at sim_time_s: the time actions.csv gets
  // (MonitorResult::action_finish_s), said once per action as it is decided (a recording made
  // while the run goes, record/live_recording.hpp). Lifelong runs do not say it.
  virtual void action_finished(uint32_t /*robot*/, uint32_t /*seq*/, double /*sim_time_s*/) {}
  // A passing order switched (a switchable run), said before any window it changes is
  // published: kept where a new monitor can find it (results.hpp SwitchesCsvWriter), the
  // orders a resume must rebuild.
  virtual void switched(const PassingSwitch& /*s*/) {}
};

class RunSupervisor {
 public:
  RunSupervisor(const Instance& instance, const SupervisorConfig& config, RunWriter& writer);
  // A lifelong run (execution.hpp): `execution` grows while the run goes (on_time after each
  // answered tick or real-time poll), is complete when its duration passed, and has no final goals.
  RunSupervisor(Execution& execution, const SupervisorConfig& config, RunWriter& writer);

  // Before start(): take over a run from the hosts' reported progress (any order, any
  // duplicates). Returns an error naming what does not fit; the run then is over (host lost).
  std::string resume(const std::vector<ProgressEvent>& reported);
  void start(double now_s);  // publishes every robot's window

  void on_clock(const wire::Tick& tick, double now_s);
  void on_progress(const ProgressEvent& progress, double now_s);
  // True when the state belongs to this run (then it is worth recording).
  bool on_state(const StateEvent& state, double now_s);
  void on_sim_status(const SimStatusEvent& status);
  void on_hosts_matched(uint32_t count, double now_s);
  void on_host_failure(const std::string& what);
  // Another monitor owns the run: end without a word to the hosts (they follow the owner).
  void refuse(const std::string& why);
  void stop(const std::string& why);
  void poll(double now_s);
  // Ends the run (if it is not over yet: stopped) and sends every host the final stop.
  void finish(double now_s);
  // After finish() and the hosts' final states and status: the verdict on a complete run.
  void conclude();

  bool over() const { return res_.outcome != Outcome::kRunning; }
  // The sim host's last word is in: a status of this run (lock-step: stamped at or after the last
  // tick, so no contact can follow it). The edge drains until it is, or the sim host left.
  bool has_final_sim_status() const;
  // Lock-step: nothing to do with progress until a tick is pending (the edge may sleep on ticks).
  bool wants_progress() const { return !config_.lockstep || handshake_.pending().has_value(); }
  const MonitorResult& result() const { return res_; }
  const Execution& execution() const { return *exec_; }
  // A plan's run: each robot's activity and waits now, as its ADG or passing orders have them
  // (the plan view draws it).
  PlanSnapshot plan_snapshot() const;
  std::size_t robots_done() const;
  // Things worth a log line (rejected progress, the resume), taken by the edge.
  std::vector<std::string> take_notes();

 private:
  void init(std::size_t robots);
  void end(Outcome outcome, std::string error);
  void advance_time(double time_s);
  void publish_window(uint32_t robot);
  void take_switches();  // the execution's new switches: into the results, said to the writer
  void apply_progress(const ProgressEvent& p, double sim_time_s);
  void hold_progress(const ProgressEvent& p);
  void take_held_progress(double now_s);
  void try_answer(double now_s);
  void update_waiting(double sim_time_s);
  void count_wait_cause(uint32_t robot, double dt, double sim_time_s, bool began);
  void check_end();
  void check_liveness(double now_s);
  std::string resume_check(const std::vector<ProgressEvent>& reported, std::vector<int64_t>& target,
                           uint64_t& run) const;
  void resume_fixpoint(const std::vector<int64_t>& target);
  void mark_done(uint32_t robot, double sim_time_s);
  std::optional<std::string> collision_seen() const;

  const Instance* in_ = nullptr;  // a plan's run; nullptr in a lifelong run
  SupervisorConfig config_;
  RunWriter& writer_;
  std::optional<ExecutionTracker> tracker_;      // a plan's run
  std::optional<SwitchableTracker> switchable_;  // a plan's run with --execution switchable
  Execution* exec_ = nullptr;
  std::size_t taken_switches_ = 0;       // of exec_->switches()
  std::size_t unreplayed_switches_ = 0;  // of config.resume_switches: matched no pair
  wire::MonitorHandshake handshake_;
  wire::SyncCounter sent_;  // end of the windows published, per robot
  // Lock-step: the progress of the tick under way, held until it adds up (hold_progress).
  static constexpr int64_t kNoneHeld = INT64_MIN;
  std::vector<int64_t> held_seq_;      // per robot: newest finished_seq held, kNoneHeld if none
  std::vector<uint32_t> held_robots_;  // robots with progress held
  uint64_t held_gain_ = 0;             // finished actions the held progress adds
  std::vector<uint8_t> waiting_;
  // Why each robot waits, as last told, and when to ask again (count_wait_cause).
  static constexpr double kWaitCauseRefreshS = 0.5;
  struct ToldCause {
    WaitCause cause = WaitCause::kAtLocation;
    double next_s = 0;
  };
  std::vector<ToldCause> wait_cause_;
  std::vector<double> robot_seen_s_;         // real time: when each robot's host was last heard of
  std::vector<grid::WorldPoint> goal_;       // per robot, world frame
  std::vector<grid::WorldPoint> last_pose_;  // per robot, the last pose seen
  std::vector<uint8_t> seen_done_;           // a pose was seen after the robot finished
  MonitorResult res_;
  std::vector<std::string> notes_;
  double last_finish_sim_s_ = 0;
  double last_metrics_sim_s_ = 0;
  double last_sim_sign_s_ = 0;
  uint32_t max_matched_ = 0;
  bool sim_seen_ = false;
  uint64_t newest_tick_ = 0;                   // the newest tick of this run announced by the sim
  double status_sim_time_s_ = -1;              // of the newest sim status of this run
  std::optional<SeparationWatch> separation_;  // real time with robot_radius_m
};

}  // namespace smart::monitor
