#include "smart/tools/run_options.hpp"

#include <spdlog/spdlog.h>

#include "smart/dds/topics.hpp"

namespace smart::tools {

const EnumNames<grid::Heading> kHeadingNames{{"east", grid::Heading::kEast},
                                             {"north", grid::Heading::kNorth},
                                             {"west", grid::Heading::kWest},
                                             {"south", grid::Heading::kSouth}};
const EnumNames<sim::ClockMode> kClockNames{{"lockstep", sim::ClockMode::kLockstep},
                                            {"realtime", sim::ClockMode::kRealtime}};
const EnumNames<grid::AxisOrder> kAxisNames{{"xy", grid::AxisOrder::kXY},
                                            {"rowcol", grid::AxisOrder::kRowCol}};
const EnumNames<planning::HeuristicKind> kHeuristicNames{
    {"auto", planning::HeuristicKind::kAuto},
    {"tables", planning::HeuristicKind::kTables},
    {"paths", planning::HeuristicKind::kPaths}};
const EnumNames<grid::PlanFormat> kFormatNames{{"auto", grid::PlanFormat::kAuto},
                                               {"smart", grid::PlanFormat::kSmart},
                                               {"lacam", grid::PlanFormat::kLacam},
                                               {"yaml", grid::PlanFormat::kYaml}};

void add_world_options(CLI::App* cmd, WorldCliOptions& o) {
  cmd->add_option("--map", o.map, "MovingAI .map file")->required();
  cmd->add_option("--scen", o.scen, "MovingAI .scen file (robot starts)")->required();
  cmd->add_option("--agents,--robots", o.agents,
                  "number of robots (first N of the scenario / plan)")
      ->check(CLI::PositiveNumber);
  add_enum_option(cmd, "--initial-heading", o.heading, kHeadingNames,
                  "heading every robot starts with (default east)");
  cmd->add_option("--cell-m", o.cell_m, "grid cell size in metres")
      ->check(finite_in(0.05, 100.0))
      ->capture_default_str();
  cmd->add_option("--robot", o.robot, "robot model: name in config/robots or a YAML file")
      ->capture_default_str();
}

void add_plan_options(CLI::App* cmd, std::string& plan, std::optional<grid::AxisOrder>& axis,
                      grid::PlanFormat& format) {
  cmd->add_option("--plan", plan, "plan file (SMART/MAPF-LNS2, LaCAM/PIBT, YAML)")->required();
  add_enum_option(cmd, "--axis", axis, kAxisNames,
                  "xy (x = column) or rowcol; required for SMART path files");
  add_enum_option(cmd, "--format", format, kFormatNames, "plan format (default auto)");
}

namespace {
// Execution uncertainty (agent/uncertainty.hpp), overriding the robot model's section.
void add_uncertainty_options(CLI::App* cmd, SimCliOptions& o) {
  cmd->add_option("--stall-probability", o.stall_probability,
                  "chance that a robot at rest stalls before an action")
      ->check(finite_in(0.0, 1.0));
  cmd->add_option("--stall-s", o.stall_s, "how long a stall lasts (sim seconds)")
      ->check(finite_in(0.0, 3600.0));
  cmd->add_option("--speed-sigma", o.speed_sigma,
                  "per-robot top-speed factor ~ N(1, sigma), clipped to [0.3, 1]")
      ->check(finite_in(0.0, 1.0));
  cmd->add_option("--slip-sigma", o.slip_sigma,
                  "sim wheel slip: each wheel's speed times 1 + N(0, sigma) per control period")
      ->check(finite_in(0.0, 0.5));
  cmd->add_option("--delay-probability", o.delay_probability,
                  "chance per 0.1 s tick that a robot starts a delay event: it stops where it is "
                  "(LoRR 2026 delays, Bernoulli)")
      ->check(finite_in(0.0, 1.0));
  cmd->add_option("--delay-rate-hz", o.delay_rate_hz,
                  "delay events per robot per second (Poisson), instead of --delay-probability")
      ->check(finite_in(0.0, 10.0));
  cmd->add_option("--delay-min-s", o.delay_min_s, "shortest delay (sim seconds)")
      ->check(finite_in(0.0, 3600.0));
  cmd->add_option("--delay-max-s", o.delay_max_s, "longest delay (sim seconds)")
      ->check(finite_in(0.0, 3600.0));
  cmd->add_option("--delay-mean-ratio", o.delay_mean_ratio,
                  "Gaussian delays: mean at min + ratio x (max - min)")
      ->check(finite_in(0.0, 1.0));
  cmd->add_option("--delay-std-ratio", o.delay_std_ratio,
                  "Gaussian delays: sd = ratio x (max - min); 0: uniform in [min, max]")
      ->check(finite_in(0.0, 10.0));
  cmd->add_option("--seed", o.seed, "seed of the execution uncertainty (same seed, same run)");
}
}  // namespace

agent::RobotModel run_robot_model(const SimCliOptions& o) {
  auto m = agent::load_robot_model(find_config_file("robots", o.world.robot));
  auto& u = m.uncertainty;
  if (o.stall_probability) u.stall_probability = *o.stall_probability;
  if (o.stall_s) u.stall_s = *o.stall_s;
  if (o.speed_sigma) u.speed_sigma = *o.speed_sigma;
  if (o.slip_sigma) u.slip_sigma = *o.slip_sigma;
  if (o.delay_probability) u.delay_probability = *o.delay_probability;
  if (o.delay_rate_hz) u.delay_rate_hz = *o.delay_rate_hz;
  if (o.delay_min_s) u.delay_min_s = *o.delay_min_s;
  if (o.delay_max_s) u.delay_max_s = *o.delay_max_s;
  if (o.delay_mean_ratio) u.delay_mean_ratio = *o.delay_mean_ratio;
  if (o.delay_std_ratio) u.delay_std_ratio = *o.delay_std_ratio;
  if (u.delay_max_s < u.delay_min_s) {
    throw std::invalid_argument("--delay-max-s " + exact(u.delay_max_s) +
                                " is below the shortest "
                                "delay " +
                                exact(u.delay_min_s) +
                                "; give --delay-min-s <= "
                                "--delay-max-s");
  }
  if (o.seed) u.seed = *o.seed;
  return m;
}

void add_common_run_options(CLI::App* cmd, SimCliOptions& o) {
  add_dds_options(cmd, o.dds);
  add_world_options(cmd, o.world);
  add_enum_option(cmd, "--clock", o.clock, kClockNames,
                  "lockstep (bit-identical; default) or realtime");
  cmd->add_option("--state-rate-hz", o.state_rate_hz,
                  "robot state samples per sim second (0: none but each robot's final state)")
      ->check(finite_in(0.0, 1000.0))
      ->capture_default_str();
  add_uncertainty_options(cmd, o);
  cmd->add_option("--timeout-s", o.timeout_s, "wall seconds without the other side before failing")
      ->check(finite_in(0.1, 1e6))
      ->capture_default_str();
  cmd->add_option("--ros-namespace", o.ros_namespace,
                  "put the ROS 2 view's topics under this namespace (e.g. /run_a: /run_a/tf, "
                  "/run_a/smart/poses), so two runs on one domain can be shown side by side")
      ->check([](const std::string& ns) {
        try {
          dds::check_ros_namespace(ns);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      });
}

void add_sim_host_options(CLI::App* cmd, SimCliOptions& o) {
  cmd->add_option("--system-capacity", o.system_capacity,
                  "robot bodies per Simbody system (0: automatic)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  cmd->add_option("--threads", o.threads,
                  "sim threads (0: automatic, 1 below 2000 simulated robots, else 2)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_option("--real-time-factor", o.real_time_factor,
                  "lockstep: run at most this many times real time, to watch a run live (same "
                  "results); 0: as fast as possible")
      ->check(finite_in(0.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--ros-pose-robots", o.ros_pose_robots,
                  "robots that also get a ROS 2 PoseStamped topic rt/robot_<id>/pose")
      ->delimiter(',');
}

void add_monitor_options(CLI::App* cmd, MonitorCliOptions& o) {
  add_common_run_options(cmd, o.sim);
  add_plan_options(cmd, o.plan, o.axis, o.format);
  cmd->add_option("--out", o.out,
                  "folder for summary.json, stats.csv, robots.csv, actions.csv, states.csv");
  cmd->add_option("--stats", o.stats,
                  "append this run's stats.csv row to FILE (its header when new): one table for "
                  "a batch of runs");
  cmd->add_option("--window-cap", o.window_cap, "most actions sent to a robot at once")
      ->check(CLI::Range(1u, dds::kMaxWindowActions))
      ->capture_default_str();
  static const EnumNames<MonitorCliOptions::Execution> kExecutionNames{
      {"adg", MonitorCliOptions::Execution::kAdg},
      {"switchable", MonitorCliOptions::Execution::kSwitchable},
      {"switchable-opt", MonitorCliOptions::Execution::kSwitchableOpt},
      {"switchable-lookahead", MonitorCliOptions::Execution::kSwitchableLookahead}};
  add_enum_option(cmd, "--execution", o.execution, kExecutionNames,
                  "'adg': every shared location passed in the plan's order; 'switchable': a robot "
                  "ready at a free location may pass before one that is late and was not sent "
                  "its way in yet; 'switchable-opt': also, a robot about to be sent its way into "
                  "a shared location yields its place when the next robot is expected to pass "
                  "sooner (expected times learned in the run; docs/execution.md); "
                  "'switchable-lookahead': switchable-opt comparing the two orders by the "
                  "expected times of every action they affect, 24 actions ahead")
      ->capture_default_str();
  cmd->add_option(
         "--switch-commit-actions", o.switch_commit_actions,
         "switching executions: a robot is sent a way into a shared location this many "
         "actions ahead (fewer: more room to switch, but robots brake before such entries; "
         "default 6)")
      ->check(CLI::Range(1u, 1000u));
  cmd->add_option(
         "--switch-chain-locations", o.switch_chain_locations,
         "switching executions: a ready robot that the deadlock search stops because the robot "
         "it would pass goes on ahead of it passes that robot at up to this many shared "
         "locations in a row at once (1: one location at a time; default 8; docs/execution.md)")
      ->check(CLI::Range(1u, 64u));
  cmd->add_option("--switch-margin-s", o.switch_margin_s,
                  "switchable-opt and -lookahead: the expected waiting an anticipated switch must "
                  "save (default 10 s for switchable-opt, 0.5 s for the lookahead)")
      ->check(finite_in(0.0, 3600.0));
  cmd->add_option("--switch-horizon-actions", o.switch_horizon_actions,
                  "switchable-opt and -lookahead: a robot farther than this many actions from a "
                  "location is not expected there yet (default 12)")
      ->check(CLI::Range(1u, 1000u));
  cmd->add_option("--switch-lookahead-actions", o.switch_lookahead_actions,
                  "switchable-lookahead: the two orders are compared over each robot's next this "
                  "many actions (default 24)")
      ->check(CLI::Range(1u, 1000u));
  cmd->add_option("--switch-window-pairs", o.switch_window_pairs,
                  "switchable-lookahead: a pair is compared with every setting of up to this many "
                  "other pairs in its cone, SES's search over a bounded window (default 0: off; "
                  "at most 6; docs/execution.md)")
      ->check(CLI::Range(0u, monitor::kMaxWindowPairs));
  cmd->add_option("--stall-timeout-s", o.stall_timeout_s,
                  "sim seconds without a finished action before failing")
      ->check(finite_in(0.1, 1e9))
      ->capture_default_str();
  cmd->add_option("--max-sim-time-s", o.max_sim_time_s, "fail past this sim time (0: no limit)")
      ->check(finite_in(0.0, 1e9));
  cmd->add_flag("!--no-progress", o.progress, "no progress bar");
  cmd->add_option("--ros-plan-hz", o.ros_plan_hz,
                  "publish the plan for rviz2 (paths on /robot_<id>/plan, robots, goals and "
                  "waits on /smart/markers; config/rviz/smart.rviz) at this rate; 0: off")
      ->check(finite_in(0.0, 50.0))
      ->capture_default_str();
}

void add_task_source_options(CLI::App* cmd, TaskSourceOptions& o) {
  for (const char* name : {"--map", "--scen", "--plan"}) {
    if (auto* opt = cmd->get_option_no_throw(name)) opt->required(false);
  }
  cmd->add_option("--lifelong", o.problem,
                  "run a lifelong problem: a LoRR problem JSON (its map, agents and tasks "
                  "files beside it); replaces --map/--scen/--plan")
      ->check(CLI::ExistingFile);
  cmd->add_option("--tasks", o.tasks,
                  "'random': a lifelong run of seeded random tasks on --map for --agents robots "
                  "(errands alternate endpoints and workstations where the map marks them)")
      ->check(CLI::IsMember({"random"}));
  cmd->add_option("--task-errands", o.errands, "errands per generated task")
      ->check(CLI::Range(1u, 100u))
      ->capture_default_str();
}

namespace {

// Who plans a lifelong run's windows: the built-in planner, a `smart planner` over DDS or a
// command over a pipe, and what happens when its window is refused.
void add_window_planner_options(CLI::App* cmd, LifelongCliOptions& o) {
  static const EnumNames<LifelongCliOptions::Planner> kPlannerNames{
      {"builtin", LifelongCliOptions::Planner::kBuiltin},
      {"external", LifelongCliOptions::Planner::kExternal}};
  add_enum_option(cmd, "--planner", o.planner, kPlannerNames,
                  "who plans the windows: 'builtin' (PIBT in this process) or 'external' (wait for "
                  "a `smart planner` in the run, over DDS; docs/planner-protocol.md)")
      ->capture_default_str();
  cmd->add_option("--planner-wait-s", o.planner_wait_s,
                  "--planner external: wall seconds to wait for a planner to announce itself")
      ->check(finite_in(0.1, 86400.0))
      ->capture_default_str();
  cmd->add_option("--planner-cmd", o.planner_cmd,
                  "plan windows with this command instead of the built-in planner: it runs under "
                  "sh -c and speaks newline-delimited JSON on stdin/stdout "
                  "(docs/planner-protocol.md; examples/planners/)");
  cmd->add_option(
         "--planner-timeout-s", o.planner_timeout_s,
         "wall seconds an external planner has to answer a window (a later answer is refused "
         "as late; robots stop at the cut)")
      ->check(finite_in(0.01, 3600.0))
      ->capture_default_str();
  static const EnumNames<LifelongCliOptions::Fallback> kFallbackNames{
      {"stop", LifelongCliOptions::Fallback::kStop},
      {"builtin", LifelongCliOptions::Fallback::kBuiltin}};
  add_enum_option(
      cmd, "--planner-fallback", o.planner_fallback, kFallbackNames,
      "when an external planner's window is refused: 'stop' (robots finish the committed "
      "actions and wait for the next window) or 'builtin' (the built-in planner plans "
      "that window)")
      ->capture_default_str();
}

}  // namespace

void add_lifelong_options(CLI::App* cmd, LifelongCliOptions& o) {
  cmd->add_option("--duration-s", o.duration_s, "how long a lifelong run goes (sim seconds)")
      ->check(finite_in(0.1, 1e7))
      ->capture_default_str();
  cmd->add_option("--replan-period-s", o.period_s, "plan a new window every this many seconds")
      ->check(finite_in(0.05, 3600.0))
      ->capture_default_str();
  cmd->add_option("--replan-when-left", o.replan_when_left,
                  "also replan as soon as a robot with a task has at most this many actions left "
                  "(event-based, Hönig et al. 2019); 0: periodic only")
      ->check(CLI::Range(0u, 1000u))
      ->capture_default_str();
  cmd->add_option("--window-steps", o.window_steps, "timesteps the planner plans per window")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--lookahead", o.lookahead,
                  "unfinished actions the commit cut keeps per robot (at least; and the most sent "
                  "to a robot at once in a lifelong run)")
      ->check(CLI::Range(0u, 1000u))
      ->capture_default_str();
  cmd->add_option("--plan-budget-s", o.budget_s,
                  "lock-step: sim seconds each planning call is charged (its window arrives "
                  "then; robots keep executing the cut meanwhile)")
      ->check(finite_in(0.0, 3600.0))
      ->capture_default_str();
  cmd->add_option("--distance-budget-mb", o.distance_budget_mb,
                  "memory for the planner's distance tables (one BFS over the map per goal cell; "
                  "past it the least recently used are recomputed): large maps with many goals "
                  "need more")
      ->check(finite_in(16.0, 1e6))
      ->capture_default_str();
  add_enum_option(cmd, "--heuristic", o.heuristic, kHeuristicNames,
                  "how the planner ranks moves: 'tables' (exact distances, a BFS table per goal "
                  "cell), 'paths' (a shortest path per robot, A* with landmarks: maps too large "
                  "for tables), 'auto' (tables when one per robot fits --distance-budget-mb)")
      ->capture_default_str();
  cmd->add_option("--window-lns-passes", o.lns_passes,
                  "rounds of replanning each robot's path in PIBT's window by space-time A* "
                  "against the others' (large neighbourhood search, planning/window_lns.hpp); 0: "
                  "PIBT's window as it is")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  cmd->add_option("--lorr-output", o.lorr_output,
                  "also write the run as a League of Robot Runners output JSON (PlanViz, LoRR "
                  "tools): actions discretised to 0.1 s ticks, as the file says");
  add_window_planner_options(cmd, o);
}

void check_plan_run_flags(const MonitorCliOptions& o) {
  std::string missing;
  for (const auto& [flag, value] :
       {std::pair<const char*, const std::string*>{"--map", &o.sim.world.map},
        {"--scen", &o.sim.world.scen},
        {"--plan", &o.plan}}) {
    if (value->empty()) missing += std::string(missing.empty() ? "" : ", ") + flag;
  }
  if (!missing.empty()) {
    throw std::invalid_argument(
        missing +
        " required: a run executes a plan on a map for a "
        "scenario's robots, or a lifelong problem (--lifelong PROBLEM.json, "
        "or --tasks random with --map and --agents)");
  }
}

monitor::Footprint robot_footprint(const WorldCliOptions& world) {
  const auto model = agent::load_robot_model(find_config_file("robots", world.robot));
  const auto f = monitor::footprint_for(model.radius_m, world.cell_m);
  if (!f) {
    throw std::invalid_argument(fmt::format(
        "--robot {} (radius {} m) is half a --cell-m {} m cell wide or more: robots on "
        "neighbouring cells would touch; use --cell-m {:.3g} or more, or a smaller robot",
        world.robot, model.radius_m, world.cell_m, 2.5 * model.radius_m));
  }
  return *f;
}

monitor::InstanceOptions instance_options(const WorldCliOptions& world, const std::string& plan,
                                          std::optional<grid::AxisOrder> axis,
                                          grid::PlanFormat format) {
  monitor::InstanceOptions io;
  io.map = world.map;
  io.scen = world.scen;
  io.plan = plan;
  io.agents = world.agents;
  io.read.format = format;
  io.read.axis = axis;
  io.initial_heading = world.heading;
  io.footprint = robot_footprint(world);
  return io;
}

void check_real_time_factor(const SimCliOptions& o) {
  if (o.clock == sim::ClockMode::kRealtime && o.real_time_factor > 0) {
    throw std::invalid_argument("--real-time-factor " + exact(o.real_time_factor) +
                                " paces a lock-step run, but --clock realtime already runs at "
                                "real time: drop --real-time-factor or use --clock lockstep");
  }
}

sim::SimHostOptions sim_host_options(const SimCliOptions& o) {
  check_real_time_factor(o);
  sim::SimHostOptions ho;
  ho.clock = o.clock;
  ho.state_rate_hz = o.state_rate_hz;
  ho.timeout_s = o.timeout_s;
  ho.real_time_factor = o.real_time_factor;
  ho.sim.cell_m = o.world.cell_m;
  ho.sim.system_capacity = o.system_capacity;
  ho.sim.threads = o.threads;
  ho.external_robots = o.external;
  ho.ros_pose_robots = o.ros_pose_robots;
  ho.ros_namespace = o.ros_namespace;
  ho.shard = o.shard;
  ho.shards = o.shards;
  return ho;
}

std::pair<uint32_t, uint32_t> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  uint32_t i = 0, n = 0;
  std::size_t used_i = 0, used_n = 0;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    i = static_cast<uint32_t>(std::stoul(text.substr(0, slash), &used_i));
    n = static_cast<uint32_t>(std::stoul(text.substr(slash + 1), &used_n));
  } catch (const std::exception&) {
    used_i = 0;
  }
  if (used_i == 0 || used_i != slash || used_n != text.size() - slash - 1 || n < 1 ||
      n > dds::kMaxShards || i >= n) {
    throw std::invalid_argument("--shard '" + text + "': give I/N, shard I (0 to N-1) of N (1 to " +
                                std::to_string(dds::kMaxShards) + "), e.g. --shard 0/2");
  }
  return {i, n};
}

