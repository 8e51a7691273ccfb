#include "smart/tools/cli_common.hpp"

#include <fmt/format.h>
#include <net/if.h>
#include <signal.h>  // NOLINT(modernize-deprecated-headers): sigaction is POSIX, not <csignal>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "smart/config/yaml_checks.hpp"
#include "smart/security/keystore.hpp"

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
  cmd->add_option("--qos", o.qos,
                  "QoS profile: " + std::string(dds::kShippedQosProfiles) + ", or a YAML file")
      ->envname("SMART_QOS")
      ->capture_default_str();
  cmd->add_option("--run", o.run,
                  "run name: processes of one run share it, concurrent runs on one domain never "
                  "see each other (default: 'default'; `smart run` makes a fresh one)")
      ->envname("SMART_RUN")
      ->check(CLI::Validator(
          [](std::string& s) -> std::string {
            const bool ok = !s.empty() && s.size() <= 64 &&
                            s.find_first_not_of(
                                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                "0123456789._-") == std::string::npos;
            return ok ? "" : "'" + s + "' is not a run name: use 1-64 of A-Z a-z 0-9 . _ -";
          },
          "NAME", "run name"))
      ->each([&o](const std::string&) { o.run_given = true; });
  cmd->add_option("--security", o.security,
                  "DDS Security keystore made by `smart security init` (authentication, access "
                  "control, encryption); every process of the run needs it")
      ->envname("SMART_SECURITY")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--identity", o.identity,
                  "identity in the --security keystore (default: this command's role: monitor, "
                  "sim, agent-<robot id>)");
  cmd->add_option("--run-key", o.run_key,
                  "the run's shared key file: monitor, sim hosts and agents prove their "
                  "membership with it and hear only each other (`smart run` makes a private one "
                  "for the processes it starts, or this file when missing; give it to every "
                  "`smart agent` of a mixed run)")
      ->envname("SMART_RUN_KEY");
  cmd->add_option("--link-delay-ms", o.link_delay_ms,
                  "link model: delay of windows and progress, each way (over the profile's)")
      ->check(finite_in(0, 60000));
  cmd->add_option("--link-jitter-ms", o.link_jitter_ms, "link model: +- uniform jitter")
      ->check(finite_in(0, 60000));
  cmd->add_option("--link-loss-per-mille", o.link_loss_per_mille,
                  "link model: lost samples per 1000, each repaired by a retransmission later")
      ->check(finite_in(0, 1000));
  cmd->add_option("--link-seed", o.link_seed, "link model seed (same seed, same run)");
  add_enum_option(cmd, "--network", o.network, kNetworkNames,
                  "loopback (this host only, no multicast; default) or network (Cyclone's "
                  "default interface with multicast discovery, for multi-host runs)");
  cmd->add_option("--interface", o.interface,
                  "with --network network: the network interface DDS uses (e.g. wlan0 on a "
                  "Jetson beside docker0 and l4tbr0; default: Cyclone's choice)")
      ->envname("SMART_INTERFACE");
}

void check_interface(const DdsOptions& o) {
  if (o.interface.empty()) return;
  if (o.network != Network::kNetwork) {
    throw std::invalid_argument("--interface " + o.interface +
                                " needs --network network (loopback runs use lo only)");
  }
  if (if_nametoindex(o.interface.c_str()) != 0) return;
  std::string names;
  if (auto* list = if_nameindex()) {
    for (auto* i = list; i->if_index != 0; ++i)
      names += (names.empty() ? "" : ", ") + std::string(i->if_name);
    if_freenameindex(list);
  }
  throw std::invalid_argument("--interface " + o.interface +
                              ": no such network interface on this host; it has " + names +
                              " (`ip -br addr` shows them with their addresses)");
}

void group_options(CLI::App* cmd) {
  static const std::vector<std::pair<const char*, std::vector<const char*>>> kGroups{
      {"Problem",
       {"--map", "--scen", "--agents", "--plan", "--axis", "--format", "--initial-heading",
        "--cell-m"}},
      {"Lifelong runs (tasks stream in, windows are replanned)",
       {"--lifelong", "--tasks", "--task-errands", "--duration-s", "--replan-period-s",
        "--heuristic", "--replan-when-left", "--window-steps", "--window-lns-passes", "--lookahead", "--plan-budget-s",
        "--distance-budget-mb"}},
      {"Robots and execution uncertainty",
       {"--robot", "--stall-probability", "--stall-s", "--speed-sigma", "--slip-sigma",
        "--delay-probability", "--delay-rate-hz", "--delay-min-s", "--delay-max-s",
        "--delay-mean-ratio", "--delay-std-ratio", "--seed"}},
      {"Network, DDS and trust",
       {"--domain", "--qos", "--run", "--network", "--interface", "--security", "--identity",
        "--run-key", "--link-delay-ms", "--link-jitter-ms", "--link-loss-per-mille",
        "--link-seed"}},
      {"Run control",
       {"--clock", "--real-time-factor", "--timeout-s", "--window-cap", "--stall-timeout-s",
        "--max-sim-time-s", "--resume", "--resume-switches", "--require-sim-status"}},
      {"Outputs",
       {"--out", "--stats", "--no-progress", "--state-rate-hz", "--ros-plan-hz",
        "--ros-pose-robots"}},
      {"Sim host",
       {"--sim-hosts", "--shard", "--threads", "--system-capacity", "--external-robots"}},
  };
  for (const auto& [group, names] : kGroups) {
    for (const char* name : names) {
      if (auto* opt = cmd->get_option_no_throw(name)) opt->group(group);
    }
  }
}

