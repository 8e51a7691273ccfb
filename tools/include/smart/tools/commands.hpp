// Contract: each register_* function adds its subcommands to the `smart` CLI; a subcommand's
// callback stores its process exit code in `exit_code` (0 = success).
#pragma once

#include <CLI/CLI.hpp>

#include "smart/monitor/grid.hpp"
#include "smart/monitor/scen_reader.hpp"

namespace smart::tools {

void register_dds_commands(CLI::App& app, int& exit_code);
// Throws monitor::InputError when the scenario does not fit the map.
void throw_if_any_scen(const monitor::Scenario& scen, const monitor::Grid& grid);
void register_demo_command(CLI::App& app, int& exit_code);
void register_check_plan_command(CLI::App& app, int& exit_code);
void register_run_commands(CLI::App& app, int& exit_code);
void register_bench_command(CLI::App& app, int& exit_code);

}  // namespace smart::tools
