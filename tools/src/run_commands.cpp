// `smart sim`, `smart monitor` and `smart run`: executing a plan on a simulated fleet over DDS.
// Options are bound to library structs in run_options.hpp; errors reach the one error printer
// in main.cpp (exit codes in cli_common.hpp).
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <tuple>
#include <variant>

#include "run_support.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/common/child_process.hpp"
#include "smart/dds/topics.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/results.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/monitor/sim_reports.hpp"
#include "smart/record/live_recording.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/machine.hpp"
#include "smart/tools/record_run.hpp"
#include "smart/tools/run_key.hpp"
#include "smart/tools/run_options.hpp"
#include "smart/wire/lockstep.hpp"
#include "temp_dir.hpp"

namespace smart::tools {

namespace {

// The JSON line `smart sim` prints last; others read its keys through results_format.hpp.
nlohmann::json sim_report(const sim::SimHostResult& r) {
  using namespace results::sim_report_key;
  return {{kOk, r.ok},
          {kError, r.error},
          {"stopped_by_monitor", r.stopped_by_monitor},
          {"ticks", r.ticks},
          {kSimTimeS, r.sim_time_s},
          {"wall_time_s", r.wall_time_s},
          {"sim_speed", r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0},
          {kRobotContacts, r.contacts.robot_robot_events},
          {kWallContacts, r.contacts.robot_wall_events},
          {"mean_awake_robots", r.mean_awake_robots},
          {"mean_active_systems", r.mean_active_systems},
          {kHandoversIn, r.handovers_in},
          {"rejected_samples", r.rejected_samples},
          {"peak_rss_mb", peak_rss_mb()}};
}

// The world a sim host executes: a map and a scenario's starts, or a lifelong problem's.
struct SimWorld {
  std::string name;
  grid::Grid grid;
  std::vector<grid::Cell> starts;
};

SimWorld sim_world(SimCliOptions& o) {
  auto& w = o.world;
  if (o.source.active()) {
    auto p = load_lifelong_problem(o);
    apply_lorr_delays(p, o);
    return {p.source, std::move(p.grid), std::move(p.starts)};
  }
  if (w.map.empty() || w.scen.empty()) {
    throw std::invalid_argument(
        "--map and --scen required: a sim host executes a scenario's robots on a map, or a "
        "lifelong problem's (--lifelong PROBLEM.json, or --tasks random with --map and --agents)");
  }
  SimWorld out{w.map, grid::parse_map(grid::read_text_file(w.map, "map"), w.map), {}};
  const auto scen = grid::parse_scen(grid::read_text_file(w.scen, "scenario"), w.scen, w.agents);
  grid::throw_if_any(grid::check_scen_against_map(scen, out.grid));
  for (const auto& a : scen.agents) out.starts.push_back(a.start);
  return out;
}

int run_sim(SimCliOptions o) {
  const auto world = sim_world(o);
  const auto& w = o.world;
  const auto model = run_robot_model(o);
  const auto profile = run_qos_profile(o.dds);
  if (const auto warning =
          link_model_warning(o.clock == sim::ClockMode::kLockstep, o.dds, profile)) {
    spdlog::warn("sim: {}", *warning);
  }
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile, "sim"));
  dds::Participant participant(domain, o.dds.run);
  prove_member(participant, o.dds, "sim");
  sim::SimHost host(participant, profile, world.grid, model,
                    sim::start_poses(world.grid, w.cell_m, world.starts, grid::yaw_rad(w.heading)),
                    sim_host_options(o));
  spdlog::info("sim: {} robots on {} ({}x{}), {} clock, domain {}", world.starts.size(), world.name,
               world.grid.width(), world.grid.height(), enum_name(o.clock, kClockNames),
               o.dds.domain);
  const auto r = host.run(g_stop_requested);
  std::cout << sim_report(r).dump() << std::endl;
  if (!r.ok) spdlog::error("sim: {}", r.error);
  return r.ok ? kExitSuccess : kExitRunFailed;
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

void check_ros_pose_robots(const std::vector<uint32_t>& ids, std::size_t robots) {
  for (const auto r : ids) {
    if (r >= robots) {
      throw std::invalid_argument("--ros-pose-robots: robot " + std::to_string(r) +
                                  " but the run has " + std::to_string(robots) +
                                  " robots (ids 0.." + std::to_string(robots - 1) + ")");
    }
  }
}

}  // namespace

