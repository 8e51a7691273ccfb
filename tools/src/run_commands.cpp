// `smart sim`, `smart monitor` and `smart run`: executing a plan on a simulated fleet over DDS.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "smart/agent/robot_model.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/monitor/node.hpp"
#include "smart/monitor/results.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/sim/host.hpp"
#include "smart/tools/child_process.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/machine.hpp"

namespace smart::tools {

namespace {

struct SimOptions {
  DdsOptions dds;
  std::string map, scen, robot = "footbot", clock = "lockstep", heading = "east";
  std::size_t agents = 0;
  double cell_m = 1.0;
  double state_rate_hz = 2.0;
  double timeout_s = 30.0;
  int system_capacity = 0, threads = 2;
  std::vector<uint32_t> external;
  std::vector<uint32_t> ros_pose_robots;
};

struct MonitorCliOptions {
  DdsOptions dds;
  std::string map, scen, plan, axis, format = "auto", heading = "east", clock = "lockstep";
  std::string robot = "footbot";
  std::string out;
  std::size_t agents = 0;
  double cell_m = 1.0;
  uint32_t window_cap = 32;
  double timeout_s = 30.0, stall_timeout_s = 300.0, max_sim_time_s = 0;
  double state_rate_hz = 2.0;
  int system_capacity = 0, threads = 2;
  std::vector<uint32_t> ros_pose_robots;  // `smart run`: passed to the sim
  bool resume = false;                    // `smart monitor` only
  bool progress = true;
};

void add_world_options(CLI::App* cmd, std::string& map, std::string& scen, std::size_t& agents,
                       std::string& heading, double& cell_m) {
  cmd->add_option("--map", map, "MovingAI .map file")->required();
  cmd->add_option("--scen", scen, "MovingAI .scen file (robot starts)")->required();
  cmd->add_option("--agents", agents, "number of robots (first N of the scenario / plan)");
  cmd->add_option("--initial-heading", heading, "heading every robot starts with")
      ->check(CLI::IsMember({"east", "north", "west", "south"}))
      ->capture_default_str();
  cmd->add_option("--cell-m", cell_m, "grid cell size in metres")
      ->check(CLI::Range(0.05, 100.0))
      ->capture_default_str();
}

int run_sim(const SimOptions& o) {
  const auto grid = grid::parse_map(grid::read_text_file(o.map, "map"), o.map);
  const auto scen =
      grid::parse_scen(grid::read_text_file(o.scen, "scenario"), o.scen, o.agents);
  grid::throw_if_any(grid::check_scen_against_map(scen, grid));
  const auto model = agent::load_robot_model(find_config_file("robots", o.robot));
  const auto profile = dds::find_qos_profile(o.dds.qos);
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile));
  dds::Participant participant(domain);
  std::vector<grid::Cell> starts;
  for (const auto& a : scen.agents) starts.push_back(a.start);
  sim::SimHostOptions ho;
  ho.clock = o.clock == "realtime" ? sim::ClockMode::kRealtime : sim::ClockMode::kLockstep;
  ho.state_rate_hz = o.state_rate_hz;
  ho.timeout_s = o.timeout_s;
  ho.sim.cell_m = o.cell_m;
  ho.sim.system_capacity = o.system_capacity;
  ho.sim.threads = o.threads;
  ho.external_robots = o.external;
  ho.ros_pose_robots = o.ros_pose_robots;
  sim::SimHost host(
      participant, profile, grid, model,
      sim::start_poses(grid, o.cell_m, starts, grid::yaw_rad(grid::parse_heading(o.heading))),
      ho);
  spdlog::info("sim: {} robots on {} ({}x{}), {} clock, domain {}", starts.size(), o.map,
               grid.width(), grid.height(), o.clock, o.dds.domain);
  const auto r = host.run(g_stop_requested);
  std::cout << nlohmann::json{{"ok", r.ok},
                              {"error", r.error},
                              {"stopped_by_monitor", r.stopped_by_monitor},
                              {"ticks", r.ticks},
                              {"sim_time_s", r.sim_time_s},
                              {"wall_time_s", r.wall_time_s},
                              {"sim_speed", r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0},
                              {"robot_contacts", r.contacts.robot_robot_events},
                              {"wall_contacts", r.contacts.robot_wall_events},
                              {"mean_awake_robots", r.mean_awake_robots},
                              {"mean_active_systems", r.mean_active_systems},
                              {"peak_rss_mb", peak_rss_mb()}}
                   .dump()
            << std::endl;
  if (!r.ok) spdlog::error("sim: {}", r.error);
  return r.ok ? 0 : 1;
}

