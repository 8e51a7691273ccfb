// `smart run --lifelong PROBLEM.json` and `smart run --tasks random --map M --agents N`: a
// lifelong run on the simulated fleet (lifelong/ decides; this is the file and process edge).
// The sim child gets the map and the robots' starts as MovingAI files written beside the results
// (or in a temp folder): the same `smart sim` executes plan runs and lifelong runs.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "run_support.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/agent/uncertainty.hpp"
#include "smart/common/memory.hpp"
#include "smart/grid/lorr.hpp"
#include "smart/lifelong/lifelong_execution.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/task_generator.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/dds_planner.hpp"
#include "smart/tools/machine.hpp"
#include "smart/tools/pipe_planner.hpp"
#include "smart/wire/lockstep.hpp"
#include "temp_dir.hpp"

namespace smart::tools {

namespace {

// events.csv, tasks.csv and throughput.csv, streamed as the run goes (memory stays flat).
class LifelongFiles {
 public:
  explicit LifelongFiles(const std::string& dir) {
    if (dir.empty()) return;
    open(events_, dir, results::kEventsCsv, results::kEventsHeader);
    open(tasks_, dir, results::kTasksCsv, results::kTasksHeader);
    open(throughput_, dir, results::kThroughputCsv, results::kThroughputHeader);
  }
  // The LoRR output, told every event and planning call as they are drained.
  void feed(lifelong::LorrOutput* lorr) { lorr_ = lorr; }
  void drain(lifelong::LifelongExecution& exec) {
    std::string text;
    for (const auto& e : exec.take_events()) {
      if (lorr_ != nullptr) lorr_->on_event(e);
      results::append_row(text, e);
    }
    write(events_, text);
    text.clear();
    for (const auto& t : exec.tasks().take_finished()) {
      latency_sum_s += *t.finished_s - t.revealed_s;
      ++latency_n;
      results::append_row(text, t);
    }
    write(tasks_, text);
    text.clear();
    for (const auto& r : exec.take_throughput()) {
      if (lorr_ != nullptr) lorr_->on_planner_call(r);
      robots_with_task_sum += static_cast<double>(r.robots_with_task);
      ++rows;
      results::append_row(text, r);
    }
    write(throughput_, text);
  }
  void finish(const std::vector<results::TaskRow>& unfinished) {
    std::string text;
    for (const auto& t : unfinished) results::append_row(text, t);
    write(tasks_, text);
  }
  double latency_sum_s = 0, robots_with_task_sum = 0;
  uint64_t latency_n = 0, rows = 0;

