// Contract: the command-line options of the jobs that read an instance or execute a plan,
// bound straight to the library structs they configure (enums parsed into their types):
// - InstanceCliOptions: map + scen + plan as monitor::InstanceOptions (`check-plan`, `monitor`,
//   `run`);
// - SimCliOptions: one option set for the sim host (`smart sim`, and what `smart run` passes to
//   its sim child: sim_argv() generates that command line from the struct, so the two cannot
//   drift apart);
// - MonitorCliOptions: the monitor's run policy on top (`monitor`, `run`).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "smart/monitor/instance.hpp"
#include "smart/monitor/node.hpp"
#include "smart/planning/goal_heuristic.hpp"
#include "smart/sim/host.hpp"
#include "smart/tools/cli_common.hpp"

namespace smart::tools {

extern const EnumNames<grid::Heading> kHeadingNames;
extern const EnumNames<sim::ClockMode> kClockNames;
extern const EnumNames<grid::AxisOrder> kAxisNames;
extern const EnumNames<grid::PlanFormat> kFormatNames;
extern const EnumNames<planning::HeuristicKind> kHeuristicNames;

// Map, scenario, robot count and start heading: what every job on a fleet shares.
struct WorldCliOptions {
  std::string map, scen;
  std::size_t agents = 0;  // first N robots of the scenario / plan; 0: all
  grid::Heading heading = grid::Heading::kEast;
  double cell_m = 1.0;
  std::string robot = "footbot";  // name in config/robots or a YAML file
};

// Where a lifelong run's map, robots and tasks come from: every process of the run (`smart run`,
// `smart monitor`, `smart sim`) loads the same problem, so hosts agree on the world.
struct TaskSourceOptions {
  std::string problem;   // --lifelong PROBLEM.json (LoRR 2024/2026)
  std::string tasks;     // --tasks random: generated on --map for --agents robots
  uint32_t errands = 2;  // --task-errands: errands per generated task
  bool active() const { return !problem.empty() || !tasks.empty(); }
};

struct SimCliOptions {
  DdsOptions dds;
  WorldCliOptions world;
  TaskSourceOptions source;  // a lifelong problem instead of --scen
  sim::ClockMode clock = sim::ClockMode::kLockstep;
  double state_rate_hz = 2.0;
  double timeout_s = 30.0;
  int system_capacity = 0;         // robot bodies per Simbody system (0: automatic)
  int threads = 0;                 // 0: automatic (sim::sim_threads)
  double real_time_factor = 0;     // lockstep: at most this many times real time; 0: unpaced
  std::vector<uint32_t> external;  // `smart sim` only: robots executed by other hosts
  std::vector<uint32_t> ros_pose_robots;
  std::string ros_namespace;       // --ros-namespace: the ROS 2 view's topics under it
  uint32_t shard = 0, shards = 1;  // `smart sim --shard I/N` (sim/shard.hpp)
  // Execution uncertainty overrides of the robot model's `uncertainty:` section.
  std::optional<double> stall_probability, stall_s, speed_sigma, slip_sigma;
  // Delay events (agent/uncertainty.hpp; a LoRR delayConfig sets them in lifelong runs).
  std::optional<double> delay_probability, delay_rate_hz, delay_min_s, delay_max_s,
      delay_mean_ratio, delay_std_ratio;
  std::optional<uint64_t> seed;
};

// The robot model named by --robot with the command line's uncertainty overrides applied.
agent::RobotModel run_robot_model(const SimCliOptions& o);

// `smart run --lifelong` (lifelong/): how windows are planned (the problem: TaskSourceOptions).
struct LifelongCliOptions {
  double duration_s = 600;  // sim seconds (lock-step) or wall seconds (real time)
  double period_s = 1.0;
  uint32_t replan_when_left = 0;
  int window_steps = 10;
  uint32_t lookahead = 8;
  double budget_s = 0.1;
  double distance_budget_mb = 1024;
  planning::HeuristicKind heuristic = planning::HeuristicKind::kAuto;
  int lns_passes = 0;  // --window-lns-passes: planning/window_lns.hpp over PIBT's windows
  // Where windows are planned: in this process, or by a `smart planner` of the run over DDS
  // (tools/dds_planner.hpp); --planner-cmd (tools/pipe_planner.hpp) replaces the built-in one.
  enum class Planner { kBuiltin, kExternal };
  Planner planner = Planner::kBuiltin;
  double planner_wait_s = 60;  // --planner external: wall seconds to wait for one
  std::string planner_cmd;
  double planner_timeout_s = 2.0;           // wall seconds per window
  enum class Fallback { kStop, kBuiltin };  // a refused external window: wait, or built-in
  Fallback planner_fallback = Fallback::kStop;
  std::string lorr_output;  // a LoRR output JSON at the run's end (lifelong/lorr_output.hpp)
  bool external() const { return planner == Planner::kExternal || !planner_cmd.empty(); }
};

struct MonitorCliOptions {
  SimCliOptions sim;  // `smart run` passes these on to its sim child
  LifelongCliOptions lifelong;
  std::string plan, out;
  std::string stats;  // --stats FILE: a stats.csv row appended per run
  std::optional<grid::AxisOrder> axis;
  grid::PlanFormat format = grid::PlanFormat::kAuto;
  uint32_t window_cap = 32;
  // --execution: the plan's passing orders fixed (adg) or switched while it goes (issue 29).
  enum class Execution { kAdg, kSwitchable, kSwitchableOpt, kSwitchableLookahead };
  Execution execution = Execution::kAdg;
  // --switch-commit-actions and --switch-chain-locations (none: SwitchOptions' defaults), read
  // by every switching execution, plan and lifelong runs alike; plain ADG refuses them.
  std::optional<uint32_t> switch_commit_actions, switch_chain_locations;
  // Anticipation's knobs (none: SwitchOptions' defaults): --switch-margin-s and
  // --switch-horizon-actions (switchable-opt and -lookahead), --switch-lookahead-actions (the
  // lookahead's reach). The executions that do not read one refuse it.
  std::optional<double> switch_margin_s;
  std::optional<uint32_t> switch_horizon_actions, switch_lookahead_actions;
  // --switch-window-pairs (the lookahead's window search; SwitchOptions::window_pairs).
  std::optional<uint32_t> switch_window_pairs;
  double stall_timeout_s = 300.0, max_sim_time_s = 0;
  bool resume = false;  // `smart monitor` only
  // --resume-switches FILE: a switchable run's live switches.csv, replayed by --resume.
  std::filesystem::path resume_switches;
  // Success needs a sim host's final status: lock-step, `smart run`, or --require-sim-status.
  bool require_sim_status = false;
  bool progress = true;
  double ros_plan_hz = 0;  // the rviz2 plan view; 0: off
  // `smart run --mcap` of a plan's run: recorded while it goes (record/live_recording.hpp);
  // empty otherwise (a lifelong run is recorded from its results by the caller).
  std::string mcap;
};

// --map --scen --agents --initial-heading --cell-m --robot.
void add_world_options(CLI::App* cmd, WorldCliOptions& o);
void add_plan_options(CLI::App* cmd, std::string& plan, std::optional<grid::AxisOrder>& axis,
                      grid::PlanFormat& format);
// DDS, world, --clock, --state-rate-hz, --timeout-s: shared by sim, monitor and run.
void add_common_run_options(CLI::App* cmd, SimCliOptions& o);
// --system-capacity, --threads, --ros-pose-robots: the sim host's own (sim and run).
void add_sim_host_options(CLI::App* cmd, SimCliOptions& o);
// The monitor's options: plan, results, run policy, progress bar.
void add_monitor_options(CLI::App* cmd, MonitorCliOptions& o);

// --lifelong, --tasks, --task-errands (`smart run`, `monitor`, `sim`); --map, --scen and --plan
// then stop being required (run_monitor and run_sim check them for plan runs).
void add_task_source_options(CLI::App* cmd, TaskSourceOptions& o);
// The replanning policy of a lifelong run (`smart run`, `smart monitor`).
void add_lifelong_options(CLI::App* cmd, LifelongCliOptions& o);
// Throws std::invalid_argument naming the flags a plan run lacks (--map, --scen, --plan).
void check_plan_run_flags(const MonitorCliOptions& o);

// How the ADG orders robots of the world's robot model on its cells (monitor/adg.hpp); throws
// std::invalid_argument when the robots are too wide for the cells.
monitor::Footprint robot_footprint(const WorldCliOptions& world);
// The instance of the world and plan, with robot_footprint(world).
monitor::InstanceOptions instance_options(const WorldCliOptions& world, const std::string& plan,
                                          std::optional<grid::AxisOrder> axis,
                                          grid::PlanFormat format);
// Throws std::invalid_argument naming the flags when --real-time-factor is given with --clock
// realtime (pacing is for lock-step runs).
void check_real_time_factor(const SimCliOptions& o);
// The sim host's options (checks them with check_real_time_factor first).
sim::SimHostOptions sim_host_options(const SimCliOptions& o);
// "I/N" of --shard: shard I (from 0) of N; throws std::invalid_argument saying what is wrong.
std::pair<uint32_t, uint32_t> parse_shard(const std::string& text);
// What --execution and --switch-commit-actions ask of switching (plan and lifelong runs).
monitor::SwitchOptions switch_options(const MonitorCliOptions& o);
monitor::MonitorOptions monitor_options(const MonitorCliOptions& o);
// `exe sim ...` with every option of `o`, for `smart run`'s child.
std::vector<std::string> sim_argv(const std::string& exe, const SimCliOptions& o);

}  // namespace smart::tools
