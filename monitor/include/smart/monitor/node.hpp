// Contract: the monitor process's DDS edge. Given a loaded Instance (validated plan, actions,
// ADG) it publishes each robot's action window on the keyed action topic (push: a robot gets
// new actions as soon as they are enqueued), consumes cumulative progress, advances the
// ExecutionTracker, and detects completion, ADG deadlock, stalls (no action finished for
// stall_timeout_s of sim time) and a lost host (lock-step: the sim's writers unmatched, or
// silent for timeout_s of wall time; real time: no state of a robot for timeout_s, so a host
// that restarts within it carries on). Lock-step mode answers each sim tick only after applying
// exactly the progress the tick announces (idl/smart.idl, Clock). Metrics are on the sim clock
// (wall time separately). The run ends with a stop on the clock topic so hosts shut down.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/monitor/instance.hpp"

namespace smart::monitor {

struct StateRow {
  double t_s;
  uint32_t robot;
  double x_m, y_m, yaw_rad, v_mps, w_radps, left_mps, right_mps;
  uint32_t queue;
};

struct MonitorOptions {
  bool lockstep = true;
  uint32_t window_cap = 32;  // look-ahead: most actions in one window
  double cell_m = 1.0;
  // Wall time without any sign of the sim host (lock-step), or of a robot's host, sim or agent
  // (real time: hosts may restart within it).
  double timeout_s = 30.0;
  double stall_timeout_s = 300.0;  // sim time without any finished action
  double max_sim_time_s = 0;       // 0: no limit
  uint64_t run_id = 0;             // 0: derived from the wall clock (increasing run to run)
  // Take over a run whose monitor died: the run id and every robot's finished actions come
  // from the hosts' progress (transient local, kept by their writers); windows continue from
  // there. Fails if no host reports progress within timeout_s or the progress does not fit
  // this plan's ADG.
  bool resume = false;
  // Optional watchdog for hosts this process started (`smart run`'s sim child), polled about
  // every 100 ms: a non-empty message ends the run at once as sim_lost with that error, instead
  // of after timeout_s of silence.
  std::function<std::string()> host_check;
  // Robot states as they arrive (e.g. streamed to states.csv by StatesCsvWriter, results.hpp).
  // Not kept in memory: 1000 robots at 2 Hz for 20 min are 2.4 M rows.
  std::function<void(const StateRow&)> on_state;
};

struct RobotMetrics {
  double finish_time_s = 0;   // sim time its last action finished (0: no actions)
  double waiting_time_s = 0;  // not done, nothing enqueued to execute (waiting for others)
  uint32_t stops = 0;         // times it became blocked that way
  uint32_t actions = 0;
};

struct MonitorResult {
  bool success = false;
  bool deadlock = false;
  bool sim_lost = false;
  bool stalled = false;
  std::string error;
  uint64_t run_id = 0;
  double sim_time_s = 0;
  double wall_time_s = 0;
  double first_progress_wall_s = 0;  // wall time from start until the sim first reported
  std::size_t finished_actions = 0;
  std::size_t total_actions = 0;
  std::vector<RobotMetrics> robots;
  uint64_t robot_contacts = 0;
  uint64_t wall_contacts = 0;
  std::optional<double> min_gap_m;
  std::optional<double> host_peak_rss_mb;  // largest peak memory a sim host reported
  // Resumed runs: finish and waiting times before the resume are unknown (finish_time_s NaN
  // for robots already done; AET and makespan then unknown).
  bool resumed = false;
  double resumed_at_s = 0;                 // sim time of the first tick after the resume
  std::size_t finished_before_resume = 0;  // actions
  std::size_t robots_done_before_resume = 0;
  bool have_sim_status = false;
  uint64_t rejected_progress = 0;
};

// Called about every 100 ms of wall time with the running state (progress display).
using ProgressCallback = std::function<void(const MonitorResult&, std::size_t robots_done)>;

class MonitorNode {
 public:
  MonitorNode(const dds::Participant& participant, const dds::QosProfile& qos,
              const Instance& instance, const MonitorOptions& options);
  ~MonitorNode();
  MonitorResult run(const std::atomic<bool>& stop_requested, const ProgressCallback& progress = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::monitor