void print_progress(const monitor::MonitorResult& r, std::size_t done, bool final) {
  const double frac = r.total_actions ? double(r.finished_actions) / double(r.total_actions) : 1;
  const int width = 30;
  const int filled = static_cast<int>(frac * width);
  std::fprintf(stderr, "\r[%.*s%.*s] %zu/%zu actions, %zu/%zu robots done, sim %.1f s, %.1fx  ",
               filled, "##############################", width - filled,
               "                              ", r.finished_actions, r.total_actions, done,
               r.robots.size(), r.sim_time_s, r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0);
  if (final) std::fprintf(stderr, "\n");
}

monitor::Instance load(const MonitorCliOptions& o) {
  return monitor::load_instance(
      instance_options(o.map, o.scen, o.plan, o.agents, o.format, o.axis, o.heading));
}

// Runs the monitor; with `spawn_sim` also a `smart sim` child process with matching options.
int run_monitor(const MonitorCliOptions& o, bool spawn_sim) {
  monitor::Instance in;
  try {
    in = load(o);
  } catch (const grid::InputError& e) {
    std::cerr << e.what() << "\n" << e.problems().size() << " problem(s) found\n";
    return 2;
  }
  for (const auto r : o.ros_pose_robots) {
    if (r >= in.plan.paths.size()) {
      std::cerr << "--ros-pose-robots: robot " << r << " but the run has " << in.plan.paths.size()
                << " robots (ids 0.." << in.plan.paths.size() - 1 << ")\n";
      return 2;
    }
  }
  const auto robot_file = find_config_file("robots", o.robot);
  (void)agent::load_robot_model(robot_file);  // fail early on a bad model
  const auto profile = dds::find_qos_profile(o.dds.qos);
  std::optional<ChildProcess> sim;
  if (spawn_sim) {
    std::vector<std::string> argv{self_executable().string(),
                                  "sim",
                                  "--map",
                                  o.map,
                                  "--scen",
                                  o.scen,
                                  "--agents",
                                  std::to_string(in.plan.paths.size()),
                                  "--initial-heading",
                                  o.heading,
                                  "--cell-m",
                                  std::to_string(o.cell_m),
                                  "--robot",
                                  robot_file,
                                  "--clock",
                                  o.clock,
                                  "--domain",
                                  std::to_string(o.dds.domain),
                                  "--qos",
                                  o.dds.qos,
                                  "--network",
                                  o.dds.network,
                                  "--state-rate-hz",
                                  std::to_string(o.state_rate_hz),
                                  "--timeout-s",
                                  std::to_string(o.timeout_s),
                                  "--system-capacity",
                                  std::to_string(o.system_capacity),
                                  "--threads",
                                  std::to_string(o.threads)};
    if (!o.ros_pose_robots.empty()) {
      std::string ids;
      for (const auto r : o.ros_pose_robots) ids += (ids.empty() ? "" : ",") + std::to_string(r);
      argv.insert(argv.end(), {"--ros-pose-robots", ids});
    }
    sim.emplace(argv, "/dev/null");
  }
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile));
  dds::Participant participant(domain);
  monitor::MonitorOptions mo;
  mo.run.lockstep = o.clock == "lockstep";
  mo.run.window_cap = o.window_cap;
  mo.cell_m = o.cell_m;
  mo.run.timeout_s = o.timeout_s;
  mo.run.stall_timeout_s = o.stall_timeout_s;
  mo.run.max_sim_time_s = o.max_sim_time_s;
  mo.resume = o.resume;
  std::optional<monitor::StatesCsvWriter> states;
  if (!o.out.empty()) {
    states.emplace(o.out);
    mo.on_state = [&states](const monitor::StateRow& row) { states->add(row); };
  }
  if (sim) {
    mo.host_check = [&sim]() -> std::string {
      if (sim->running()) return {};
      const int code = sim->wait(std::chrono::milliseconds(0)).value_or(-1);
      return "the `smart sim` process this run started " +
             (code > 128 ? "was killed by signal " + std::to_string(code - 128)
                         : "exited with code " + std::to_string(code)) +
             " before the run ended; its messages are above";
    };
  }
  monitor::MonitorNode node(participant, profile, in, mo);
  const bool tty = o.progress && isatty(STDERR_FILENO);
  monitor::ProgressCallback cb;
  if (tty)
    cb = [](const monitor::MonitorResult& r, std::size_t done) { print_progress(r, done, false); };
  auto result = node.run(g_stop_requested, cb);
  if (tty) print_progress(result, result.success() ? result.robots.size() : 0, true);
  if (sim) {
    const auto rc = sim->wait(std::chrono::seconds(5));
    if (!rc) sim->terminate();
  }
  monitor::RunInfo info;
  info.map = o.map;
  info.scen = o.scen;
  info.plan = o.plan;
  info.robot = robot_file;
  info.qos = o.dds.qos;
  info.clock = o.clock;
  info.cell_m = o.cell_m;
  info.monitor_peak_rss_mb = peak_rss_mb();
  info.machine = machine_description();
  if (!o.out.empty()) monitor::write_results(o.out, in, result, info);
  if (!result.success()) spdlog::error("run failed: {}", result.error);
  std::cout << monitor::summary_json(in, result, info).dump(2) << std::endl;
  return result.success() ? 0 : 1;
}

