// Contract: options and helpers shared by the `smart` subcommands: DDS domain/QoS/network
// options, stop signals (SIGINT/SIGTERM set a flag; nothing calls exit()), logging set-up.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <string>

#include "smart/dds/domain.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/monitor/instance.hpp"

namespace smart::tools {

struct DdsOptions {
  int domain = 0;
  std::string qos = "lan";
  std::string network = "loopback";  // loopback | network
};

void add_dds_options(CLI::App* cmd, DdsOptions& options);
// Loads the QoS profile and renders the domain configuration for `options`.
dds::DomainConfig domain_config(const DdsOptions& options, const dds::QosProfile& profile);

// A config file given by name ("footbot" -> <config dir>/<kind>/footbot.yaml) or by path
// (anything with '/' or ending in .yaml). Throws config::ConfigError listing where it looked.
std::string find_config_file(const std::string& kind, const std::string& name_or_path);

// Instance options from command-line words (format, axis may be empty, heading).
monitor::InstanceOptions instance_options(const std::string& map, const std::string& scen,
                                          const std::string& plan, std::size_t agents,
                                          const std::string& format, const std::string& axis,
                                          const std::string& heading);

// Set by SIGINT/SIGTERM once install_stop_handlers() ran.
extern std::atomic<bool> g_stop_requested;
void install_stop_handlers();

// level: trace, debug, info, warn, error, critical, off. Logs go to stderr.
void init_logging(const std::string& level);

}  // namespace smart::tools
