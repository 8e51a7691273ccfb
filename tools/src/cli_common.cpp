#include "smart/tools/cli_common.hpp"

#include <fmt/format.h>
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

const EnumNames<Network> kNetworkNames{{"loopback", Network::kLoopback},
                                       {"network", Network::kNetwork}};

void add_dds_options(CLI::App* cmd, DdsOptions& o) {
  cmd->add_option("--domain", o.domain, "DDS domain id (0-230)")
      ->envname("SMART_DOMAIN")
      ->check(CLI::Range(0, 230))
      ->capture_default_str();
  cmd->add_option("--qos", o.qos, "QoS profile: lan, wifi, lossy-wifi or a YAML file")
      ->envname("SMART_QOS")
      ->capture_default_str();
  add_enum_option(cmd, "--network", o.network, kNetworkNames,
                  "loopback (this host only, no multicast; default) or network (Cyclone's "
                  "default interface with multicast discovery, for multi-host runs)");
}

std::vector<std::string> dds_argv(const DdsOptions& o) {
  return {"--domain",  std::to_string(o.domain),           "--qos", o.qos,
          "--network", enum_name(o.network, kNetworkNames)};
}

dds::DomainConfig domain_config(const DdsOptions& o, const dds::QosProfile& profile) {
  return profile.domain_config(o.network == Network::kNetwork ? dds::DomainConfig::network()
                                                              : dds::DomainConfig::loopback());
}

std::string exact(double value) { return fmt::format("{}", value); }

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