void add_monitor_options(CLI::App* cmd, MonitorCliOptions& o) {
  add_dds_options(cmd, o.dds);
  add_world_options(cmd, o.map, o.scen, o.agents, o.heading, o.cell_m);
  cmd->add_option("--plan", o.plan, "plan file (SMART/MAPF-LNS2, LaCAM/PIBT, YAML)")->required();
  cmd->add_option("--axis", o.axis, "xy (x = column) or rowcol; required for SMART path files")
      ->check(CLI::IsMember({"xy", "rowcol"}));
  cmd->add_option("--format", o.format, "plan format")
      ->check(CLI::IsMember({"auto", "smart", "lacam", "yaml"}))
      ->capture_default_str();
  cmd->add_option("--clock", o.clock, "lockstep (bit-identical) or realtime")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->capture_default_str();
  cmd->add_option("--robot", o.robot, "robot model: name in config/robots or a YAML file")
      ->capture_default_str();
  cmd->add_option("--out", o.out, "folder for summary.json, stats.csv, states.csv, robots.csv");
  cmd->add_option("--window-cap", o.window_cap, "most actions sent to a robot at once")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  cmd->add_option("--timeout-s", o.timeout_s, "wall seconds without the sim before failing")
      ->capture_default_str();
  cmd->add_option("--stall-timeout-s", o.stall_timeout_s,
                  "sim seconds without a finished action before failing")
      ->capture_default_str();
  cmd->add_option("--max-sim-time-s", o.max_sim_time_s, "fail past this sim time (0: no limit)");
  cmd->add_option("--state-rate-hz", o.state_rate_hz, "robot state samples per sim second")
      ->capture_default_str();
  cmd->add_flag("!--no-progress", o.progress, "no progress bar");
}

}  // namespace

void register_run_commands(CLI::App& app, int& exit_code) {
  auto so = std::make_shared<SimOptions>();
  auto* sim = app.add_subcommand("sim",
                                 "Simulated fleet: Simbody world + one agent per robot, "
                                 "driven over DDS by `smart monitor`");
  add_dds_options(sim, so->dds);
  add_world_options(sim, so->map, so->scen, so->agents, so->heading, so->cell_m);
  sim->add_option("--robot", so->robot, "robot model: name in config/robots or a YAML file")
      ->capture_default_str();
  sim->add_option("--clock", so->clock, "lockstep or realtime")
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->capture_default_str();
  sim->add_option("--state-rate-hz", so->state_rate_hz)->capture_default_str();
  sim->add_option("--timeout-s", so->timeout_s, "lockstep: wall seconds to wait for the monitor")
      ->capture_default_str();
  sim->add_option("--system-capacity", so->system_capacity,
                  "robot bodies per Simbody system (0: automatic)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  sim->add_option("--threads", so->threads)->check(CLI::Range(1, 64))->capture_default_str();
  sim->add_option("--ros-pose-robots", so->ros_pose_robots,
                  "robots that also get a ROS 2 PoseStamped topic rt/robot_<id>/pose")
      ->delimiter(',');
  sim->add_option("--external-robots", so->external,
                  "robots executed by other hosts (mixed runs), shown at their published poses")
      ->delimiter(',');
  sim->callback([&exit_code, so] {
    install_stop_handlers();
    exit_code = run_sim(*so);
  });

  auto mo = std::make_shared<MonitorCliOptions>();
  auto* mon = app.add_subcommand("monitor",
                                 "Execute a plan: publish action windows, track "
                                 "progress, detect completion/deadlock, write results");
  add_monitor_options(mon, *mo);
  mon->add_flag("--resume", mo->resume,
                "take over a run whose monitor died: its run id and finished actions come from "
                "the sim hosts' progress (same plan, --agents and --initial-heading)");
  mon->callback([&exit_code, mo] {
    install_stop_handlers();
    exit_code = run_monitor(*mo, false);
  });

  auto ro = std::make_shared<MonitorCliOptions>();
  auto* run = app.add_subcommand("run",
                                 "Execute a plan on a simulated fleet: `smart monitor` "
                                 "here plus a `smart sim` process, over DDS");
  add_monitor_options(run, *ro);
  run->add_option("--system-capacity", ro->system_capacity,
                  "robot bodies per Simbody system (0: automatic)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  run->add_option("--threads", ro->threads, "sim threads")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  run->add_option("--ros-pose-robots", ro->ros_pose_robots,
                  "robots that also get a ROS 2 PoseStamped topic rt/robot_<id>/pose")
      ->delimiter(',');
  run->callback([&exit_code, ro] {
    install_stop_handlers();
    exit_code = run_monitor(*ro, true);
  });
}

}  // namespace smart::tools
