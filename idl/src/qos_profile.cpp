#include "smart/dds/qos_profile.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdlib>

#include "smart/common/install_paths.hpp"
#include "smart/config/yaml_checks.hpp"
#include "smart/dds/error.hpp"

#ifndef SMART_SOURCE_CONFIG_DIR
#define SMART_SOURCE_CONFIG_DIR "config"
#endif

namespace smart::dds {

namespace {

using config::choice;
using config::fail;
using config::millis;
using config::reject_unknown;
using config::require_map;
using config::scalar;

// A period that must not be 0: a deadline or lease of 0 ms asks DDS to react all the time (the
// monitor spun at 100 % CPU and never exited).
std::chrono::milliseconds positive_millis(const std::string& source, const YAML::Node& v,
                                          const std::string& key) {
  const auto ms = millis(source, v, key);
  if (ms.count() == 0) fail(source, v, "'" + key + "' must be at least 1 ms (or left out)");
  return ms;
}

void parse_topic(const std::string& source, const YAML::Node& node, const std::string& path,
                 TopicQos& q) {
  require_map(source, node, path);
  reject_unknown(source, node, path,
                 {"reliability", "max_blocking_ms", "history", "depth", "durability", "deadline_ms",
                  "lifespan_ms", "liveliness", "liveliness_lease_ms", "autodispose"});
  for (const auto& kv : node) {
    const auto key = kv.first.as<std::string>();
    const auto& v = kv.second;
    const auto full = path + "." + key;
    if (key == "reliability") {
      q.reliability = choice<Reliability>(
          source, v, full,
          {{"reliable", Reliability::kReliable}, {"best_effort", Reliability::kBestEffort}});
    } else if (key == "max_blocking_ms") {
      q.max_blocking = millis(source, v, full);
    } else if (key == "history") {
      q.history = choice<HistoryKind>(
          source, v, full,
          {{"keep_last", HistoryKind::kKeepLast}, {"keep_all", HistoryKind::kKeepAll}});
    } else if (key == "depth") {
      q.depth = scalar<int32_t>(source, v, full, "a whole number >= 1");
      if (q.depth < 1 || q.depth > 10000) {
        fail(source, v, "'" + full + "' must be >= 1 and <= 10000 (samples kept per robot)");
      }
    } else if (key == "durability") {
      q.durability = choice<Durability>(
          source, v, full,
          {{"volatile", Durability::kVolatile}, {"transient_local", Durability::kTransientLocal}});
    } else if (key == "deadline_ms") {
      q.deadline = positive_millis(source, v, full);
    } else if (key == "lifespan_ms") {
      q.lifespan = millis(source, v, full);
    } else if (key == "liveliness") {
      q.liveliness =
          choice<LivelinessKind>(source, v, full,
                                 {{"automatic", LivelinessKind::kAutomatic},
                                  {"manual_by_participant", LivelinessKind::kManualByParticipant},
                                  {"manual_by_topic", LivelinessKind::kManualByTopic}});
    } else if (key == "liveliness_lease_ms") {
      q.liveliness_lease = positive_millis(source, v, full);
    } else if (key == "autodispose") {
      q.autodispose = scalar<bool>(source, v, full, "true or false");
    }
  }
}

void parse_transport(const std::string& source, const YAML::Node& node, TransportConfig& t) {
  require_map(source, node, "transport");
  reject_unknown(
      source, node, "transport",
      {"heartbeat_interval_ms", "nack_delay_ms", "auto_resched_nack_delay_ms", "loss_per_mille"});
  for (const auto& kv : node) {
    const auto key = kv.first.as<std::string>();
    const auto full = "transport." + key;
    if (key == "heartbeat_interval_ms") {
      t.heartbeat_interval = positive_millis(source, kv.second, full);
    }
    if (key == "nack_delay_ms") t.nack_delay = millis(source, kv.second, full);
    if (key == "auto_resched_nack_delay_ms") {
      t.auto_resched_nack_delay = millis(source, kv.second, full);
    }
    if (key == "loss_per_mille") {
      t.loss_per_mille = scalar<int>(source, kv.second, full, "a whole number from 0 to 1000");
      if (t.loss_per_mille < 0 || t.loss_per_mille > 1000) {
        fail(source, kv.second,
             "'" + full + "' must be from 0 to 1000 (per mille of sent packets dropped)");
      }
    }
  }
}

void parse_link_direction(const std::string& source, const YAML::Node& node,
                          const std::string& path, wire::LinkDirection& d) {
  const auto number = [&](const char* key, double hi, double& v) {
    if (!node[key]) return;
    v = scalar<double>(source, node[key], path + "." + key, "a number");
    if (!(v >= 0 && v <= hi)) {
      fail(source, node[key], "'" + path + "." + key + "' must be from 0 to " + std::to_string(hi));
    }
  };
  number("delay_ms", 60000, d.delay_ms);
  number("jitter_ms", 60000, d.jitter_ms);
  number("loss_per_mille", 1000, d.loss_per_mille);
  number("retransmit_ms", 60000, d.retransmit_ms);
  if (node["reorder"])
    d.reorder = scalar<bool>(source, node["reorder"], path + ".reorder", "true or false");
}

// link: {seed, delay_ms, jitter_ms, loss_per_mille, retransmit_ms, reorder (both directions),
// to_host: {...}, to_monitor: {...} (either direction's own, over the shared ones)}.
void parse_link(const std::string& source, const YAML::Node& node, wire::LinkModel& l) {
  require_map(source, node, "link");
  reject_unknown(source, node, "link",
                 {"seed", "delay_ms", "jitter_ms", "loss_per_mille", "retransmit_ms", "reorder",
                  "to_host", "to_monitor"});
  if (node["seed"]) l.seed = scalar<uint64_t>(source, node["seed"], "link.seed", "a whole number");
  parse_link_direction(source, node, "link", l.to_host);
  l.to_monitor = l.to_host;
  for (const auto& [key, d] : {std::pair{"to_host", &l.to_host}, {"to_monitor", &l.to_monitor}}) {
    if (!node[key]) continue;
    require_map(source, node[key], std::string("link.") + key);
    reject_unknown(source, node[key], std::string("link.") + key,
                   {"delay_ms", "jitter_ms", "loss_per_mille", "retransmit_ms", "reorder"});
    parse_link_direction(source, node[key], std::string("link.") + key, *d);
  }
}

}  // namespace

const TopicQos& QosProfile::topic(TopicRole role) const {
  switch (role) {
    case TopicRole::kAction:
      return action;
    case TopicRole::kProgress:
      return progress;
    case TopicRole::kState:
      return state;
    case TopicRole::kClock:
      return clock;
    case TopicRole::kStatus:
      return status;
    case TopicRole::kShard:
      return shard;
    case TopicRole::kPlan:
      return plan;
  }
  return action;
}

DomainConfig QosProfile::domain_config(DomainConfig base) const {
  base.transport = transport;
  return base;
}

QosProfile default_qos_profile() {
  QosProfile p;
  p.name = "default";
  p.description = "docs/architecture.md defaults, Cyclone's transport timers";
  // Action windows and progress are state: keep-last 1 per robot, late joiners get the latest.
  p.action.reliability = Reliability::kReliable;
  p.action.durability = Durability::kTransientLocal;
  p.action.depth = 1;
  p.progress = p.action;
  p.progress.autodispose = false;  // a restarted agent must not erase its finished progress
  p.state.reliability = Reliability::kBestEffort;
  p.state.durability = Durability::kVolatile;
  p.state.depth = 1;
  p.clock.reliability = Reliability::kReliable;
  p.clock.durability = Durability::kVolatile;
  p.clock.depth = 1;
  // SimStatus is state too (latest counts), and a monitor that starts late needs it.
  p.status.reliability = Reliability::kReliable;
  p.status.durability = Durability::kTransientLocal;
  p.status.depth = 1;
  p.status.autodispose = false;
  // Sim shards wait for each other's exchange of every period: reliable, and a shard that is
  // discovered late still gets the last few (a shard is at most one period ahead of another).
  p.shard.reliability = Reliability::kReliable;
  p.shard.durability = Durability::kTransientLocal;
  p.shard.depth = 4;
  p.shard.max_blocking = std::chrono::milliseconds(1000);
  // Planning over DDS: the latest problem, request and reply, none lost, and kept for a planner
  // or monitor discovered late; a 10 000-robot reply is ~1 MB, so a writer may block a while.
  p.plan.reliability = Reliability::kReliable;
  p.plan.durability = Durability::kTransientLocal;
  p.plan.depth = 1;
  p.plan.max_blocking = std::chrono::milliseconds(2000);
  return p;
}

QosProfile parse_qos_profile(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = config::load(yaml_text, source);
  if (!root.IsMap()) {
    throw ConfigError(source +
                      ": a QoS profile must be a YAML mapping with keys name, description, "
                      "transport, topics");
  }
  QosProfile p = default_qos_profile();
  reject_unknown(source, root, "(top level)",
                 {"name", "description", "transport", "topics", "link"});
  if (!root["name"]) {
    throw ConfigError(source + ": missing key 'name'; add e.g. 'name: lan' at the top");
  }
  p.name = scalar<std::string>(source, root["name"], "name", "a profile name");
  if (root["description"]) {
    p.description = scalar<std::string>(source, root["description"], "description", "text");
  }
  if (root["transport"]) parse_transport(source, root["transport"], p.transport);
  if (root["link"]) parse_link(source, root["link"], p.link);
  if (root["topics"]) {
    const auto topics = root["topics"];
    require_map(source, topics, "topics");
    reject_unknown(source, topics, "topics",
                   {"action", "progress", "state", "clock", "status", "shard", "plan"});
    if (topics["action"]) parse_topic(source, topics["action"], "topics.action", p.action);
    if (topics["progress"]) {
      parse_topic(source, topics["progress"], "topics.progress", p.progress);
    }
    if (topics["state"]) parse_topic(source, topics["state"], "topics.state", p.state);
    if (topics["clock"]) parse_topic(source, topics["clock"], "topics.clock", p.clock);
    if (topics["status"]) parse_topic(source, topics["status"], "topics.status", p.status);
    if (topics["shard"]) parse_topic(source, topics["shard"], "topics.shard", p.shard);
    if (topics["plan"]) parse_topic(source, topics["plan"], "topics.plan", p.plan);
  }
  return p;
}

QosProfile load_qos_profile(const std::filesystem::path& file) {
  return parse_qos_profile(config::read_file(file.string(), "QoS profile"), file.string());
}

std::vector<std::filesystem::path> config_search_path() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("SMART_CONFIG_DIR"); env != nullptr && *env != '\0') {
    dirs.emplace_back(env);
  }
  // Installed (cmake --install, the .deb packages) before the source tree of a build.
  if (const auto share = common::installed_share_dir()) dirs.push_back(*share / "config");
  dirs.emplace_back(SMART_SOURCE_CONFIG_DIR);
  return dirs;
}