namespace {
// A knob given to an execution that does not read it is refused, not silently ignored.
void refuse_unread(bool given, bool read, const char* flag, const char* takers) {
  if (given && !read) {
    throw std::invalid_argument(std::string(flag) + ": only --execution " + takers +
                                " reads it; drop it or pick one of those");
  }
}
}  // namespace

monitor::SwitchOptions switch_options(const MonitorCliOptions& o) {
  using Execution = MonitorCliOptions::Execution;
  const bool lookahead = o.execution == Execution::kSwitchableLookahead;
  monitor::SwitchOptions s;
  s.anticipate = o.execution == Execution::kSwitchableOpt || lookahead;
  const bool switching = o.execution != Execution::kAdg;
  const char* switchers = "switchable, switchable-opt or switchable-lookahead";
  refuse_unread(o.switch_commit_actions.has_value(), switching, "--switch-commit-actions",
                switchers);
  refuse_unread(o.switch_chain_locations.has_value(), switching, "--switch-chain-locations",
                switchers);
  s.commit_actions = o.switch_commit_actions.value_or(s.commit_actions);
  s.chain_locations = o.switch_chain_locations.value_or(s.chain_locations);
  refuse_unread(o.switch_margin_s.has_value(), s.anticipate, "--switch-margin-s",
                "switchable-opt or switchable-lookahead");
  refuse_unread(o.switch_horizon_actions.has_value(), s.anticipate, "--switch-horizon-actions",
                "switchable-opt or switchable-lookahead");
  refuse_unread(o.switch_lookahead_actions.has_value(), lookahead, "--switch-lookahead-actions",
                "switchable-lookahead");
  refuse_unread(o.switch_window_pairs.has_value(), lookahead, "--switch-window-pairs",
                "switchable-lookahead");
  s.horizon_actions = o.switch_horizon_actions.value_or(s.horizon_actions);
  s.window_pairs = o.switch_window_pairs.value_or(s.window_pairs);
  if (lookahead) {
    s.lookahead_actions = o.switch_lookahead_actions.value_or(monitor::kDefaultLookaheadActions);
    s.lookahead_margin_s = o.switch_margin_s.value_or(s.lookahead_margin_s);
  } else {
    s.margin_s = o.switch_margin_s.value_or(s.margin_s);
  }
  return s;
}

