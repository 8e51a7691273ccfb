// Contract: lifelong MAPF problems read into the grid vocabulary.
// - League of Robot Runners (LoRR) problems, 2024 and 2026 (Start-Kit v3.1,
//   Input_Output_Format.md; examples in ../shared/benchmarks/lorr-2026/): a problem JSON naming
//   `mapFile`, `agentFile`, `taskFile` (relative to the JSON's folder), `teamSize`,
//   `numTasksReveal`, and for 2026 `agentCounter` (ticks per action), `agentSize` (footprint side
//   in cells) and `delayConfig`; an agents file ("# version" comment, a count, one linear cell id
//   `row * width + col` a line; the first teamSize are used) and a tasks file (a count, then one
//   task a line: comma-separated errand cell ids, visited in order).
// - LSMART maps (smart-mapf/lifelong-smart maps/*.json): `n_row`, `n_col`, `layout` rows of
//   '.' free, '@'/'T' blocked, 'w' workstation, 'e' endpoint (both free).
// Parsers are pure; load_lorr_problem() is the file edge. Every problem names the file, line,
// robot or task and what to fix, all at once (InputError): ids out of range or on an obstacle,
// counts that disagree with the lines, two robots on one cell, an errand no robot can reach.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/problem.hpp"

namespace smart::grid {

struct Task {
  uint32_t id = 0;            // index in the tasks file (0-based)
  int line = 0;               // source line
  std::vector<Cell> errands;  // visited in this order
};

// LoRR 2026 `delayConfig`: random delay events in ticks (one tick = one LoRR action time).
struct LorrDelayConfig {
  bool present = false;
  uint64_t seed = 0;
  int min_delay_ticks = 0;
  int max_delay_ticks = 0;
  std::string event_model = "bernoulli";  // "bernoulli" (p per tick) or "poisson" (rate per tick)
  double p_delay = 0;
  std::string duration_model = "uniform";  // "uniform" or "gaussian"
  double gauss_mean_ratio = 0.5;           // of [min, max]
  double gauss_std_ratio = 0.2;
};

// The problem JSON's fields (paths as written).
struct LorrSpec {
  std::string map_file, agent_file, task_file;
  std::size_t team_size = 0;
  double num_tasks_reveal = 1;
  int version = 2024;     // 2026 when "version" names it or a 2026 field is present
  int agent_counter = 1;  // ticks per action
  double agent_size = 0;  // footprint side in cells; 0: a point robot (2024)
  LorrDelayConfig delay;
};

struct LorrProblem {
  std::string source;  // the problem JSON
  LorrSpec spec;
  Grid grid;
  MapMarks marks;
  std::vector<Cell> starts;  // teamSize robots
  std::vector<Task> tasks;
};

LorrSpec parse_lorr_spec(std::string_view json, const std::string& source);
// Linear ids `row * width + col` of free cells; `expect` > 0: at least that many lines.
std::vector<Cell> parse_lorr_agents(std::string_view text, const std::string& source,
                                    const Grid& grid, std::size_t expect);
std::vector<Task> parse_lorr_tasks(std::string_view text, const std::string& source,
                                   const Grid& grid);
Grid parse_lsmart_map(std::string_view json, const std::string& source, MapMarks* marks = nullptr);

// Errands in a part of the map no robot's start reaches (4-connected), one Problem per task.
std::vector<Problem> check_tasks_reachable(const Grid& grid, const std::vector<Cell>& starts,
                                           const std::vector<Task>& tasks,
                                           const std::string& source);

// Reads the problem JSON and the files it names (map: LoRR dialect, or an LSMART .json map).
LorrProblem load_lorr_problem(const std::filesystem::path& problem_json);

// A map file of either kind: MovingAI/LoRR text (LoRR symbols accepted) or an LSMART .json.
Grid load_task_map(const std::filesystem::path& path, MapMarks* marks);

std::string to_string_cell_id(const Grid& grid, Cell c);  // "1005 (x=13,y=31)"

}  // namespace smart::grid
