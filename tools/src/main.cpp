// `smart`: the one SMART-DDS executable; every job is a subcommand (`smart --help`).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "smart/grid/problem.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"SMART-DDS: execute MAPF plans on simulated and physical robot fleets over DDS"};
  app.require_subcommand(1);
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical, off")
      ->envname("SMART_LOG_LEVEL")
      ->capture_default_str();
  int exit_code = 0;
  smart::tools::register_dds_commands(app, exit_code);
  smart::tools::register_demo_command(app, exit_code);
  smart::tools::register_check_plan_command(app, exit_code);
  smart::tools::register_run_commands(app, exit_code);
  smart::tools::register_bench_command(app, exit_code);
  smart::tools::register_generate_commands(app, exit_code);
  smart::tools::register_agent_command(app, exit_code);
  app.parse_complete_callback([&] { smart::tools::init_logging(log_level); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const smart::grid::InputError& e) {
    std::cerr << "smart: " << e.what() << "\n" << e.problems().size() << " problem(s) found\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "smart: error: " << e.what() << "\n";
    return 2;
  }
  return exit_code;
}