// A sim child's report: sim-<shard>.json in the results folder, or a file of this process's
// own in the temp folder (removed once read): the verdict is checked against it either way.
std::filesystem::path sim_report_file(const MonitorCliOptions& o, uint32_t shard) {
  if (o.out.empty()) {
    return std::filesystem::temp_directory_path() /
           ("smart-" + std::to_string(getpid()) + "-" + results::sim_report_name(shard));
  }
  return std::filesystem::path(o.out) / results::sim_report_name(shard);
}

// `smart run`'s sim children (one per shard), with the monitor's own options and the plan's
// robot count.
// Their reports (JSON) go to sim-<shard>.json in the results folder, when there is one.
std::vector<common::ChildProcess> spawn_sims(const MonitorCliOptions& o, std::size_t robots,
                                             const std::string& robot) {
  std::vector<common::ChildProcess> out;
  if (!o.out.empty()) std::filesystem::create_directories(o.out);
  for (uint32_t s = 0; s < o.sim.shards; ++s) {
    SimCliOptions child = o.sim;
    child.world.agents = robots;
    child.world.robot = robot;
    child.shard = s;
    // N shards started here share this machine's cores: automatic threads divide them (more
    // threads than cores stall at the sub-step barriers, sim::kMinRobotsPerThread).
    if (child.threads == 0 && o.sim.shards > 1) {
      child.threads = static_cast<int>(
          std::max<uint32_t>(1, std::thread::hardware_concurrency() / o.sim.shards));
    }
    out.emplace_back(sim_argv(common::self_executable().string(), child), sim_report_file(o, s));
  }
  return out;
}

// What each sim child reported, or why its report cannot be read.
std::vector<monitor::SimWord> sim_words(const MonitorCliOptions& o) {
  std::vector<monitor::SimWord> out;
  for (uint32_t s = 0; s < o.sim.shards; ++s) {
    const auto file = sim_report_file(o, s);
    try {
      out.emplace_back(
          results::parse_sim_report(grid::read_text_file(file, "sim report"), file.string()));
    } catch (const std::exception& e) {
      out.emplace_back(std::string(e.what()));
    }
    if (o.out.empty()) std::filesystem::remove(file);
  }
  return out;
}

// Robots handed between shards, from the shards' reports (nothing when one is missing).
std::optional<uint64_t> sim_handovers(const std::vector<monitor::SimWord>& words) {
  uint64_t sum = 0;
  for (const auto& w : words) {
    const auto* report = std::get_if<results::SimReport>(&w);
    if (!report) return std::nullopt;
    sum += report->handovers_in;
  }
  return sum;
}

std::function<std::string()> watch(std::vector<common::ChildProcess>& sims) {
  return [&sims]() -> std::string {
    for (std::size_t s = 0; s < sims.size(); ++s) {
      if (sims[s].running()) continue;
      const int code = sims[s].wait(std::chrono::milliseconds(0)).value_or(-1);
      return "the `smart sim` process " +
             (sims.size() > 1 ? "of shard " + std::to_string(s) + " " : std::string()) +
             "this run started " +
             (code > 128 ? "was killed by signal " + std::to_string(code - 128)
                         : "exited with code " + std::to_string(code)) +
             " before the run ended; its messages are above";
    }
    return {};
  };
}

// Input files as absolute paths: summary.json names them for whoever reads it later, from
// another folder (`smart serve --open` finds the map there).
std::string absolute_path(const std::string& p) {
  return p.empty() ? p : std::filesystem::absolute(p).lexically_normal().string();
}

