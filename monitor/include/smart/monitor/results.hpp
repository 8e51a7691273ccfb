// Contract: turns a finished run into its result files (file edge):
// - summary.json: success, robots, aet_s, makespan_s, sim_time_s, wall_time_s, sim_speed,
//   collisions (robot-robot), wall_contacts, min_separation_m (closest approach between robot
//   surfaces; negative = overlap), waiting_time_s (mean, total and, when the execution tells
//   why robots wait, by_cause: execution.hpp WaitCause), execution (mode, switches and, for a
//   switching one, its options), adg, plan, per-run flags and versions;
// - stats.csv: one row with SMART's stats columns (server/src/ADG_server.cpp saveStats); its
//   two wall-clock columns hold sim time here and are named so ("makespan sim s", "sum of
//   finish times sim s");
// - robots.csv: per robot finish time (empty: not finished, or before a resume), waiting time,
//   stops, actions, motion lower bound (empty: limits unknown);
// - actions.csv: per action (ADG order) robot, seq, type and the sim time it finished;
// - states.csv: t, robot, x, y, yaw, v, ω, left/right wheel speed, queue length, written row by
//   row while the run goes (StatesCsvWriter), so memory does not grow with the run.
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "smart/monitor/instance.hpp"
#include "smart/monitor/motion_bound.hpp"
#include "smart/monitor/run_supervisor.hpp"

namespace smart::monitor {

// NOLINTNEXTLINE(bugprone-exception-escape): clang-tidy 14 flags the implicit special members
struct RunInfo {
  std::string map, scen, plan, robot, qos, clock;
  std::string run;  // the run name (its DDS partition, idl/smart.idl "Runs")
  double cell_m = 1.0;
  double control_period_s = 0.1;
  uint64_t seed = 0;
  uint32_t sim_hosts = 1;  // `smart run --sim-hosts`: the sim's shards (sim/shard.hpp)
  // Robots handed from one shard to another over the run, when `smart run` read its shards'
  // reports.
  std::optional<uint64_t> sim_handovers;
  // Filled by the tools when known: peak resident memory of the monitor process (the sim's
  // comes with its status, MonitorResult::host_peak_rss_mb) and the machine the run was
  // measured on.
  std::optional<double> monitor_peak_rss_mb;
  // CPU seconds (user + system) of the monitor and, when `smart run` started it, the sim host.
  std::optional<double> monitor_cpu_s, sim_cpu_s;
  std::string machine;
  // The robot model's limits, when known: each robot's motion lower bound (motion_bound.hpp)
  // goes into robots.csv and their AET / makespan and the finish-over-bound ratios into
  // summary.json ("motion_bound").
  std::optional<MotionLimits> limits;
  std::string robot_model;  // the model's name (its YAML's name:), shown with its limits
  // The execution uncertainty the run had (agent/uncertainty.hpp to_json); null: none given.
  nlohmann::json uncertainty;
  nlohmann::json link;  // the link model (smart/wire/link.hpp to_json); null: not known
  // A switching execution's knobs (switching.hpp), so a run's summary says which settings
  // made its switches ("execution": "options"); none: plain ADG.
  std::optional<SwitchOptions> switching;
};

// The "adg" and "plan" objects shared by summary.json and `smart check-plan`.
nlohmann::json adg_json(const AdgStats& stats);
nlohmann::json plan_json(const Plan& plan, const PlanStats& stats);
// How long loading the instance took: read, validate, actions, adg, acyclic, adg_total (ms).
nlohmann::json build_time_json(const InstanceTimings& timings);
// Every knob of a switching execution, named as SwitchOptions' fields.
nlohmann::json switch_options_json(const SwitchOptions& options);

nlohmann::json summary_json(const Instance& instance, const MonitorResult& result,
                            const RunInfo& info);
// What every run's summary.json holds, whether it executed a plan or a lifelong stream (a
// lifelong run adds its "lifelong" object: lifelong/, tools/).
nlohmann::json run_summary_json(const MonitorResult& result, const RunInfo& info);
// Streams states.csv into `dir` (created if missing); throws std::runtime_error naming the
// file when it cannot be written.
class StatesCsvWriter {
 public:
  explicit StatesCsvWriter(const std::filesystem::path& dir);
  void add(const StateRow& row);
  // A row already written by results::append_row (with its newline), e.g. shared with another
  // reader of the same rows.
  void add_line(std::string_view line);
  std::size_t rows() const { return rows_; }

 private:
  std::ofstream out_;
  std::size_t rows_ = 0;
};

// progress.csv in `dir`, a row per call, flushed: read while the run goes (results_format.hpp).
class ProgressCsvWriter {
 public:
  explicit ProgressCsvWriter(const std::filesystem::path& dir);
  void add(const results::ProgressRow& row);

 private:
  std::ofstream out_;
};

// finished.csv in `dir`, replaced whole at each write (written aside, then renamed): a reader
// never sees half of it (results_format.hpp).
void write_finished_csv(const std::filesystem::path& dir, const std::vector<uint32_t>& finished);

// Appends the run's stats.csv row to `file` (with the header when the file is new or empty): a
// batch of runs in one table, as SMART users keep it. Throws std::runtime_error naming the file.
void append_stats(const std::filesystem::path& file, const Instance& instance,
                  const MonitorResult& result, const RunInfo& info);

// Writes summary.json, stats.csv, robots.csv and actions.csv into `dir` (created if missing).
// Throws std::runtime_error naming the file when it cannot be written.
// switches.csv (results_format.hpp kSwitchesCsv): every switch of a passing order (adg.hpp
// switch_row; `actions` null: a lifelong run's, whose actions are no fixed plan).
void write_switches_csv(const std::filesystem::path& dir, const Grid& grid,
                        const ActionPlan* actions, const std::vector<PassingSwitch>& switches);

// switches.csv in `dir` while a run goes: a row per switch as it is made, flushed before the
// windows it changes are published, so that `smart monitor --resume --resume-switches` can
// rebuild the passing orders a monitor that stopped had reached. write_results() writes the
// whole file again at the end.
class SwitchesCsvWriter {
 public:
  explicit SwitchesCsvWriter(const std::filesystem::path& dir);
  void add(const results::SwitchRow& row);

 private:
  std::ofstream out_;
};

void write_results(const std::filesystem::path& dir, const Instance& instance,
                   const MonitorResult& result, const RunInfo& info);

}  // namespace smart::monitor
