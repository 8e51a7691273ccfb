#include "smart/tools/cli_common.hpp"

#include <signal.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <stdexcept>

#include "smart/config/yaml_checks.hpp"

namespace smart::tools {

std::atomic<bool> g_stop_requested{false};

namespace {
void on_stop_signal(int) { g_stop_requested.store(true); }
}  // namespace

void add_dds_options(CLI::App* cmd, DdsOptions& o) {
  cmd->add_option("--domain", o.domain, "DDS domain id (0-230)")
      ->envname("SMART_DOMAIN")
      ->check(CLI::Range(0, 230))
      ->capture_default_str();
  cmd->add_option("--qos", o.qos, "QoS profile: lan, wifi, lossy-wifi or a YAML file")
      ->envname("SMART_QOS")
      ->capture_default_str();
  cmd->add_option("--network", o.network,
                  "loopback (this host only, no multicast) or network (Cyclone's default "
                  "interface with multicast discovery, for multi-host runs)")
      ->check(CLI::IsMember({"loopback", "network"}))
      ->capture_default_str();
}

dds::DomainConfig domain_config(const DdsOptions& o, const dds::QosProfile& profile) {
  return profile.domain_config(o.network == "network" ? dds::DomainConfig::network()
                                                      : dds::DomainConfig::loopback());
}

std::string find_config_file(const std::string& kind, const std::string& name) {
  if (name.find('/') != std::string::npos || name.ends_with(".yaml")) return name;
  std::string looked;
  for (const auto& dir : dds::config_search_path()) {
    const auto file = dir / kind / (name + ".yaml");
    if (std::filesystem::exists(file)) return file.string();
    looked += (looked.empty() ? "" : ", ") + file.string();
  }
  throw config::ConfigError(kind + " '" + name + "' not found (looked for " + looked +
                            "); pass a path to a YAML file");
}

monitor::InstanceOptions instance_options(const std::string& map, const std::string& scen,
                                          const std::string& plan, std::size_t agents,
                                          const std::string& format, const std::string& axis,
                                          const std::string& heading) {
  monitor::InstanceOptions io;
  io.map = map;
  io.scen = scen;
  io.plan = plan;
  io.agents = agents;
  io.read.format = monitor::parse_plan_format(format);
  if (!axis.empty()) io.read.axis = monitor::parse_axis_order(axis);
  io.initial_heading = grid::parse_heading(heading);
  return io;
}

void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

void init_logging(const std::string& level) {
  auto logger = spdlog::stderr_color_mt("smart");
  spdlog::set_default_logger(logger);
  const auto lvl = spdlog::level::from_str(level);
  if (lvl == spdlog::level::off && level != "off") {
    throw std::invalid_argument("unknown log level '" + level +
                                "'; use trace, debug, info, warn, error, critical or off");
  }
  spdlog::set_level(lvl);
}

}  // namespace smart::tools