monitor::RunInfo run_info(const MonitorCliOptions& o, const std::string& robot_file) {
  monitor::RunInfo info;
  info.map = absolute_path(o.sim.world.map);
  info.scen = absolute_path(o.sim.world.scen);
  info.plan = absolute_path(o.plan);
  info.robot = robot_file;
  const auto m = run_robot_model(o.sim);
  info.uncertainty = agent::to_json(m.uncertainty);
  info.link = wire::to_json(run_qos_profile(o.sim.dds).link);
  info.seed = m.uncertainty.seed;
  info.limits = monitor::MotionLimits{m.max_speed_mps, m.max_accel_mps2, m.max_decel_mps2,
                                      m.max_turn_rate_radps, m.max_angular_accel_radps2};
  info.robot_model = m.name;
  if (o.execution != MonitorCliOptions::Execution::kAdg) info.switching = switch_options(o);
  info.qos = o.sim.dds.qos;
  info.clock = enum_name(o.sim.clock, kClockNames);
  info.run = o.sim.dds.run;
  info.cell_m = o.sim.world.cell_m;
  info.sim_hosts = o.sim.shards;
  info.monitor_peak_rss_mb = peak_rss_mb();
  info.machine = machine_description();
  return info;
}

// `smart run` owns its run's key (issue 25: the run's processes hear only each other): a
// --run-key file is made when missing; without one, a private key for the processes it starts,
// unless robots run elsewhere (a mixed run: its agents need the file, so the user names it).
std::unique_ptr<PrivateRunKey> own_run_key(SimCliOptions& o) {
  if (!o.dds.run_key.empty()) {
    if (!std::filesystem::exists(o.dds.run_key)) make_run_key(o.dds.run_key);
    return nullptr;
  }
  if (!o.external.empty()) {
    spdlog::warn(
        "a mixed run without --run-key: any participant that learns the run's partition can "
        "speak for a robot or the monitor; give `smart run` and every `smart agent` the same "
        "--run-key FILE (README, \"Running safely\")");
    return nullptr;
  }
  auto key = std::make_unique<PrivateRunKey>();
  o.dds.run_key = key->file().string();
  return key;
}