CLI::Validator finite_in(double lo, double hi) {
  const std::string range = exact(lo) + " to " + exact(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v) || !std::isfinite(v) || v < lo || v > hi) {
          return "'" + s + "' is not a number from " + range;
        }
        return {};
      },
      "FINITE in [" + range + "]", "finite");
}

std::vector<std::string> dds_argv(const DdsOptions& o) {
  std::vector<std::string> argv{"--domain",  std::to_string(o.domain),
                                "--qos",     o.qos,
                                "--network", enum_name(o.network, kNetworkNames),
                                "--run",     o.run};
  if (!o.security.empty()) argv.insert(argv.end(), {"--security", o.security});
  if (!o.run_key.empty()) argv.insert(argv.end(), {"--run-key", o.run_key});
  if (!o.interface.empty()) argv.insert(argv.end(), {"--interface", o.interface});
  for (const auto& [flag, v] : {std::pair{"--link-delay-ms", o.link_delay_ms},
                                {"--link-jitter-ms", o.link_jitter_ms},
                                {"--link-loss-per-mille", o.link_loss_per_mille}}) {
    if (v) argv.insert(argv.end(), {flag, exact(*v)});
  }
  if (o.link_seed) argv.insert(argv.end(), {"--link-seed", std::to_string(*o.link_seed)});
  return argv;
}

dds::QosProfile run_qos_profile(const DdsOptions& o) {
  auto p = dds::find_qos_profile(o.qos);
  for (auto* d : {&p.link.to_host, &p.link.to_monitor}) {
    if (o.link_delay_ms) d->delay_ms = *o.link_delay_ms;
    if (o.link_jitter_ms) d->jitter_ms = *o.link_jitter_ms;
    if (o.link_loss_per_mille) d->loss_per_mille = *o.link_loss_per_mille;
  }
  if (o.link_seed) p.link.seed = *o.link_seed;
  return p;
}

std::string fresh_run_name() {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
  return "run-" + std::to_string(::getpid()) + "-" + std::to_string(ns % 1000000000000LL);
}

dds::DomainConfig domain_config(const DdsOptions& o, const dds::QosProfile& profile,
                                const std::string& role) {
  check_interface(o);
  auto c = profile.domain_config(o.network == Network::kNetwork ? dds::DomainConfig::network()
                                                                : dds::DomainConfig::loopback());
  if (!o.interface.empty()) c.interfaces = {o.interface};
  if (!o.security.empty())
    c.security = security::identity_files(o.security, o.identity.empty() ? role : o.identity);
  return c;
}

std::string exact(double value) { return fmt::format("{}", value); }

std::optional<std::string> link_model_warning(bool lockstep, const DdsOptions& dds,
                                              const dds::QosProfile& profile) {
  if (lockstep && profile.transport.loss_per_mille > 0) {
    return "--qos " + dds.qos + " drops " + std::to_string(profile.transport.loss_per_mille) +
           " per mille of the real packets: a lock-step tick waits for their retransmissions, "
           "so the run is slower in wall time and no different on the sim clock; use --qos "
           "sim-lossy-wifi to model a lossy link at full speed";
  }
  if (lockstep || !profile.link.active()) return std::nullopt;
  const auto& d = profile.link.to_host;
  return "--qos " + dds.qos + " models a link (" + exact(d.delay_ms) + " ms delay, " +
         exact(d.loss_per_mille) +
         " per mille loss each way): in a real-time run it is added to "
         "the real network's own delay and loss; over a real network use --qos lan (or "
         "--link-delay-ms 0 --link-loss-per-mille 0), or --clock lockstep to study the model alone";
}

namespace {
uint32_t parse_id(const std::string& word, const std::string& text) {
  std::size_t used = 0;
  unsigned long v = 0;
  try {
    v = std::stoul(word, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (word.empty() || used != word.size() || !std::isdigit(static_cast<unsigned char>(word[0])) ||
      v > 1000000) {
    throw std::invalid_argument("robot list '" + text + "': '" + word +
                                "' is not a robot index (0..1000000); write e.g. 0-9,12");
  }
  return static_cast<uint32_t>(v);
}
}  // namespace

std::vector<uint32_t> parse_id_ranges(const std::string& text) {
  std::vector<uint32_t> ids;
  std::stringstream parts(text);
  std::string part;
  while (std::getline(parts, part, ',')) {
    const auto dash = part.find('-');
    const uint32_t first = parse_id(part.substr(0, dash), text);
    const uint32_t last = dash == std::string::npos ? first : parse_id(part.substr(dash + 1), text);
    if (last < first || (!ids.empty() && first <= ids.back())) {
      throw std::invalid_argument("robot list '" + text + "': '" + part +
                                  "' is not ascending or repeats a robot");
    }
    for (uint32_t id = first; id <= last; ++id) ids.push_back(id);
  }
  if (ids.empty()) throw std::invalid_argument("robot list is empty; write e.g. 0-9,12");
  return ids;
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