monitor::MonitorOptions monitor_options(const MonitorCliOptions& o) {
  const bool switching = o.execution != MonitorCliOptions::Execution::kAdg;
  if (o.resume && switching && o.resume_switches.empty()) {
    throw std::invalid_argument(
        "--resume with --execution " + std::string(execution_name(switch_options(o))) +
        ": the switches made are not in the robots' reports; give the stopped monitor's "
        "switches.csv (written as the run went into its --out folder) with --resume-switches");
  }
  if (!o.resume_switches.empty() && (!o.resume || !switching)) {
    throw std::invalid_argument(
        "--resume-switches " + o.resume_switches.string() +
        ": only with --resume and a switching --execution (the one of the run being resumed)");
  }
  monitor::MonitorOptions mo;
  mo.run.lockstep = o.sim.clock == sim::ClockMode::kLockstep;
  mo.run.window_cap = o.window_cap;
  mo.run.switchable = o.execution != MonitorCliOptions::Execution::kAdg;
  mo.run.switch_options = switch_options(o);
  mo.run.timeout_s = o.sim.timeout_s;
  mo.run.stall_timeout_s = o.stall_timeout_s;
  mo.run.max_sim_time_s = o.max_sim_time_s;
  mo.cell_m = o.sim.world.cell_m;
  mo.resume = o.resume;
  mo.run.require_sim_status = mo.run.lockstep || o.require_sim_status;
  mo.ros_plan_hz = o.ros_plan_hz;
  mo.ros_namespace = o.sim.ros_namespace;
  return mo;
}

