// Contract: `smart experiment`'s pure core: a spec (YAML) read into a grid of runs, each run's
// folder name and `smart run` arguments, and the tidy results table (a row per run with every
// parameter and every summary.json field). No I/O, no processes: the command
// (experiment_command.cpp) resolves files, runs the cells and writes what this core makes.
//
// Spec (every list is one axis of the grid; the cells are their product):
//   name: warehouse-scaling           # 1-64 of A-Z a-z 0-9 . _ -
//   maps: [a.map]                     # one map for every scen, or one map per scen (paired)
//   scens: [a-random-1.scen]
//   agents: [10, 100]                 # first N robots
//   plan: {file: paths.txt, axis: rowcol}   # or {planner: builtin} (algorithm: pp, pibt or lacam;
//                                     # lns_passes: N, `smart plan --lns-passes`;
//                                     # lns_neighbourhood: N, lns_expansions: N, as
//                                     # `--lns-neighbourhood`, `--lns-expansions`), or
//         {command: "lns2 -m {map} -a {scen} -k {agents} -o {plan}", axis: xy}
//   plans: [{name: pp, planner: builtin}, {name: lns2, command: "...", axis: xy}]
//                                     # instead of plan: a planner axis (names 1-64 plain)
//   robots: [footbot, footbot-smart]  # default [footbot]
//   qos: [lan, sim-lossy-wifi]            # default [lan]
//   clock: lockstep                   # or realtime
//   uncertainty: [{}, {stall_probability: 0.05, stall_s: 2}]   # agent/uncertainty.hpp keys
//   executions: [adg, switchable]     # `smart run --execution`; default [adg] (issue 29)
//   switch_commit_actions: [2, 6]     # `--switch-commit-actions` of the switching executions
//   switch_chain_locations: [1, 8]    # `--switch-chain-locations` of theirs (plan runs)
//   switch_margin_s: [1, 3, 10]       # `--switch-margin-s` of switchable-opt and -lookahead
//   switch_horizon_actions: [12, 24]  # `--switch-horizon-actions` of the same two
//   switch_lookahead_actions: [24, 48]  # `--switch-lookahead-actions` of switchable-lookahead
//   switch_window_pairs: [0, 3]       # `--switch-window-pairs` of switchable-lookahead
//                                     # (each an axis for the executions that read it; the
//                                     # others, and adg cells, run once); default: its default
//   repeats: 3                        # repeat r of every cell, seed r; default 1
//   state_rate_hz: 0                  # `smart run --state-rate-hz` of every run (0: states.csv
//                                     # holds each robot's final state only; a 1000-robot,
//                                     # 300 s run's is 45 MB at the default); default: its default
// A lifelong experiment (issue 28: tasks stream in; throughput is the measure) has a lifelong:
// section instead of maps, scens and plan(s), and a planner axis of its own:
//   lifelong:
//     map: random-32-32-20.map        # random tasks on this map (`--tasks random`), or
//     problem: maze-example_40.json   # a LoRR problem (`--lifelong`; its team: no agents axis)
//     duration_s: 120                 # sim seconds per run; default 60
//     task_errands: 1                 # errands per random task (optional)
//     replan_period_s: [1, 2]         # an axis; default [1]
//     lookahead: [4, 8]               # `smart run --lookahead` (actions the commit cut keeps
//                                     # per robot), an axis; default: its default
//   planners: [{planner: builtin}, {name: greedy, command: "python3 greedy_planner.py"}]
//                                     # --planner-cmd per command; default [{planner: builtin}];
//                                     # {planner: builtin, window_lns_passes: 1}: PIBT's windows
//                                     # made better (`smart run --window-lns-passes`)
//   uncertainty: [{}, {delay_probability: 0.01, delay_max_s: 2}]   # LoRR-style delays too
// Errors name the spec file, the line and the field, and say what to write instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace smart::experiment {

enum class PlanSource { kFile, kBuiltin, kCommand };

// One value of the planner axis: where the plans come from, and its name in results.csv
// (default: the file's stem, "builtin", or "command" + its index).
struct PlanSpec {
  std::string name;
  PlanSource source = PlanSource::kFile;
  std::string text;  // the file, or the command template
  std::string axis = "xy";
  std::string algorithm = "pp";  // kBuiltin: `smart plan --algorithm` (pp, pibt or lacam)
  // kBuiltin: `smart plan --lns-passes` (lns_passes:), lifelong `smart run --window-lns-passes`
  // (window_lns_passes:); 0: not given
  int lns_passes = 0;
  int lns_neighbourhood = 1;   // kBuiltin, with lns_passes: `smart plan --lns-neighbourhood`
  int64_t lns_expansions = 0;  // the same, `--lns-expansions`; 0: smart plan's default
};