namespace {

// What the monitor's callbacks feed while the run goes: the live results files and, with --mcap,
// the recording made beside the run from the same rows (record/live_recording.hpp).
struct ResultsTaps {
  std::optional<monitor::StatesCsvWriter> states;
  std::optional<monitor::ProgressCsvWriter> progress;
  std::optional<monitor::SwitchesCsvWriter> switches;  // a switchable run's, as they are made
  std::optional<record::LiveRecording> recording;
};

void tap_results(const MonitorCliOptions& o, const monitor::Instance& in, double robot_radius_m,
                 monitor::MonitorOptions& mo, ResultsTaps& taps) {
  if (o.out.empty()) return;
  auto& recording = taps.recording;
  if (!o.mcap.empty()) {
    if (mo.run.run_id == 0) mo.run.run_id = monitor::wall_clock_run_id();  // in the messages
    recording.emplace(record::LiveRecordingSetup{o.mcap, run_recorder_options(o), mo.run.run_id,
                                                 &in, o.sim.world.cell_m, robot_radius_m});
    mo.on_action_finished = [&recording](uint32_t robot, uint32_t seq, double t_s) {
      recording->action_finished(robot, seq, t_s);
    };
  }
  taps.states.emplace(o.out);
  // The row formatted once, for the file and the recording.
  mo.on_state = [&states = taps.states, &recording,
                 line = std::string()](const monitor::StateRow& row) mutable {
    line.clear();
    results::append_row(line, row);
    states->add_line(line);
    if (recording) recording->state(line);
  };
  taps.progress.emplace(o.out);
  mo.on_finished = [&progress = taps.progress](const results::ProgressRow& row) {
    progress->add(row);
  };
  if (mo.run.switchable) {
    taps.switches.emplace(o.out);
    for (const auto& s : mo.run.resume_switches) {
      taps.switches->add(monitor::switch_row(in.grid, &in.actions, s));
    }
    mo.on_switch = [&taps, &in](const monitor::PassingSwitch& s) {
      taps.switches->add(monitor::switch_row(in.grid, &in.actions, s));
    };
  }
  mo.on_robots_finished = [dir = o.out](const std::vector<uint32_t>& finished) {
    monitor::write_finished_csv(dir, finished);
  };
}

// --resume-switches FILE: the stopped monitor's switches, each checked as it is replayed onto
// this plan's passing orders (a row that swaps no pair there is named: another run's file).
std::vector<monitor::PassingSwitch> resume_switches(const std::filesystem::path& file,
                                                    const monitor::Instance& in) {
  const auto where = "--resume-switches " + file.string();
  std::vector<monitor::PassingSwitch> out;
  try {
    out = monitor::passing_switches(
        in.grid, in.actions,
        results::parse_switches_csv(grid::read_text_file(file, "switches file")));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
  auto orders = monitor::passing_orders(in.actions, in.grid, in.adg.footprint);
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (monitor::apply_switches(orders, {out[k]}) == 0) continue;
    throw std::invalid_argument(
        where + " line " + std::to_string(k + 2) + ": robot " + std::to_string(out[k].first) +
        " passing robot " + std::to_string(out[k].second) +
        " there matches no pair of this plan's passing orders (with the rows before it "
        "replayed); give the switches.csv of the run being resumed, with its plan, --agents and "
        "--execution");
  }
  return out;
}

// A sharded sim hands robots over between hosts in lock-step; a link model's delays would
// reorder those handovers.
void check_shards(const SimCliOptions& o, const dds::QosProfile& profile) {
  if (o.shards <= 1) return;
  if (o.clock == sim::ClockMode::kLockstep && !profile.link.to_host.active() &&
      !profile.link.to_monitor.active()) {
    return;
  }
  throw std::invalid_argument(
      "--sim-hosts " + std::to_string(o.shards) +
      ": a sharded sim runs in lock-step without a link model; use --clock lockstep and "
      "--qos lan or wifi, or --sim-hosts 1");
}

// monitor/adg.hpp: half-cell locations would let a robot on an edge midpoint come within half a
// cell of one on the next cell's centre.
void log_cell_footprint(const agent::RobotModel& model, double cell_m) {
  spdlog::info(
      "robots of radius {} m ({}) are wider than a quarter of a {} m cell: a robot crossing an "
      "edge holds both cells, so following robots keep a cell apart",
      model.radius_m, model.name, cell_m);
}

// The run's info once it ended: CPU (the recording's thread is not the monitor's work; the
// reaped sim hosts when this process spawned them) and, with sims, their reports merged into
// `result`.
monitor::RunInfo finished_run_info(const MonitorCliOptions& o, const std::string& robot_file,
                                   ResultsTaps& taps, bool own_sims,
                                   monitor::MonitorResult& result) {
  auto info = run_info(o, robot_file);
  auto& recording = taps.recording;
  if (recording) {
    recording->stop();
    spdlog::info("recording: {:.1f} s of CPU beside the run", recording->cpu_s());
  }
  info.monitor_cpu_s = common::cpu_seconds_self() - (recording ? recording->cpu_s() : 0.0);
  if (own_sims) {
    info.sim_cpu_s = common::cpu_seconds_children();
    const auto words = sim_words(o);
    if (!o.out.empty()) info.sim_handovers = sim_handovers(words);
    monitor::apply_sim_reports(result, words);
  }
  return info;
}

// Results written, the summary printed first and the verdict and warnings last (on a terminal
// the JSON buried them); the exit code.
int report_run(const MonitorCliOptions& o, const monitor::Instance& in,
               const monitor::MonitorResult& result, const monitor::RunInfo& info,
               ResultsTaps& taps) {
  if (!o.out.empty()) monitor::write_results(o.out, in, result, info);
  if (!o.stats.empty()) monitor::append_stats(o.stats, in, result, info);
  std::cout << monitor::summary_json(in, result, info).dump(2) << std::endl;
  if (taps.recording) print_recording(taps.recording->finish(o.out), o.mcap);
  if (!result.success()) spdlog::error("run failed: {}", result.error);
  if (const auto& c = result.first_pose_contact) {
    spdlog::warn(
        "the robots' reported poses show {} contact(s), first robots {} and {} at {:.1f} s "
        "({:.3f} m overlap): check the robots' sizes, pose calibration and the plan's spacing",
        result.pose_contacts, c->a, c->b, c->t_s, -c->gap_m);
  }
  return result.success() ? kExitSuccess : kExitRunFailed;
}

// Runs the monitor; with `spawn_sim_child` also `smart sim` child processes with matching options.
int run_monitor(MonitorCliOptions o, bool spawn_sim_child) {
  check_plan_run_flags(o);
  // A run this process starts whole gets a run (partition) of its own unless one was named.
  if (spawn_sim_child && !o.sim.dds.run_given) o.sim.dds.run = fresh_run_name();
  const auto in = monitor::load_instance(instance_options(o.sim.world, o.plan, o.axis, o.format));
  check_ros_pose_robots(o.sim.ros_pose_robots, in.plan.paths.size());
  const auto robot_file = find_config_file("robots", o.sim.world.robot);
  const auto model = agent::load_robot_model(robot_file);  // fail early on a bad model
  const auto profile = run_qos_profile(o.sim.dds);
  check_real_time_factor(o.sim);
  check_shards(o.sim, profile);
  auto mo = monitor_options(o);
  // Read before the results' taps open a new switches.csv, which may be this very file.
  if (!o.resume_switches.empty()) mo.run.resume_switches = resume_switches(o.resume_switches, in);
  std::unique_ptr<PrivateRunKey> private_key;
  if (spawn_sim_child) private_key = own_run_key(o.sim);
  std::vector<common::ChildProcess> sims;
  if (spawn_sim_child) sims = spawn_sims(o, in.plan.paths.size(), robot_file);
  dds::Domain domain(o.sim.dds.domain, domain_config(o.sim.dds, profile, "monitor"));
  dds::Participant participant(domain, o.sim.dds.run);
  prove_member(participant, o.sim.dds, "monitor");
  mo.robot_radius_m = model.radius_m;
  mo.run.robot_radius_m = model.radius_m;  // real time: reported poses watched for contacts
  if (in.adg.footprint == monitor::Footprint::kCells) log_cell_footprint(model, o.sim.world.cell_m);
  mo.run.require_sim_status = mo.run.require_sim_status || spawn_sim_child;
  // Its own sim host's exit is seen at once (host_check); a slow start on a loaded machine is not
  // a lost host.
  if (spawn_sim_child) mo.run.join_timeout_s = wire::kJoinTimeouts * mo.run.timeout_s;
  ResultsTaps taps;  // outlives the node, whose callbacks write to it
  tap_results(o, in, model.radius_m, mo, taps);
  if (!sims.empty()) mo.host_check = watch(sims);
  monitor::MonitorNode node(participant, profile, in, mo);
  const bool tty = o.progress && isatty(STDERR_FILENO);
  monitor::ProgressCallback cb;
  if (tty) cb = [](const monitor::MonitorResult& r, std::size_t d) { print_progress(r, d, false); };
  auto result = node.run(g_stop_requested, cb);
  if (tty) print_progress(result, result.success() ? result.robots.size() : 0, true);
  for (auto& sim : sims) {
    if (!sim.wait(std::chrono::seconds(5))) sim.terminate();
  }
  const auto info = finished_run_info(o, robot_file, taps, !sims.empty(), result);
  return report_run(o, in, result, info, taps);
}

// `smart monitor`: the monitor alone, against hosts started elsewhere (or taking a run over).
void register_monitor_command(CLI::App& app, int& exit_code) {
  auto mo = std::make_shared<MonitorCliOptions>();
  auto* mon = app.add_subcommand("monitor",
                                 "Execute a plan: publish action windows, track "
                                 "progress, detect completion/deadlock, write results");
  add_monitor_options(mon, *mo);
  add_task_source_options(mon, mo->sim.source);
  add_lifelong_options(mon, mo->lifelong);
  mon->add_flag("--resume", mo->resume,
                "take over a run whose monitor died: its run id and finished actions come from "
                "the sim hosts' progress (same plan, --agents and --initial-heading)");
  mon->add_option("--resume-switches", mo->resume_switches,
                  "with --resume of a switchable run: the stopped monitor's switches.csv (its "
                  "--out folder's, written as the run went), to rebuild its passing orders")
      ->type_name("FILE");
  mon->add_flag("--require-sim-status", mo->require_sim_status,
                "real time: succeed only with a `smart sim` host's final status (its collision "
                "counts); lock-step runs always need it");
  group_options(mon);
  mon->callback([&exit_code, mo] {
    install_stop_handlers();
    exit_code = mo->sim.source.active() ? run_lifelong(*mo, false) : run_monitor(*mo, false);
  });
}

}  // namespace

