// Contract: each register_* function adds its subcommands to the `smart` CLI; a subcommand's
// callback stores its process exit code in `exit_code` (0 = success).
#pragma once

#include <CLI/CLI.hpp>

#include "smart/grid/grid.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/plan_lns.hpp"
#include "smart/tools/cli_common.hpp"

namespace smart::tools {

void register_dds_commands(CLI::App& app, int& exit_code);
void register_demo_command(CLI::App& app, int& exit_code);
void register_check_plan_command(CLI::App& app, int& exit_code);
void register_run_commands(CLI::App& app, int& exit_code);
void register_bench_command(CLI::App& app, int& exit_code);
void register_generate_commands(CLI::App& app, int& exit_code);
void register_agent_command(CLI::App& app, int& exit_code);
void register_security_command(CLI::App& app, int& exit_code);
void register_serve_command(CLI::App& app, int& exit_code);
void register_experiment_command(CLI::App& app, int& exit_code);
void register_calibrate_command(CLI::App& app, int& exit_code);
void register_doctor_command(CLI::App& app, int& exit_code);
void register_planner_command(CLI::App& app, int& exit_code);
void register_record_commands(CLI::App& app, int& exit_code);
void register_bridge_command(CLI::App& app, int& exit_code);

// The generation pipeline, also used by `smart demo`. Each prints one JSON line and returns an
// exit code; bad input throws grid::InputError.
struct GenMapOptionsPublic {
  int32_t width = 32, height = 32;
  double obstacles = 0.2;
  int corridor = 2;
  uint64_t seed = 1;
  planning::WarehouseOptions warehouse;
};
enum class MapKind { kWarehouse, kRandom, kEmpty, kMaze };
int generate_map(MapKind kind, const std::string& out, const GenMapOptionsPublic& o);
int generate_scen(const std::string& map, std::size_t agents, uint64_t seed,
                  const std::string& out);
// `smart plan`'s planners: prioritized planning (planner.hpp) or PIBT alone (pibt_plan.hpp).
enum class PlanAlgorithm { kPrioritized, kPibt, kLacam };
// `lns`: then rounds of planning/plan_lns.hpp over the plan (passes 0: the planner's as it is).
int plan_instance(const std::string& map, const std::string& scen, std::size_t agents,
                  uint64_t seed, double time_limit_s, const std::string& out,
                  PlanAlgorithm algorithm = PlanAlgorithm::kPrioritized,
                  planning::PlanLnsOptions lns = {.passes = 0});

}  // namespace smart::tools