 private:
  static void open(std::ofstream& f, const std::string& dir, std::string_view name,
                   std::string_view header) {
    f.open(std::filesystem::path(dir) / name);
    if (!f) throw std::runtime_error(dir + "/" + std::string(name) + ": cannot be written");
    f << header << '\n';
  }
  static void write(std::ofstream& f, const std::string& text) {
    if (f.is_open() && !text.empty()) f << text << std::flush;
  }
  std::ofstream events_, tasks_, throughput_;
  lifelong::LorrOutput* lorr_ = nullptr;
};

// The run as a LoRR output JSON (--lorr-output): its delays as the agents drew them (the same
// pure draws, agent/uncertainty.hpp), its first collision.
void write_lorr_output(const MonitorCliOptions& o, const lifelong::LorrOutput& lorr,
                       const lifelong::LifelongExecution& exec,
                       const monitor::MonitorResult& result) {
  lifelong::LorrRunEnd end;
  end.duration_s = result.sim_time_s;
  end.tasks_finished = exec.stats().tasks_finished;
  const auto u = run_robot_model(o.sim).uncertainty;
  const auto ticks = lifelong::lorr_tick(end.duration_s);
  for (uint32_t r = 0; r < exec.robots(); ++r) {
    end.delay_intervals.push_back(agent::delay_intervals(u, r, ticks));
  }
  if (result.first_collision) {
    end.collisions.push_back(
        {result.first_collision->first, result.first_collision->second, result.first_collision_s});
  } else if (const auto& c = result.first_pose_contact) {
    end.collisions.push_back({c->a, c->b, c->t_s});
  }
  std::ofstream f(o.lifelong.lorr_output);
  f << lorr.json(end).dump() << "\n";
  if (!f) {
    throw std::runtime_error("--lorr-output " + o.lifelong.lorr_output +
                             ": cannot be written; give a path in a folder that exists");
  }
}

nlohmann::json lifelong_json(const LifelongProblem& p, const MonitorCliOptions& o,
                             const lifelong::LifelongExecution& exec, const LifelongFiles& f,
                             double sim_time_s) {
  const auto& s = exec.stats();
  const auto& l = o.lifelong;
  namespace key = results::summary_key;
  nlohmann::json j = {
      {"problem", p.source},
      {"duration_s", l.duration_s},
      {key::kTasksFinished, s.tasks_finished},
      {"tasks_revealed", s.tasks_revealed},
      {key::kThroughputPerMin,
       sim_time_s > 0 ? static_cast<double>(s.tasks_finished) * 60.0 / sim_time_s : 0.0},
      {"mean_latency_s", f.latency_n ? nlohmann::json(f.latency_sum_s / double(f.latency_n))
                                     : nlohmann::json(nullptr)},
      {"mean_robots_with_task", f.rows ? f.robots_with_task_sum / double(f.rows) : 0.0},
      {"task_pool", p.pool},
      {"planner",
       {{"name", l.external() ? "external" : "pibt"},
        {"via", !l.planner_cmd.empty() ? "pipe"
                : l.external()         ? "dds"
                                       : "process"},
        {"command", l.planner_cmd},
        {"fallback",
         l.planner_fallback == LifelongCliOptions::Fallback::kBuiltin ? "builtin" : "stop"},
        {"calls", s.planner_calls},
        {"total_ms", s.planner_total_ms},
        {"mean_ms", s.planner_calls ? s.planner_total_ms / double(s.planner_calls) : 0.0},
        {"max_ms", s.planner_max_ms},
        {"budget_s", l.budget_s},
        {"distance_tables", s.distance_tables},
        {"heuristic", s.heuristic},
        {"heuristic_mb", s.heuristic_mb},
        {"lns_passes", l.lns_passes}}},
      {"replan_period_s", l.period_s},
      {"replan_when_left", l.replan_when_left},
      {"window_steps", l.window_steps},
      {"lookahead", l.lookahead},
      {"windows_refused", s.windows_refused},
      {"appended_actions", s.appended_actions},
      {"type2_edges", s.type2_edges},
  };
  if (p.spec) {
    j["lorr"] = {{"version", p.spec->version},
                 {"team_size", p.spec->team_size},
                 {"num_tasks_reveal", p.spec->num_tasks_reveal},
                 {"agent_counter", p.spec->agent_counter},
                 {"agent_size", p.spec->agent_size},
                 {"delay_config", p.spec->delay.present}};
  }
  return j;
}

void print_lifelong_progress(const monitor::MonitorResult& r, const LifelongCliOptions& l,
                             uint64_t tasks, bool final) {
  std::fprintf(stderr, "\r[lifelong] sim %.1f / %.0f s, %llu tasks done, %zu actions, %.1fx  ",
               r.sim_time_s, l.duration_s, static_cast<unsigned long long>(tasks),
               r.finished_actions, r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0);
  if (final) std::fprintf(stderr, "\n");
}

lifelong::LifelongOptions lifelong_options(const MonitorCliOptions& o, const LifelongProblem& p,
                                           uint64_t seed) {
  const auto& l = o.lifelong;
  lifelong::LifelongOptions lo;
  lo.duration_s = l.duration_s;
  lo.period_s = l.period_s;
  lo.min_unfinished = l.replan_when_left;
  lo.window_steps = l.window_steps;
  lo.lookahead = l.lookahead;
  lo.budget_s = o.sim.clock == sim::ClockMode::kLockstep ? l.budget_s : 0.0;
  lo.task_pool = p.pool;
  lo.distance_budget_mb = l.distance_budget_mb;
  lo.heuristic = l.heuristic;
  lo.lns_passes = l.lns_passes;
  lo.seed = seed;
  lo.initial_heading = o.sim.world.heading;
  if (o.execution != MonitorCliOptions::Execution::kAdg) {
    lo.switching = switch_options(o);  // chains as in plan runs (live_adg_chain.cpp)
  }
  return lo;
}

monitor::MonitorOptions lifelong_monitor_options(const MonitorCliOptions& o, double radius_m) {
  auto mo = monitor_options(o);
  mo.robot_radius_m = radius_m;
  mo.run.robot_radius_m = radius_m;
  mo.run.max_sim_time_s = 0;  // the run ends at --duration-s (complete), not as a failure
  mo.run.require_sim_status = true;
  mo.run.join_timeout_s = wire::kJoinTimeouts * mo.run.timeout_s;
  mo.ros_plan_hz = 0;  // the plan view shows a fixed plan
  // Bounded dispatch: a robot holds at most the cut's look-ahead, so each window can still
  // change where it goes next (the cut keeps whatever was sent).
  mo.run.window_cap = std::min(o.window_cap, std::max<uint32_t>(1, o.lifelong.lookahead));
  return mo;
}

void check_lifelong_flags(const MonitorCliOptions& o) {
  if (!o.plan.empty() || !o.sim.world.scen.empty()) {
    throw std::invalid_argument(
        "a lifelong run plans as it goes: drop --plan and --scen (starts come from the "
        "problem's agents file, or are drawn at random with --tasks random)");
  }
  if (robot_footprint(o.sim.world) != monitor::Footprint::kHalfCells) {
    throw std::invalid_argument(
        "--robot " + o.sim.world.robot + " is wider than a quarter of a --cell-m " +
        std::to_string(o.sim.world.cell_m) +
        " m cell: lifelong runs order robots by half cells (monitor/live_adg.hpp); use a larger "
        "--cell-m");
  }
  if (o.sim.shards > 1) throw std::invalid_argument("--sim-hosts: lifelong runs use one sim host");
  if (o.resume) {
    throw std::invalid_argument(
        "--resume: a lifelong run cannot be taken over (its task state lives in the monitor); "
        "start it again");
  }
  check_real_time_factor(o.sim);
  if (!o.lifelong.planner_cmd.empty() &&
      o.lifelong.planner == LifelongCliOptions::Planner::kExternal) {
    throw std::invalid_argument(
        "--planner external and --planner-cmd: choose one (a planner over DDS, or a command "
        "over a pipe)");
  }
  if (o.lifelong.external() && o.sim.clock == sim::ClockMode::kLockstep &&
      2 * o.lifelong.planner_timeout_s >= o.sim.timeout_s) {
    throw std::invalid_argument(
        "--planner-timeout-s " + std::to_string(o.lifelong.planner_timeout_s) +
        ": in lock-step the sim waits for the monitor at most --timeout-s " +
        std::to_string(o.sim.timeout_s) +
        " s, and a planner call holds it; give a --timeout-s above twice the planner's timeout");
  }
}

// Like own_run_key, but a run whose planner is started by hand (--planner external) needs a
// key file the user names, as a mixed run does.
std::unique_ptr<PrivateRunKey> own_lifelong_run_key(MonitorCliOptions& o) {
  if (o.lifelong.planner == LifelongCliOptions::Planner::kExternal && o.sim.dds.run_key.empty()) {
    spdlog::warn(
        "--planner external without --run-key: any participant that learns the run's partition "
        "can answer its windows; give `smart run` and `smart planner` the same --run-key FILE "
        "(README, \"Running safely\")");
    return nullptr;
  }
  return own_run_key(o.sim);
}

// Where the sim child's world files go: the results folder, or a temp folder (returned: removed
// when the run ends, however it ends; a name per pid was left behind by every run that threw).
std::unique_ptr<TempDir> place_world(MonitorCliOptions& o, const LifelongProblem& p) {
  std::unique_ptr<TempDir> temp;
  if (o.out.empty()) temp = std::make_unique<TempDir>("smart-lifelong");
  write_world(p, temp ? temp->path() : std::filesystem::path(o.out), o.sim.world);
  return temp;
}

std::function<double()> steady_ms() {
  const auto t0 = std::chrono::steady_clock::now();
  return [t0] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
}

// Lock-step: the planner runs inside the monitor's answer, charged --plan-budget-s of sim time.
// Real time: on its own thread, while the monitor keeps dispatching the committed actions.
// --planner-cmd: an external planner over a pipe; --planner external: a `smart planner` of the
// run over DDS (on the monitor's participant); either with the built-in one behind it if asked.
std::unique_ptr<lifelong::WindowPlanner> window_planner(const MonitorCliOptions& o,
                                                        const dds::Participant& participant,
                                                        const dds::QosProfile& profile,
                                                        const grid::Grid& grid, std::size_t robots,
                                                        const lifelong::LifelongOptions& lo) {
  auto builtin = [&] {
    return std::make_unique<lifelong::BuiltinPlanner>(
        grid,
        lifelong::BuiltinPlannerOptions{lo.distance_budget_mb, lo.seed, lo.heuristic, robots,
                                        lo.lns_passes},
        steady_ms());
  };
  std::unique_ptr<lifelong::WindowPlanner> planner;
  const auto& l = o.lifelong;
  if (!l.external()) {
    planner = builtin();
  } else {
    if (l.planner_cmd.empty()) {
      planner =
          std::make_unique<DdsPlanner>(participant, profile, grid, robots, lo.window_steps,
                                       DdsPlannerOptions{l.planner_wait_s, 0.5, l.planner_timeout_s,
                                                         lo.budget_s, &g_stop_requested});
    } else {
      planner = std::make_unique<PipePlanner>(
          grid, robots, lo.window_steps,
          PipePlannerOptions{l.planner_cmd, l.planner_timeout_s, lo.budget_s, 0});
    }
    if (l.planner_fallback == LifelongCliOptions::Fallback::kBuiltin) {
      planner = std::make_unique<lifelong::FallbackPlanner>(std::move(planner), builtin());
    }
  }
  if (o.sim.clock == sim::ClockMode::kLockstep) return planner;
  return std::make_unique<lifelong::ThreadedPlanner>(std::move(planner));
}

// The monitor over DDS until the run ends; the files are streamed meanwhile.
monitor::MonitorResult execute(const MonitorCliOptions& o, const dds::Participant& participant,
                               const dds::QosProfile& profile, const LifelongProblem& problem,
                               lifelong::LifelongExecution& exec, LifelongFiles& files,
                               std::vector<common::ChildProcess>& sims, double radius_m) {
  auto mo = lifelong_monitor_options(o, radius_m);
  mo.host_check = watch(sims);
  std::optional<monitor::StatesCsvWriter> states;
  if (!o.out.empty()) {
    states.emplace(o.out);
    mo.on_state = [&states](const monitor::StateRow& row) { states->add(row); };
  }
  monitor::MonitorNode node(participant, profile, problem.grid, exec, mo);
  const bool tty = o.progress && isatty(STDERR_FILENO);
  auto result = node.run(g_stop_requested, [&](const monitor::MonitorResult& r, std::size_t) {
    files.drain(exec);
    if (tty) print_lifelong_progress(r, o.lifelong, exec.tasks().finished(), false);
  });
  files.drain(exec);
  files.finish(exec.tasks().unfinished());
  if (tty) print_lifelong_progress(result, o.lifelong, exec.tasks().finished(), true);
  return result;
}

// summary.json (and a switching run's switches.csv) written, the summary printed, the verdict
// last; the exit code.
int report_lifelong(const MonitorCliOptions& o, const LifelongProblem& problem,
                    const lifelong::LifelongExecution& exec, const LifelongFiles& files,
                    const monitor::MonitorResult& result, const monitor::RunInfo& info) {
  auto summary = monitor::run_summary_json(result, info);
  summary[results::summary_key::kLifelong] =
      lifelong_json(problem, o, exec, files, result.sim_time_s);
  if (!o.out.empty()) {
    std::ofstream(std::filesystem::path(o.out) / results::kSummaryJson) << summary.dump(2) << "\n";
    if (result.execution != "adg") {
      monitor::write_switches_csv(o.out, problem.grid, nullptr, result.switches);
    }
  }
  std::cout << summary.dump(2) << std::endl;
  if (!result.success()) spdlog::error("run failed: {}", result.error);
  if (!result.success() && exec.stats().planner_max_ms > 500 * o.sim.timeout_s) {
    // A lock-step sim waits for the monitor's answer at most --timeout-s; a planner call holds
    // it (distance tables are a BFS over the map per goal cell, guide paths an A* per robot).
    spdlog::error(
        "a planning call took {:.1f} s, longer than half of --timeout-s {} s that the sim waits "
        "for an answer: give a larger --timeout-s, or fewer robots on this map",
        exec.stats().planner_max_ms / 1000, o.sim.timeout_s);
  }
  return result.success() ? kExitSuccess : kExitRunFailed;
}

}  // namespace

int run_lifelong(MonitorCliOptions o, bool spawn_sim) {
  check_lifelong_flags(o);
  // A run this process starts whole gets a run (partition) of its own unless one was named.
  if (spawn_sim && !o.sim.dds.run_given) o.sim.dds.run = fresh_run_name();
  const uint64_t seed = o.sim.seed.value_or(1);
  const auto problem = load_lifelong_problem(o.sim);
  apply_lorr_delays(problem, o.sim);
  std::unique_ptr<TempDir> temp;
  if (spawn_sim) {
    temp = place_world(o, problem);
  } else if (!o.out.empty()) {
    write_world(problem, o.out, o.sim.world);  // beside the results, for whoever reads them
  }
  const auto robot_file = find_config_file("robots", o.sim.world.robot);
  const auto model = agent::load_robot_model(robot_file);
  std::unique_ptr<PrivateRunKey> private_key;
  if (spawn_sim) private_key = own_lifelong_run_key(o);
  const auto profile = run_qos_profile(o.sim.dds);
  dds::Domain domain(o.sim.dds.domain, domain_config(o.sim.dds, profile, "monitor"));
  dds::Participant participant(domain, o.sim.dds.run);
  prove_member(participant, o.sim.dds, "monitor");
  const auto options = lifelong_options(o, problem, seed);
  // The planner first: an external one is waited for before the sim starts its clock.
  auto planner =
      window_planner(o, participant, profile, problem.grid, problem.starts.size(), options);
  std::vector<common::ChildProcess> sims;
  if (spawn_sim) sims = spawn_sims(o, problem.starts.size(), robot_file);
  lifelong::LifelongExecution exec(problem.grid, problem.starts, problem.tasks, options,
                                   std::move(planner));
  LifelongFiles files(o.out);
  std::optional<lifelong::LorrOutput> lorr;
  if (!o.lifelong.lorr_output.empty()) {
    lorr.emplace(problem.grid, problem.starts, options.initial_heading, problem.tasks);
    exec.observe(&*lorr);
    files.feed(&*lorr);
  }
  spdlog::info("lifelong: {} robots on {} ({}x{}), {} tasks in the source, pool {}, {} s",
               problem.starts.size(), problem.source, problem.grid.width(), problem.grid.height(),
               problem.tasks.size(), problem.pool, o.lifelong.duration_s);
  auto result = execute(o, participant, profile, problem, exec, files, sims, model.radius_m);
  for (auto& sim : sims) {
    if (!sim.wait(std::chrono::seconds(5))) sim.terminate();
  }
  auto info = run_info(o, robot_file);
  info.map = problem.source;
  info.scen.clear();
  info.seed = seed;
  info.monitor_cpu_s = common::cpu_seconds_self();
  if (!sims.empty()) {
    info.sim_cpu_s = common::cpu_seconds_children();
    monitor::apply_sim_reports(result, sim_words(o));
  }
  if (lorr) write_lorr_output(o, *lorr, exec, result);
  return report_lifelong(o, problem, exec, files, result, info);
}

}  // namespace smart::tools
