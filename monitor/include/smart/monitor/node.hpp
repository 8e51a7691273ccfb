// Contract: the monitor process's DDS edge, a thin pump around the RunSupervisor
// (run_supervisor.hpp), which decides everything about the run: it reads the wire (ticks,
// progress, states, sim status, matched hosts), converts samples into the supervisor's events,
// and writes its decisions (action windows, tick answers) back. Windows are pushed on the keyed
// action topic as soon as they change. At the end every host is told to stop (and the delivery
// awaited), and the sim's final status is drained.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/monitor/run_supervisor.hpp"

namespace smart::monitor {

struct MonitorOptions {
  // The run policy; run.run_id 0: derived from the wall clock (increasing run to run).
  SupervisorConfig run{.run_id = 0};
  double cell_m = 1.0;
  // Take over a run whose monitor died: the run id and every robot's finished actions come
  // from the hosts' progress (transient local, kept by their writers); windows continue from
  // there. Fails if no host reports progress within run.timeout_s or the progress does not fit
  // this plan's ADG.
  bool resume = false;
  // Optional watchdog for hosts this process started (`smart run`'s sim child), polled about
  // every 100 ms: a non-empty message ends the run at once (host lost) with that error,
  // instead of after timeout_s of silence.
  std::function<std::string()> host_check;
  // Robot states as they arrive (e.g. streamed to states.csv by StatesCsvWriter, results.hpp).
  // Not kept in memory: 1000 robots at 2 Hz for 20 min are 2.4 M rows.
  std::function<void(const StateRow&)> on_state;
  // Finished actions so far, when the count changed (checked about every 100 ms of wall time;
  // e.g. streamed to progress.csv by ProgressCsvWriter, results.hpp): live views' progress.
  std::function<void(const results::ProgressRow&)> on_finished;
  // Each action of a plan's run as it finishes (RunWriter::action_finished: robot, seq, sim
  // time), on the monitor's thread: e.g. a recording made while the run goes.
  std::function<void(uint32_t, uint32_t, double)> on_action_finished;
  // Each switch of a passing order (a switchable run) as it is made, before any window it
  // changes is published (RunWriter::switched): e.g. the live switches.csv a resume replays.
  std::function<void(const PassingSwitch&)> on_switch;
  // Each robot's finished actions (by robot), when any changed, at most once a second of wall
  // time: a live view's robot panel (e.g. write_finished_csv, results.hpp).
  std::function<void(const std::vector<uint32_t>&)> on_robots_finished;
  // The plan view for rviz2 (ros_plan_view.hpp) at this rate in wall time; 0: off.
  double ros_plan_hz = 0;
  double robot_radius_m = 0.1;  // robot markers' size
  std::string ros_namespace;    // the plan view's topics under it ("" or "/run_a")
};

// A run id from the wall clock, increasing run to run: what a run given run id 0 gets.
uint64_t wall_clock_run_id();

// Called about every 100 ms of wall time with the running state (progress display).
using ProgressCallback = std::function<void(const MonitorResult&, std::size_t robots_done)>;

class MonitorNode {
 public:
  MonitorNode(const dds::Participant& participant, const dds::QosProfile& qos,
              const Instance& instance, const MonitorOptions& options);
  // A lifelong run (execution.hpp, lifelong/): no plan, the ADG grows while robots execute.
  MonitorNode(const dds::Participant& participant, const dds::QosProfile& qos, const Grid& grid,
              Execution& lifelong, const MonitorOptions& options);
  ~MonitorNode();
  MonitorResult run(const std::atomic<bool>& stop_requested, const ProgressCallback& progress = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::monitor