void register_run_commands(CLI::App& app, int& exit_code) {
  auto so = std::make_shared<SimCliOptions>();
  auto* sim = app.add_subcommand("sim",
                                 "Simulated fleet: Simbody world + one agent per robot, "
                                 "driven over DDS by `smart monitor`");
  add_common_run_options(sim, *so);
  add_sim_host_options(sim, *so);
  add_task_source_options(sim, so->source);
  sim->add_option("--external-robots", so->external,
                  "robots executed by other hosts (mixed runs), shown at their published poses")
      ->delimiter(',');
  sim->add_option_function<std::string>(
         "--shard",
         [so](const std::string& v) {
           try {
             std::tie(so->shard, so->shards) = parse_shard(v);
           } catch (const std::invalid_argument& e) {
             throw CLI::ValidationError(e.what());
           }
         },
         "host shard I of N of a sharded sim (map strips; every shard with the same world "
         "options); `smart run --sim-hosts N` starts them all")
      ->type_name("I/N");
  group_options(sim);
  sim->callback([&exit_code, so] {
    install_stop_handlers();
    exit_code = run_sim(*so);
  });

  register_monitor_command(app, exit_code);

  auto ro = std::make_shared<MonitorCliOptions>();
  auto* run = app.add_subcommand("run",
                                 "Execute a plan on a simulated fleet: `smart monitor` "
                                 "here plus a `smart sim` process, over DDS");
  add_monitor_options(run, *ro);
  add_task_source_options(run, ro->sim.source);
  add_lifelong_options(run, ro->lifelong);
  add_sim_host_options(run, ro->sim);
  run->add_option("--sim-hosts", ro->sim.shards,
                  "start the simulated fleet as this many `smart sim --shard I/N` processes "
                  "(map strips, lock-step; docs/simulation.md \"Sharded sim\")")
      ->check(CLI::Range(1u, dds::kMaxShards))
      ->capture_default_str();
  auto mcap = std::make_shared<std::string>();
  run->add_option("--mcap", *mcap,
                  "also write the run as an MCAP file (ROS 2 view and the run's topics, for "
                  "Foxglove and `ros2 bag`; docs/ros2.md), recorded while the run goes (a "
                  "lifelong run: from its results once it ended)");
  group_options(run);
  run->callback([&exit_code, ro, mcap] {
    install_stop_handlers();
    // The recording ends with the results (attached): without --out they go to a scratch folder.
    std::optional<TempDir> scratch;
    if (!mcap->empty() && ro->out.empty()) ro->out = scratch.emplace("smart-run").path().string();
    // A plan's run records while it goes; a lifelong run from its results once it ended.
    const bool live = !mcap->empty() && !ro->sim.source.active();
    if (live) ro->mcap = *mcap;
    exit_code = ro->sim.source.active() ? run_lifelong(*ro, true) : run_monitor(*ro, true);
    if (!mcap->empty() && !live && exit_code != ExitCode::kExitSystem) {
      record_run(ro->out, *mcap, run_recorder_options(*ro));
    }
  });
}

}  // namespace smart::tools
