// Contract: options and helpers shared by the `smart` subcommands: DDS domain/QoS/network
// options (and their argv for child processes), enum options parsed straight into their types,
// stop signals (SIGINT/SIGTERM set a flag; nothing calls exit()), logging set-up, and the exit
// codes every subcommand returns (README, "Exit codes").
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "smart/dds/domain.hpp"
#include "smart/dds/qos_profile.hpp"

namespace smart::tools {

// Process exit codes (README, "Exit codes").
enum ExitCode : int {
  kExitSuccess = 0,
  kExitRunFailed = 1,  // the job ran and failed: a run that did not succeed, an invalid plan
  kExitBadInput = 2,   // flags, files or configuration the user must fix
  kExitSystem = 3,     // DDS, I2C, sockets, files that cannot be written: the machine failed
};

enum class Network { kLoopback, kNetwork };

struct DdsOptions {
  int domain = 0;
  std::string qos = "lan";
  Network network = Network::kLoopback;
};

// A named value of an enum option, as shown in --help and accepted on the command line.
template <class E>
using EnumNames = std::vector<std::pair<std::string, E>>;

template <class E>
const std::string& enum_name(E value, const EnumNames<E>& names) {
  for (const auto& [name, v] : names) {
    if (v == value) return name;
  }
  return names.front().first;
}

// Adds an option parsed straight into `value` (an enum, or std::optional of one); anything
// but the given names is a parse error listing them.
template <class T, class E>
CLI::Option* add_enum_option(CLI::App* cmd, const std::string& flag, T& value,
                             const EnumNames<E>& names, const std::string& help) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : "|") + n.first;
  auto* opt = cmd->add_option(flag, value, help);
  opt->type_name(list);
  opt->transform(CLI::Validator(
      [names, list](std::string& s) -> std::string {
        for (const auto& [name, v] : names) {
          if (name != s) continue;
          s = std::to_string(static_cast<int>(v));
          return {};
        }
        return "'" + s + "' is not one of " + list;
      },
      "", "one of " + list));
  return opt;
}

extern const EnumNames<Network> kNetworkNames;

void add_dds_options(CLI::App* cmd, DdsOptions& options);
// The same options as command-line words, for a child process.
std::vector<std::string> dds_argv(const DdsOptions& options);
// Loads the QoS profile and renders the domain configuration for `options`.
dds::DomainConfig domain_config(const DdsOptions& options, const dds::QosProfile& profile);

// A config file given by name ("footbot" -> <config dir>/<kind>/footbot.yaml) or by path
// (anything with '/' or ending in .yaml). Throws config::ConfigError listing where it looked.
std::string find_config_file(const std::string& kind, const std::string& name_or_path);

// Shortest text that reads back as the same double (child argv, messages).
std::string exact(double value);

// Set by SIGINT/SIGTERM once install_stop_handlers() ran.
extern std::atomic<bool> g_stop_requested;
void install_stop_handlers();

// level: trace, debug, info, warn, error, critical, off. Logs go to stderr.
void init_logging(const std::string& level);

}  // namespace smart::tools
