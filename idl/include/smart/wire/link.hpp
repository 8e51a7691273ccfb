// Contract: the link model (issue 13): what a network between the monitor and a host does to the
// samples a run depends on, modelled in the project's own transport edge (AgentNode) because
// neither DDS nor this kernel (no netem) can delay packets. Per direction (to the host: action
// windows; to the monitor: progress), each sample arrives after
//   delay_ms + U(-jitter_ms, +jitter_ms)   (never below 0)
// plus, for each loss (probability loss_per_mille / 1000, repeated), one retransmit_ms: the
// samples travel on reliable topics, so a lost packet is repaired by a retransmission, later.
// Without `reorder`, a robot's samples keep their order (an arrival is never before the previous
// one's). Every draw is a hash of (seed, direction, robot, sample index): in lock-step, where the
// edge measures time on the sim clock, a run is bit-identical for a given seed; in real time the
// edge uses the wall clock. Robot states (best effort, monitoring only) are not delayed. Pure.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>

namespace smart::wire {

struct LinkDirection {
  double delay_ms = 0;
  double jitter_ms = 0;
  double loss_per_mille = 0;
  double retransmit_ms = 100;  // Cyclone's default heartbeat period: when a loss is repaired
  bool reorder = false;
  bool active() const { return delay_ms > 0 || jitter_ms > 0 || loss_per_mille > 0; }
  bool operator==(const LinkDirection&) const = default;
};

struct LinkModel {
  LinkDirection to_host;     // monitor -> host: action windows
  LinkDirection to_monitor;  // host -> monitor: progress
  uint64_t seed = 0;
  bool active() const { return to_host.active() || to_monitor.active(); }
  bool operator==(const LinkModel&) const = default;
};

// {"to_host": {...}, "to_monitor": {...}, "seed"} for summary.json.
nlohmann::json to_json(const LinkModel& link);

// One direction's arrivals, robot by robot.
class LinkChannel {
 public:
  LinkChannel(LinkDirection d, uint64_t seed, uint32_t direction);
  // When the next sample of `robot`, sent at sent_s, arrives (seconds on the caller's clock).
  double arrival_s(uint32_t robot, double sent_s);
  bool active() const { return d_.active(); }

 private:
  LinkDirection d_;
  uint64_t seed_;
  uint32_t direction_;
  std::map<uint32_t, std::pair<uint64_t, double>> robots_;  // samples sent, last arrival
};

}  // namespace smart::wire