std::string find_config_file(const std::string& kind, const std::string& name) {
  if (name.find('/') != std::string::npos || name.ends_with(".yaml")) return name;
  std::string looked;
  for (const auto& dir : config_search_path()) {
    const auto file = dir / kind / (name + ".yaml");
    if (std::filesystem::exists(file)) return file.string();
    looked += (looked.empty() ? "" : ", ") + file.string();
  }
  throw ConfigError(kind + " '" + name + "' not found (looked for " + looked +
                    "); pass a path to a YAML file");
}

QosProfile find_qos_profile(const std::string& name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       name_or_path.ends_with(".yaml") || name_or_path.ends_with(".yml");
  if (is_path) return load_qos_profile(name_or_path);
  if (name_or_path == "lossy-wifi") {
    throw ConfigError(
        "QoS profile 'lossy-wifi' was split (issue 26): use sim-lossy-wifi to model a lossy link "
        "on the sim clock, or protocol-loss-test to drop real packets and test the protocol");
  }
  std::string looked;
  for (const auto& dir : config_search_path()) {
    const auto file = dir / "qos" / (name_or_path + ".yaml");
    if (std::filesystem::exists(file)) return load_qos_profile(file);
    looked += (looked.empty() ? "" : ", ") + file.string();
  }
  throw ConfigError("QoS profile '" + name_or_path + "' not found (looked for " + looked +
                    "); use " + std::string(kShippedQosProfiles) +
                    ", or pass a path to a YAML file");
}

}  // namespace smart::dds