namespace {
std::string id_list(const std::vector<uint32_t>& ids) {
  std::string out;
  for (const auto id : ids) out += (out.empty() ? "" : ",") + std::to_string(id);
  return out;
}
}  // namespace

std::vector<std::string> sim_argv(const std::string& exe, const SimCliOptions& o) {
  const auto& w = o.world;
  // The child logs at this process's level (`smart --log-level warn run` quiets both).
  std::vector<std::string> argv{
      exe, "--log-level",
      std::string(spdlog::level::to_string_view(spdlog::get_level()).data(),
                  spdlog::level::to_string_view(spdlog::get_level()).size()),
      "sim"};
  const auto dds = dds_argv(o.dds);
  argv.insert(argv.end(), dds.begin(), dds.end());
  argv.insert(argv.end(), {"--map",
                           w.map,
                           "--scen",
                           w.scen,
                           "--agents",
                           std::to_string(w.agents),
                           "--initial-heading",
                           enum_name(w.heading, kHeadingNames),
                           "--cell-m",
                           exact(w.cell_m),
                           "--robot",
                           w.robot,
                           "--clock",
                           enum_name(o.clock, kClockNames),
                           "--state-rate-hz",
                           exact(o.state_rate_hz),
                           "--timeout-s",
                           exact(o.timeout_s),
                           "--system-capacity",
                           std::to_string(o.system_capacity),
                           "--threads",
                           std::to_string(o.threads),
                           "--real-time-factor",
                           exact(o.real_time_factor)});
  if (!o.ros_pose_robots.empty())
    argv.insert(argv.end(), {"--ros-pose-robots", id_list(o.ros_pose_robots)});
  if (!o.ros_namespace.empty()) argv.insert(argv.end(), {"--ros-namespace", o.ros_namespace});
  if (!o.external.empty()) argv.insert(argv.end(), {"--external-robots", id_list(o.external)});
  if (o.shards > 1) {
    argv.insert(argv.end(), {"--shard", std::to_string(o.shard) + "/" + std::to_string(o.shards)});
  }
  for (const auto& [flag, v] : {std::pair{"--stall-probability", o.stall_probability},
                                {"--stall-s", o.stall_s},
                                {"--speed-sigma", o.speed_sigma},
                                {"--slip-sigma", o.slip_sigma},
                                {"--delay-probability", o.delay_probability},
                                {"--delay-rate-hz", o.delay_rate_hz},
                                {"--delay-min-s", o.delay_min_s},
                                {"--delay-max-s", o.delay_max_s},
                                {"--delay-mean-ratio", o.delay_mean_ratio},
                                {"--delay-std-ratio", o.delay_std_ratio}}) {
    if (v) argv.insert(argv.end(), {flag, exact(*v)});
  }
  if (o.seed) argv.insert(argv.end(), {"--seed", std::to_string(*o.seed)});
  return argv;
}

}  // namespace smart::tools
