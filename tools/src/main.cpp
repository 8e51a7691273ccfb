// `smart`: the one SMART-DDS executable; every job is a subcommand (`smart --help`). Errors of
// every subcommand end here, in one printer that names the problem and how to fix it, and map
// to the exit codes of the README (cli_common.hpp, ExitCode).
#include <dds/version.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

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

// Edit distance (Levenshtein) of two short words, for "did you mean".
std::size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The first word that is not an option (or --log-level's value) must name a command: otherwise
// a message naming the word and the nearest command (CLI11 said only "A subcommand is required").
std::optional<std::string> unknown_command(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "--log-level") {
      ++i;
      continue;
    }
    if (word.empty() || word[0] == '-') continue;
    std::string nearest;
    std::size_t best = 3;  // suggest only a near miss
    for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      if (sub->get_name() == word) return std::nullopt;
      if (const auto d = distance(word, sub->get_name()); d < best) {
        best = d;
        nearest = sub->get_name();
      }
    }
    return "'" + word + "' is not a smart command" +
           (nearest.empty() ? std::string() : "; did you mean '" + nearest + "'?") +
           " (`smart --help` lists them)";
  }
  return std::nullopt;
}

// Every subcommand registered, the command line parsed and the chosen one run.
int run(int argc, char** argv) {
  CLI::App app{"SMART-DDS: execute MAPF plans on simulated and physical robot fleets over DDS"};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", std::string("smart ") + SMART_VERSION + " (Cyclone DDS " + DDS_VERSION + ")");
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical, off")
      ->envname("SMART_LOG_LEVEL")
      ->capture_default_str();
  int exit_code = 0;
  smart::tools::register_dds_commands(app, exit_code);
#ifndef SMART_AGENT_ONLY  // an agent-only build (a robot's package): no sim, monitor or server
  smart::tools::register_demo_command(app, exit_code);
  smart::tools::register_check_plan_command(app, exit_code);
  smart::tools::register_run_commands(app, exit_code);
  smart::tools::register_bench_command(app, exit_code);
  smart::tools::register_generate_commands(app, exit_code);
  smart::tools::register_serve_command(app, exit_code);
  smart::tools::register_experiment_command(app, exit_code);
  smart::tools::register_planner_command(app, exit_code);
  smart::tools::register_record_commands(app, exit_code);
  smart::tools::register_bridge_command(app, exit_code);
#endif
  smart::tools::register_agent_command(app, exit_code);
  smart::tools::register_security_command(app, exit_code);
  smart::tools::register_calibrate_command(app, exit_code);
  smart::tools::register_doctor_command(app, exit_code);
  app.parse_complete_callback([&] { smart::tools::init_logging(log_level); });
  if (const auto why = unknown_command(app, argc, argv)) {
    std::cerr << "smart: " << *why << "\n";
    return ExitCode::kExitBadInput;
  }
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
