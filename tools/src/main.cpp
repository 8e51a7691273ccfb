// `smart`: the one SMART-DDS executable; every job is a subcommand (`smart --help`). Errors of
// every subcommand end here, in one printer that names the problem and how to fix it, and map
// to the exit codes of the README (cli_common.hpp, ExitCode).
#include <CLI/CLI.hpp>
#include <exception>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "smart/config/yaml_checks.hpp"
#include "smart/dds/error.hpp"
#include "smart/grid/problem.hpp"
#include "smart/hw/i2c_bus.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace {

using smart::tools::ExitCode;

// Prints the error in flight and returns its exit code.
int report(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const smart::grid::InputError& e) {
    std::cerr << "smart: " << e.what() << "\n" << e.problems().size() << " problem(s) found\n";
    return ExitCode::kExitBadInput;
  } catch (const smart::config::ConfigError& e) {
    std::cerr << "smart: configuration error: " << e.what() << "\n";
    return ExitCode::kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "smart: " << e.what() << "\n";
    return ExitCode::kExitBadInput;
  } catch (const smart::dds::Error& e) {
    std::cerr << "smart: DDS error: " << e.what()
              << "\n(check --domain, --network and --security, and that no firewall or "
                 "sandbox blocks UDP on this host)\n";
    return ExitCode::kExitSystem;
  } catch (const smart::hw::I2cError& e) {
    std::cerr << "smart: I2C error: " << e.what() << "\n";
    return ExitCode::kExitSystem;
  } catch (const std::exception& e) {
    std::cerr << "smart: error: " << e.what() << "\n";
    return ExitCode::kExitSystem;
  } catch (...) {
    std::cerr << "smart: error: an exception of unknown type\n";
    return ExitCode::kExitSystem;
  }
}

// Every subcommand registered, the command line parsed and the chosen one run.
int run(int argc, char** argv) {
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
  smart::tools::register_security_command(app, exit_code);
  smart::tools::register_serve_command(app, exit_code);
  smart::tools::register_experiment_command(app, exit_code);
  smart::tools::register_calibrate_command(app, exit_code);
  smart::tools::register_doctor_command(app, exit_code);
  app.parse_complete_callback([&] { smart::tools::init_logging(log_level); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with code 0; every other parse error is bad input.
    return app.exit(e) == 0 ? ExitCode::kExitSuccess : ExitCode::kExitBadInput;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (...) {
    return report(std::current_exception());
  }
}
