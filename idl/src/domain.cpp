#include "smart/dds/domain.hpp"

#include <sstream>

#include "smart/dds/error.hpp"

namespace smart::dds {

namespace {
std::string ms(Millis m) { return std::to_string(m.count()) + " ms"; }
}  // namespace

namespace {
// Cyclone's <Security> section (cyclonedds-doc, "DDS Security" configuration); the plugin
// libraries by absolute path, as Debian keeps them out of the default library path.
std::string security_xml(const SecurityFiles& s) {
  const std::string dir = SMART_DDS_SECURITY_PLUGIN_DIR;
  auto file = [](const std::string& path) { return "file:" + path; };
  std::ostringstream x;
  x << "<Security><Authentication><Library path=\"" << dir
    << "/libdds_security_auth.so\" initFunction=\"init_authentication\" "
       "finalizeFunction=\"finalize_authentication\"/>"
    << "<IdentityCA>" << file(s.identity_ca) << "</IdentityCA><IdentityCertificate>"
    << file(s.identity_certificate) << "</IdentityCertificate><PrivateKey>" << file(s.private_key)
    << "</PrivateKey></Authentication>";
  x << "<AccessControl><Library path=\"" << dir
    << "/libdds_security_ac.so\" initFunction=\"init_access_control\" "
       "finalizeFunction=\"finalize_access_control\"/>"
    << "<PermissionsCA>" << file(s.permissions_ca) << "</PermissionsCA><Governance>"
    << file(s.governance) << "</Governance><Permissions>" << file(s.permissions)
    << "</Permissions></AccessControl>";
  x << "<Cryptographic><Library path=\"" << dir
    << "/libdds_security_crypto.so\" initFunction=\"init_crypto\" "
       "finalizeFunction=\"finalize_crypto\"/></Cryptographic></Security>";
  return x.str();
}
}  // namespace

std::string render_cyclone_config(const DomainConfig& c) {
  if (c.transport.loss_per_mille < 0 || c.transport.loss_per_mille > 1000) {
    throw ConfigError("loss_per_mille is " + std::to_string(c.transport.loss_per_mille) +
                      ": it must be between 0 and 1000 (per mille of packets dropped)");
  }
  std::ostringstream x;
  x << "<CycloneDDS><Domain id=\"any\"><General>";
  if (!c.interfaces.empty()) {
    x << "<Interfaces>";
    for (const auto& name : c.interfaces) x << "<NetworkInterface name=\"" << name << "\"/>";
    x << "</Interfaces>";
  }
  x << "<AllowMulticast>" << (c.allow_multicast ? "default" : "false") << "</AllowMulticast>";
  x << "</General><Discovery>";
  x << "<ParticipantIndex>auto</ParticipantIndex>";
  x << "<MaxAutoParticipantIndex>" << c.max_auto_participant_index << "</MaxAutoParticipantIndex>";
  if (!c.peers.empty()) {
    x << "<Peers>";
    for (const auto& p : c.peers) x << "<Peer address=\"" << p << "\"/>";
    x << "</Peers>";
  }
  x << "</Discovery><Internal>";
  // Writes are packed until the writer is flushed (Writer<T>: write() flushes at once,
  // write_batched() + flush() send a fleet's states in a few messages instead of one per robot).
  // Cyclone 0.10 has this only as a domain-wide setting (Internal/WriteBatch, dds_write_flush).
  x << "<WriteBatch>true</WriteBatch>";
  if (c.transport.heartbeat_interval) {
    x << "<HeartbeatInterval>" << ms(*c.transport.heartbeat_interval) << "</HeartbeatInterval>";
  }
  if (c.transport.nack_delay) x << "<NackDelay>" << ms(*c.transport.nack_delay) << "</NackDelay>";
  if (c.transport.auto_resched_nack_delay) {
    x << "<AutoReschedNackDelay>" << ms(*c.transport.auto_resched_nack_delay)
      << "</AutoReschedNackDelay>";
  }
  if (c.transport.loss_per_mille > 0) {
    x << "<Test><XmitLossiness>" << c.transport.loss_per_mille << "</XmitLossiness></Test>";
  }
  x << "</Internal>";
  if (c.security) x << security_xml(*c.security);
  x << "<Tracing><Verbosity>" << c.tracing_verbosity
    << "</Verbosity><OutputFile>stderr</OutputFile></Tracing>";
  x << "</Domain></CycloneDDS>";
  return x.str();
}

Domain::Domain(dds_domainid_t id, const DomainConfig& config) : id_(id), config_(config) {
  const std::string xml = render_cyclone_config(config);
  const dds_entity_t h = dds_create_domain(id, xml.c_str());
  check(h, "creating DDS domain " + std::to_string(id) +
               " (a domain can be created once per process; share the Domain object; with "
               "loopback discovery at most " +
               std::to_string(config.max_auto_participant_index + 1) +
               " processes of one domain fit on a host: more need --network network, or "
               "several robots per agent process)");
  entity_ = std::make_shared<Entity>(h);
}

}  // namespace smart::dds
