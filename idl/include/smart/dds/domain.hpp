// Contract: DomainConfig describes how one process joins a DDS domain (network interfaces,
// discovery peers, multicast, reliability timers, simulated packet loss); render_cyclone_config()
// turns it into Cyclone DDS XML. Domain creates that domain in this process with
// dds_create_domain() and keeps it alive while any copy (or any Participant in it) exists.
//
// Loopback by default: this machine kind has a second interface Cyclone would multicast on
// (docs/architecture.md, "Tests and CI"), so the default is interface "lo", no
// multicast and unicast discovery to 127.0.0.1. Set interfaces empty to let Cyclone choose.
#pragma once

#include <dds/dds.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "smart/dds/entity.hpp"
#include "smart/dds/qos.hpp"

namespace smart::dds {

// Cyclone DDS transport tuning. Unset values keep Cyclone's defaults.
struct TransportConfig {
  std::optional<Millis> heartbeat_interval;
  std::optional<Millis> nack_delay;
  std::optional<Millis> auto_resched_nack_delay;
  // Internal/Test/XmitLossiness: per mille of outgoing packets dropped, 0..1000. Models a lossy
  // link in this process's sends (docs/architecture.md, "Lossy links").
  int loss_per_mille = 0;
  bool operator==(const TransportConfig&) const = default;
};

// DDS Security (OMG DDS Security 1.1, builtin plugins: PKI-DH authentication, permissions access
// control, AES-GCM crypto; Debian ships Cyclone's in libddsc0debian): the files of one identity
// as `smart security init` writes them (README, "Running safely on a shared network").
struct SecurityFiles {
  std::string identity_ca;           // PEM: the CA that signed every identity
  std::string identity_certificate;  // PEM: this participant's certificate
  std::string private_key;           // PEM
  std::string permissions_ca;        // PEM: the CA that signed governance and permissions
  std::string governance;            // S/MIME-signed XML (.p7s)
  std::string permissions;           // S/MIME-signed XML (.p7s): this identity's grant
  bool operator==(const SecurityFiles&) const = default;
};

struct DomainConfig {
  std::vector<std::string> interfaces{"lo"};
  std::vector<std::string> peers{"127.0.0.1"};
  bool allow_multicast = false;
  // Loopback discovery sends to the port of every participant index up to this one, and each
  // process on a host takes one index: 119 is Cyclone's largest (indices below 120 keep the
  // unicast ports inside the domain's 250-port block; Cyclone manual, Discovery/
  // ParticipantIndex), room for 100 agent processes with a monitor, sim hosts and viewers. At 60,
  // the 61st process of a domain on one host failed ("Failed to find a free participant index";
  // bench/discovery.sh, docs/performance.md).
  int max_auto_participant_index = 119;
  TransportConfig transport;
  std::string tracing_verbosity = "warning";
  std::optional<SecurityFiles> security;  // none: no DDS Security

  // Everything default: loopback only (tests, single-host runs).
  static DomainConfig loopback() { return DomainConfig{}; }
  // Cyclone picks the interface and uses multicast discovery (multi-host runs on a LAN).
  static DomainConfig network() {
    DomainConfig c;
    c.interfaces.clear();
    c.peers.clear();
    c.allow_multicast = true;
    return c;
  }
};

std::string render_cyclone_config(const DomainConfig& config);

class Domain {
 public:
  // Throws Error when the domain cannot be created, e.g. it already exists in this process.
  Domain(dds_domainid_t id, const DomainConfig& config);
  dds_domainid_t id() const { return id_; }
  const DomainConfig& config() const { return config_; }

 private:
  dds_domainid_t id_;
  DomainConfig config_;
  std::shared_ptr<Entity> entity_;
};

}  // namespace smart::dds