struct LifelongSpec {
  std::string map;      // random tasks on this map, or
  std::string problem;  // a LoRR problem file
  double duration_s = 60;
  std::optional<int> task_errands;
  std::vector<double> replan_period_s{1.0};
  std::vector<uint32_t> lookahead;  // empty: `smart run`'s default
};

struct Spec {
  std::string name;
  std::optional<LifelongSpec> lifelong;  // set: a lifelong experiment (plans: its planners)
  std::vector<std::pair<std::string, std::string>> instances;  // (map, scen) as written
  std::vector<std::size_t> agents;
  std::vector<PlanSpec> plans;  // one (plan:) or several (plans:)
  std::vector<std::string> robots{"footbot"};
  std::vector<std::string> qos{"lan"};
  std::string clock = "lockstep";
  // Execution uncertainty settings, each an object of stall_probability, stall_s, speed_sigma,
  // slip_sigma (default: one empty object, the robot model's own).
  std::vector<nlohmann::json> uncertainty{nlohmann::json::object()};
  std::vector<std::string> executions{"adg"};      // plan experiments: adg, switchable
  std::vector<uint32_t> switch_commit_actions;     // empty: `smart run`'s default
  std::vector<uint32_t> switch_chain_locations;    // plan runs; empty: `smart run`'s default
  std::vector<double> switch_margin_s;             // switchable-opt, -lookahead; empty: default
  std::vector<uint32_t> switch_horizon_actions;    // the same two; empty: default
  std::vector<uint32_t> switch_lookahead_actions;  // switchable-lookahead; empty: default
  std::vector<uint32_t> switch_window_pairs;       // the same; 0: off; empty: default
  std::optional<double> state_rate_hz;             // none: `smart run`'s default
  std::size_t repeats = 1;
};

// Throws std::invalid_argument "<source>:<line>: <field>: what is wrong; what to write".
Spec parse_spec(std::string_view yaml_text, const std::string& source);

struct Cell {
  std::size_t instance = 0;  // index into spec.instances
  std::size_t agents = 0;
  std::size_t plan = 0;  // index into spec.plans
  std::string robot, qos;
  std::size_t uncertainty = 0;  // index into spec.uncertainty
  std::size_t repeat = 0;       // also the uncertainty seed
  std::size_t period = 0;       // lifelong: index into spec.lifelong->replan_period_s
  std::string key;              // folder name, unique within the experiment, stable across runs
  std::string execution = "adg";
  uint32_t commit_actions = 0;            // --switch-commit-actions; 0: not given
  uint32_t chain_locations = 0;           // --switch-chain-locations; 0: not given
  uint32_t lookahead = 0;                 // lifelong: --lookahead; 0: not given
  std::optional<double> margin_s;         // --switch-margin-s; none: not given
  uint32_t horizon_actions = 0;           // --switch-horizon-actions; 0: not given
  uint32_t switch_lookahead_actions = 0;  // --switch-lookahead-actions; 0: not given
  std::optional<uint32_t> window_pairs;   // --switch-window-pairs; none: not given
};

// The grid, in a fixed order (instance, agents, plan, robot, qos, uncertainty, period,
// lookahead, execution, switch_commit_actions, switch_chain_locations, switch_margin_s,
// switch_horizon_actions, switch_lookahead_actions, switch_window_pairs, repeat).
std::vector<Cell> expand(const Spec& spec);

// The `smart run` flags of a cell's uncertainty and seed.
std::vector<std::string> uncertainty_flags(const Spec& spec, const Cell& cell);
// The `smart run` flags of a cell's execution (--execution and the --switch-* flags given).
std::vector<std::string> execution_flags(const Cell& cell);
// The `smart run` flags every run of the spec gets (--state-rate-hz).
std::vector<std::string> output_flags(const Spec& spec);

// One results row: the cell's parameters (plan: the planner's name; lifelong: replan_period_s),
// the wall seconds its
// planner took (planner_runtime_s; absent for a plan file), then every summary.json field,
// nested objects flattened with dots ("adg.type2"), arrays as JSON text.
nlohmann::json result_row(const Spec& spec, const Cell& cell, const nlohmann::json& summary,
                          std::optional<double> planner_runtime_s = std::nullopt);
// Whether a cell's summary.json is a result: it parses as an object and its run was not stopped
// before its end (outcome "stopped": a run ended by a signal writes what it had then). A
// resumed campaign runs such a cell again, and results.csv has no row for it.
bool ran_to_its_end(const nlohmann::json& summary);
// The rows as CSV: the union of their columns, parameters first, then summary fields sorted;
// fields quoted when they hold a comma, a quote or a newline.
std::string results_csv(const std::vector<nlohmann::json>& rows);

}  // namespace smart::experiment
