// Contract: a QosProfile names the QoS of every SMART-DDS topic plus the Cyclone transport
// settings of a link type. Profiles are YAML files (config/qos/<name>.yaml; kShippedQosProfiles).
// A real network's profile (lan, wifi) sets timers only; a modelled link's (sim-*) adds a link
// model on the sim clock; transport loss is for testing the protocol (protocol-loss-test). Parsing
// is strict: an unknown key, a wrong type or an out-of-range value throws ConfigError naming
// file:line:column, the key and the accepted values. Topics a file leaves out keep the defaults of
// default_qos_profile() (docs/architecture.md, "Topics").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "smart/dds/domain.hpp"
#include "smart/dds/qos.hpp"
#include "smart/wire/link.hpp"

namespace smart::dds {

inline constexpr const char* kShippedQosProfiles =
    "lan, wifi (real networks), sim-wifi, sim-lossy-wifi (modelled links) or protocol-loss-test";

// Which QoS of a profile a topic uses; each topic's role is in the table of topics.hpp.
enum class TopicRole { kAction, kProgress, kState, kClock, kStatus, kShard, kPlan };

struct QosProfile {
  std::string name;
  std::string description;
  TransportConfig transport;
  TopicQos action;
  TopicQos progress;
  TopicQos state;
  TopicQos clock;
  TopicQos status;  // SimStatus: the latest status of the sim host
  TopicQos shard;   // ShardExchange between sim shards: every period's, none lost
  TopicQos plan;    // lifelong planning over DDS: the problem, requests, replies (latest kept)
  // `link:` section: delay, jitter and loss of windows and progress (smart/wire/link.hpp),
  // applied by the hosts' AgentNode; none by default.
  wire::LinkModel link;

  const TopicQos& topic(TopicRole role) const;
  // A DomainConfig (loopback by default) carrying this profile's transport settings.
  DomainConfig domain_config(DomainConfig base = DomainConfig::loopback()) const;
};

QosProfile default_qos_profile();

// `source` names the text in error messages (usually the file path).
QosProfile parse_qos_profile(const std::string& yaml_text, const std::string& source);
QosProfile load_qos_profile(const std::filesystem::path& file);

// Directories searched for config files, in order: $SMART_CONFIG_DIR, then the source tree's
// config/ (compiled in, so the build tree runs without installation).
std::vector<std::filesystem::path> config_search_path();

// A config file given by name ("footbot" -> <config dir>/<kind>/footbot.yaml, the first of
// config_search_path() that has it) or by path (anything with '/' or ending in .yaml). Throws
// ConfigError listing where it looked.
std::string find_config_file(const std::string& kind, const std::string& name_or_path);

// `name_or_path`: a profile name ("lan") looked up as qos/<name>.yaml in config_search_path(),
// or a path to a YAML file (anything containing '/' or ending in .yaml/.yml).
QosProfile find_qos_profile(const std::string& name_or_path);

}  // namespace smart::dds
