// Contract: what `smart run` shares between its plan runs (run_commands.cpp) and its lifelong
// runs (lifelong_run.cpp): starting and watching its sim children, reading their reports, the
// run's key, and the RunInfo summary.json describes the run with. Private to tools/src.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "smart/common/child_process.hpp"
#include "smart/grid/lorr.hpp"
#include "smart/monitor/results.hpp"
#include "smart/monitor/sim_reports.hpp"
#include "smart/tools/run_key.hpp"
#include "smart/tools/run_options.hpp"

namespace smart::tools {

// A sim child's report: sim-<shard>.json in the results folder, or a temp file of this process.
std::filesystem::path sim_report_file(const MonitorCliOptions& o, uint32_t shard);
// `smart run`'s sim children (one per shard) with the monitor's own options.
std::vector<common::ChildProcess> spawn_sims(const MonitorCliOptions& o, std::size_t robots,
                                             const std::string& robot);
// What each sim child reported, or why its report cannot be read.
std::vector<monitor::SimWord> sim_words(const MonitorCliOptions& o);
std::optional<uint64_t> sim_handovers(const std::vector<monitor::SimWord>& words);
// A host check for the monitor: names a sim child that exited before the run ended.
std::function<std::string()> watch(std::vector<common::ChildProcess>& sims);
std::string absolute_path(const std::string& p);
monitor::RunInfo run_info(const MonitorCliOptions& o, const std::string& robot_file);
// The run's key: the named file (made when missing), or a private one for its own processes.
std::unique_ptr<PrivateRunKey> own_run_key(SimCliOptions& o);

// A lifelong run's problem (lifelong_problem.cpp), loaded alike by every process of the run.
struct LifelongProblem {
  std::string source;  // the problem JSON, or the map of generated tasks
  grid::Grid grid;
  std::vector<grid::Cell> starts;
  std::vector<grid::Task> tasks;
  std::size_t pool = 0;  // revealed unfinished tasks (LoRR numTasksReveal x teamSize)
  std::optional<grid::LorrSpec> spec;
};
// --lifelong PROBLEM.json (the first --agents robots), or --tasks random on --map for --agents
// robots seeded by --seed; throws std::invalid_argument naming the flags or the file's fault.
LifelongProblem load_lifelong_problem(const SimCliOptions& o);
// A LoRR 2026 delayConfig as the agents' delay events (ticks x 0.1 s), unless --delay-* flags
// set them.
void apply_lorr_delays(const LifelongProblem& p, SimCliOptions& o);
// The world as MovingAI files (`dir`/lifelong.map and .scen) for a sim child; sets w's map, scen
// and agents to them.
void write_world(const LifelongProblem& p, const std::filesystem::path& dir, WorldCliOptions& w);

// `smart run --lifelong PROBLEM.json` or `--tasks random` (lifelong_run.cpp), and with
// `spawn_sim` false `smart monitor --lifelong` (the fleet runs elsewhere: `smart sim --lifelong`
// on other hosts, mixed with `smart agent`s): exit code as the README documents.
int run_lifelong(MonitorCliOptions o, bool spawn_sim);

}  // namespace smart::tools
